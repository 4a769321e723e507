import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import type { DocumentLink } from 'vscode-languageserver/node';
import { fileUri, repoRoot, TestClient } from './harness';

describe('language server: links on scenarioFileName values (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;

  before(async function () {
    root = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-links-'));
    fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
    client = await TestClient.start({ root });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('links each value that resolves to the file it names, over exactly the value (so the editor underlines below the text)', async function () {
    const mainPath = path.join(root, 'main.xosc');
    const text = fs.readFileSync(mainPath, 'utf8');
    const uri = await client.openFile(mainPath);
    const links = await client.request<DocumentLink[]>('textDocument/documentLink', { textDocument: { uri } });
    const lines = text.split('\n');
    const shown = links.map((link) => [lines[link.range.start.line].slice(link.range.start.character, link.range.end.character), link.target]);
    assert.deepEqual(shown, [
      ['lane_change.xosc', fileUri(path.join(root, 'lane_change.xosc'))],
      ['braking.mosc', `mosc:${path.join(root, 'braking.mosc')}/main.xosc`],
      ['pedestrian.mosc', fileUri(path.join(root, 'pedestrian', 'main.xosc'))],
    ]);
  });

  it('gives no link where the name does not resolve', async function () {
    const mainPath = path.join(root, 'main.xosc');
    const uri = fileUri(mainPath);
    await client.open(uri, fs.readFileSync(mainPath, 'utf8').replace('scenarioFileName="lane_change.xosc"', 'scenarioFileName="nowhere_at_all.xosc"'));
    const links = await client.request<DocumentLink[]>('textDocument/documentLink', { textDocument: { uri } });
    assert.equal(links.length, 2);
  });
});
