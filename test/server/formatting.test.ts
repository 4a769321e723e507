import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { TextEdit } from 'vscode-languageserver/node';
import { fileUri, TestClient } from './harness';
import { applyEdits } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';

const MESSY =
  '<?xml version="1.0"?>\n<OpenSCENARIO>\n<FileHeader revMajor="1" revMinor="0" date="2026-01-01T00:00:00" description="formatting" author="test"/>\n<Entities>\n\n\n<ScenarioObject name="Ego"/>\n</Entities>\n</OpenSCENARIO>\n';

describe('formatting over JSON-RPC', function () {
  let root: string;
  let client: TestClient;
  const messages: { type: number; message: string }[] = [];

  before(async () => {
    root = temporaryWorkspace({ 'scenario.xosc': MESSY });
    client = await TestClient.start({ root, settings: { format: { maxLineWidth: 60 } } });
    client.connection.onNotification('window/showMessage', (params: { type: number; message: string }) => void messages.push(params));
  });

  after(async () => {
    await client.stop();
  });

  it('announces document and range formatting', () => {
    assert.equal(client.capabilities.documentFormattingProvider, true);
    assert.equal(client.capabilities.documentRangeFormattingProvider, true);
  });

  it('formats a document with the editor options and the configured width, in small edits', async () => {
    const uri = await client.open(fileUri(path.join(root, 'scenario.xosc')), MESSY);
    // The width (60) comes from the settings, read after `initialized`: wait until the server has them.
    await client.diagnosticsOf(uri);
    const edits = await client.request<TextEdit[]>('textDocument/formatting', {
      textDocument: { uri },
      options: { tabSize: 2, insertSpaces: true },
    });
    assert.ok(edits.length > 1, 'expected several small edits, not one replacement');
    for (const edit of edits) assert.match(edit.newText, /^\s*$/);
    const formatted = applyEdits(MESSY, edits);
    assert.equal(
      formatted,
      '<?xml version="1.0"?>\n<OpenSCENARIO>\n  <FileHeader\n    revMajor="1"\n    revMinor="0"\n    date="2026-01-01T00:00:00"\n    description="formatting"\n    author="test"/>\n  <Entities>\n    <ScenarioObject name="Ego"/>\n  </Entities>\n</OpenSCENARIO>\n',
    );
    const tabs = applyEdits(
      MESSY,
      await client.request<TextEdit[]>('textDocument/formatting', { textDocument: { uri }, options: { tabSize: 4, insertSpaces: false } }),
    );
    assert.ok(tabs.includes('\n\t<Entities>\n\t\t<ScenarioObject name="Ego"/>'));
  });

  it('formats only the selected lines', async () => {
    const uri = fileUri(path.join(root, 'scenario.xosc'));
    const line = MESSY.split('\n').indexOf('<ScenarioObject name="Ego"/>');
    const edits = await client.request<TextEdit[]>('textDocument/rangeFormatting', {
      textDocument: { uri },
      range: { start: { line, character: 0 }, end: { line, character: 5 } },
      options: { tabSize: 2, insertSpaces: true },
    });
    const formatted = applyEdits(MESSY, edits);
    assert.ok(formatted.includes('\n    <ScenarioObject name="Ego"/>\n'));
    assert.ok(formatted.includes('\n<Entities>\n'), 'a line outside the selection changed');
    assert.ok(formatted.includes('\n<FileHeader revMajor'), 'a line outside the selection changed');
  });

  it('refuses a malformed document: no edits, and a message naming the line', async () => {
    const broken = '<OpenSCENARIO>\n  <Entities>\n</OpenSCENARIO>\n';
    const uri = await client.open(fileUri(path.join(root, 'broken.xosc')), broken);
    const edits = await client.request<TextEdit[]>('textDocument/formatting', {
      textDocument: { uri },
      options: { tabSize: 2, insertSpaces: true },
    });
    assert.deepEqual(edits, []);
    const message = await client.until(() => messages.find((entry) => /not well-formed/.test(entry.message)), 'a message');
    assert.match(message.message, /line 2/);
  });
});
