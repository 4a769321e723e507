import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import type { DocumentLink } from 'vscode-languageserver/node';
import { fileUri, serveExamples } from './harness';

describe('language server: links on scenarioFileName values (JSON-RPC)', function () {
  const examples = serveExamples();

  it('links each value that resolves to the file it names, over exactly the value (so the editor underlines below the text)', async function () {
    const mainPath = path.join(examples.root(), 'main.xosc');
    const text = fs.readFileSync(mainPath, 'utf8');
    const uri = await examples.client().openFile(mainPath);
    const links = await examples.client().request<DocumentLink[]>('textDocument/documentLink', { textDocument: { uri } });
    const lines = text.split('\n');
    const shown = links.map((link) => [
      lines[link.range.start.line].slice(link.range.start.character, link.range.end.character),
      link.target,
    ]);
    assert.deepEqual(shown, [
      ['lane_change.xosc', fileUri(path.join(examples.root(), 'lane_change.xosc'))],
      ['braking.mosc', `mosc:${path.join(examples.root(), 'braking.mosc')}/main.xosc`],
      ['pedestrian.mosc', fileUri(path.join(examples.root(), 'pedestrian', 'main.xosc'))],
    ]);
  });

  it('gives no link where the name does not resolve', async function () {
    const mainPath = path.join(examples.root(), 'main.xosc');
    const uri = fileUri(mainPath);
    await examples
      .client()
      .open(
        uri,
        fs.readFileSync(mainPath, 'utf8').replace('scenarioFileName="lane_change.xosc"', 'scenarioFileName="nowhere_at_all.xosc"'),
      );
    const links = await examples.client().request<DocumentLink[]>('textDocument/documentLink', { textDocument: { uri } });
    assert.equal(links.length, 2);
  });
});
