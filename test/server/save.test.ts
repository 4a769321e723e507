import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { PackRequest, type WriteResult } from '../../common/src/protocol';
import { fileUri, serveExamples } from './harness';
import { positionAfter } from '../support/cursor';

describe('language server: a saved file is read again from disk (JSON-RPC)', function () {
  const examples = serveExamples();

  it('packs what was saved right before, not the bytes read when indexing', async function () {
    const mainPath = path.join(examples.root(), 'main.xosc');
    const text = fs.readFileSync(mainPath, 'utf8');
    const uri = await examples.client().openFile(mainPath);
    const at = positionAfter(text, 'key="RelativeDistanceCondition.value" value="');
    await examples.client().change(uri, [{ range: { start: at, end: { line: at.line, character: at.character + 2 } }, text: '17.5' }]);
    // The editor saves (the client's Pack does this first), then asks for the package at once.
    fs.writeFileSync(
      mainPath,
      text.replace('key="RelativeDistanceCondition.value" value="12"', 'key="RelativeDistanceCondition.value" value="17.5"'),
    );
    await examples.client().connection.sendNotification('textDocument/didSave', { textDocument: { uri } });
    const output = path.join(examples.root(), 'out.mosc');
    const result = await examples.client().request<WriteResult>(PackRequest.method, { inputs: [fileUri(mainPath)], outputPath: output });
    assert.equal(result.written, output, JSON.stringify(result.problems));
    const packed = await (await JSZip.loadAsync(fs.readFileSync(output))).file('main.xosc')?.async('string');
    assert.ok(packed?.includes('key="RelativeDistanceCondition.value" value="17.5"'), 'the package holds the bytes read before the save');
  });
});
