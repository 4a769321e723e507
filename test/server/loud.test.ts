import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CancellationTokenSource, CodeAction, CompletionItem, Diagnostic, ErrorCodes, LSPErrorCodes, ResponseError, TextEdit } from 'vscode-languageserver/node';
import { StructureRequest } from '../../server/src/protocol';
import { MAIN, SIMPLE } from './fixtures/scenarios';
import { fileUri, markers, positionAfter, temporaryWorkspace, TestClient } from './harness';

const simple = markers(SIMPLE);
const main = markers(MAIN);

/** The simple scenario of the fixtures with its speed listed by a dotted name, as the case study's simple_2.xosc does. */
const DOTTED = simple.text.replace('<AbsoluteTargetSpeed parameterAttributes="value" value="5"/>', '<AbsoluteTargetSpeed parameterAttributes="AbsoluteTargetSpeed.value" value="5"/>');

function rejectsWith(code: number, message: RegExp): (error: unknown) => boolean {
  return (error: unknown) => {
    assert.ok(error instanceof ResponseError, `a JSON-RPC error, got ${String(error)}`);
    assert.equal(error.code, code, error.message);
    assert.match(error.message, message);
    return true;
  };
}

describe('language server: failures are loud (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;
  let mainUri: string;

  before(async function () {
    assert.notEqual(DOTTED, simple.text, 'the fixture lists the speed by a dotted name');
    root = temporaryWorkspace({ 'simple.xosc': DOTTED, 'main.xosc': main.text });
    client = await TestClient.start({ root });
    await client.indexed();
    mainUri = await client.openFile(path.join(root, 'main.xosc'));
    await client.diagnosticsOf(mainUri);
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  describe('a simple scenario listing a dotted name in parameterAttributes (issue 7, item 3)', function () {
    it('still completes the keys the group offers', async function () {
      const uri = fileUri(path.join(root, 'typing.xosc'));
      const typed = markers(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="simple.xosc">
    <ManeuverGroupReference maneuverGroupName="Brake">
      <ParameterReference key="|"`);
      await client.open(uri, typed.text);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, positionAfter(typed.text, 'key="')));
      const labels = items.map((item) => item.label);
      assert.ok(labels.includes('delay') && labels.includes('SimulationTimeCondition.value'), labels.join(', '));
      assert.ok(!labels.some((label) => label.includes('AbsoluteTargetSpeed')), 'no key reaches the dotted name');
      await client.close(uri);
    });

    it('still offers the ScenarioReference snippet', async function () {
      const uri = fileUri(path.join(root, 'typing.xosc'));
      const typed = `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <Sce`;
      await client.open(uri, typed);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, positionAfter(typed, '<Sce')));
      const snippet = items.find((item) => item.label === 'ScenarioReference simple.xosc Brake');
      assert.ok(snippet, items.map((item) => item.label).join(', '));
      assert.match((snippet.textEdit as TextEdit).newText, /<ParameterReference key="delay" value="\$\{\d+:0\}"\/>/);
      await client.close(uri);
    });

    it('still adds the missing keys', async function () {
      const diagnostics = await client.diagnosticsOf(mainUri);
      const diagnostic = diagnostics.find((candidate) => candidate.code === 'unknown-key') as Diagnostic;
      assert.ok(diagnostic, JSON.stringify(diagnostics.map((candidate) => candidate.code)));
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', { textDocument: { uri: mainUri }, range: diagnostic.range, context: { diagnostics: [diagnostic] } });
      assert.ok(actions.some((action) => /missing key/.test(action.title)), actions.map((action) => action.title).join(', '));
    });
  });

  describe('errors of the handlers', function () {
    it('answers an exception as InternalError naming the method, and logs it with its stack', async function () {
      const original = client.workspace.source;
      client.workspace.source = () => Promise.reject(new TypeError('injected failure'));
      try {
        await assert.rejects(
          client.request('textDocument/documentSymbol', { textDocument: { uri: mainUri } }),
          rejectsWith(ErrorCodes.InternalError, /^textDocument\/documentSymbol failed: injected failure$/),
        );
      } finally {
        client.workspace.source = original;
      }
      const logged = await client.expectError(/^textDocument\/documentSymbol failed: TypeError: injected failure/);
      assert.match(logged, /\n\s+at /, 'the stack is logged');
    });

    it('passes a deliberate error through unchanged, logging nothing', async function () {
      await assert.rejects(
        client.request('textDocument/rename', { ...client.at(mainUri, positionAfter(main.text, '<OpenSCENARIO')), newName: 'X' }),
        rejectsWith(LSPErrorCodes.RequestFailed, /^only ManeuverGroup names can be renamed$/),
      );
      assert.deepEqual(client.errors, []);
    });

    it('answers a custom request with bad parameters as InvalidParams, logging nothing', async function () {
      await assert.rejects(client.send(StructureRequest, { uri: 'http://example.com/x' }), rejectsWith(ErrorCodes.InvalidParams, /not a scenario URI/));
      assert.deepEqual(client.errors, []);
    });

    it('answers a cancelled request with RequestCancelled', async function () {
      // The request is held inside the workspace until the client has cancelled it.
      const original = client.workspace.referringFiles;
      let release: () => void = () => undefined;
      const held = new Promise<void>((resolve) => (release = resolve));
      let entered: () => void = () => undefined;
      const reached = new Promise<void>((resolve) => (entered = resolve));
      client.workspace.referringFiles = async function (this: typeof client.workspace) {
        entered();
        await held;
        return original.call(this);
      };
      try {
        const source = new CancellationTokenSource();
        const position = positionAfter(main.text, 'maneuverGroupName="');
        const answer = client.connection.sendRequest('textDocument/references', { ...client.at(mainUri, position), context: { includeDeclaration: true } }, source.token);
        await reached;
        source.cancel();
        // The cancellation travels to the server before the work goes on.
        await new Promise((resolve) => setTimeout(resolve, 100));
        release();
        await assert.rejects(answer, rejectsWith(LSPErrorCodes.RequestCancelled, /textDocument\/references was cancelled/));
      } finally {
        client.workspace.referringFiles = original;
      }
      const locations = await client.request<unknown[]>('textDocument/references', { ...client.at(mainUri, positionAfter(main.text, 'maneuverGroupName="')), context: { includeDeclaration: true } });
      assert.ok(locations.length > 0, 'the same request answers when not cancelled');
      assert.deepEqual(client.errors, []);
    });
  });
});
