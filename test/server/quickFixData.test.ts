import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CodeAction, Diagnostic } from 'vscode-languageserver/node';
import { isDiagnosticData } from '../../server/src/features/fixes';
import { mainWithKeys, SIMPLE } from './fixtures/scenarios';
import { problemCodeOf } from '../support/diagnostics';
import { markers } from '../support/cursor';
import { temporaryWorkspace } from '../support/workspace';
import { TestClient } from './harness';

describe('quick-fix data as a client sends it back', function () {
  it('accepts a known code with the data its code names, or none, and nothing else', function () {
    assert.ok(isDiagnosticData({ code: 'unknown-key', data: { suggestion: 'speed' } }));
    assert.ok(isDiagnosticData({ code: 'unknown-key', data: { relatedReplacement: 'value' } }));
    assert.ok(isDiagnosticData({ code: 'unknown-group', data: { groups: ['A', 'B'] } }));
    assert.ok(
      isDiagnosticData({ code: 'schema-missing-element', data: { missing: ['Actors'], parent: 'ManeuverGroup', insertAt: '120' } }),
    );
    assert.ok(isDiagnosticData({ code: 'no-default' }));
    assert.ok(isDiagnosticData({ code: 'cycle' }));
    for (const junk of [
      undefined,
      null,
      'unknown-key',
      [],
      {},
      { code: 'no-such-code' },
      { code: 42 },
      { code: 'unknown-key', data: { suggestion: 7 } },
      { code: 'unknown-key', data: 'speed' },
      { code: 'unknown-group', data: { groups: 'A\nB' } },
      { code: 'schema-missing-attribute', data: { missing: 'a,b' } },
      { code: 'schema-missing-element', data: { missing: ['Actors'] } },
      { code: 'undeclared-parameter', data: { parameter: ['x'] } },
      { code: 'cycle', data: { suggestion: 'x' } },
    ]) {
      assert.equal(isDiagnosticData(junk), false, JSON.stringify(junk));
    }
  });

  describe('over JSON-RPC', function () {
    let root: string;
    let client: TestClient;
    let mainUri: string;

    before(async function () {
      root = temporaryWorkspace({
        'simple.xosc': markers(SIMPLE).text,
        'main.xosc': mainWithKeys(['<ParameterReference key="AbsoluteTargetSped.value" value="9"/>']),
      });
      client = await TestClient.start({ root });
      await client.indexed();
      mainUri = await client.openFile(path.join(root, 'main.xosc'));
    });

    after(async function () {
      await client?.stop();
      if (root) fs.rmSync(root, { recursive: true, force: true });
    });

    it('offers no fix for a diagnostic whose data is not what the server sent, and fails nothing', async function () {
      const diagnostics = await client.diagnosticsOf(mainUri, (all) => all.some((candidate) => problemCodeOf(candidate) === 'unknown-key'));
      const diagnostic = diagnostics.find((candidate) => problemCodeOf(candidate) === 'unknown-key') as Diagnostic;
      const request = (data: unknown) =>
        client.request<CodeAction[]>('textDocument/codeAction', {
          textDocument: { uri: mainUri },
          range: diagnostic.range,
          context: { diagnostics: [{ ...diagnostic, data }] },
        });
      const own = (await request(diagnostic.data)).filter((action) => action.diagnostics);
      assert.deepEqual(
        own.map((action) => action.title),
        ["Change key to 'AbsoluteTargetSpeed.value'"],
      );
      for (const junk of [
        undefined,
        'x',
        { code: 'unknown-key', data: { suggestion: 1 } },
        { code: 'unknown-key', suggestion: 'AbsoluteTargetSpeed.value' },
      ]) {
        assert.deepEqual(
          (await request(junk)).filter((action) => action.diagnostics),
          [],
          JSON.stringify(junk),
        );
      }
    });
  });
});
