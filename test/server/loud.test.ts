import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CancellationTokenSource, CodeAction, CompletionItem, Diagnostic, ErrorCodes, LSPErrorCodes, ResponseError, TextEdit } from 'vscode-languageserver/node';
import { StructureRequest } from '../../server/src/protocol';
import { MAIN, SIMPLE } from './fixtures/scenarios';
import { fileUri, useServer } from './harness';
import { markers, positionAfter } from '../support/cursor';

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
  const server = useServer({ 'simple.xosc': DOTTED, 'main.xosc': main.text }, 'main.xosc');

  describe('a simple scenario listing a dotted name in parameterAttributes (issue 7, item 3)', function () {
    it('still completes the keys the group offers', async function () {
      const uri = fileUri(path.join(server.root, 'typing.xosc'));
      const typed = markers(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="simple.xosc">
    <ManeuverGroupReference maneuverGroupName="Brake">
      <ParameterReference key="|"`);
      await server.client.open(uri, typed.text);
      const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, positionAfter(typed.text, 'key="')));
      const labels = items.map((item) => item.label);
      // With the dotted name unreachable, the condition's value is the only 'value' left.
      assert.deepEqual([...labels].sort(), ['delay', 'missing', 'value']);
      assert.ok(!labels.some((label) => label.includes('AbsoluteTargetSpeed')), 'no key reaches the dotted name');
      await server.client.close(uri);
    });

    it('still offers the ScenarioReference snippet', async function () {
      const uri = fileUri(path.join(server.root, 'typing.xosc'));
      const typed = `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <Sce`;
      await server.client.open(uri, typed);
      const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, positionAfter(typed, '<Sce')));
      const snippet = items.find((item) => item.label === 'ScenarioReference simple.xosc Brake');
      assert.ok(snippet, items.map((item) => item.label).join(', '));
      assert.match((snippet.textEdit as TextEdit).newText, /<ParameterReference key="delay" value="\$\{\d+:0\}"\/>/);
      await server.client.close(uri);
    });

    it('still adds the missing keys', async function () {
      const diagnostics = await server.client.diagnosticsOf(server.openUri);
      const diagnostic = diagnostics.find((candidate) => candidate.code === 'unknown-key') as Diagnostic;
      assert.ok(diagnostic, JSON.stringify(diagnostics.map((candidate) => candidate.code)));
      const actions = await server.client.request<CodeAction[]>('textDocument/codeAction', { textDocument: { uri: server.openUri }, range: diagnostic.range, context: { diagnostics: [diagnostic] } });
      assert.ok(actions.some((action) => /missing key/.test(action.title)), actions.map((action) => action.title).join(', '));
    });
  });

  describe('errors of the handlers', function () {
    it('answers an exception as InternalError naming the method, and logs it with its stack', async function () {
      const original = server.client.workspace.source;
      server.client.workspace.source = () => Promise.reject(new TypeError('injected failure'));
      try {
        await assert.rejects(
          server.client.request('textDocument/documentSymbol', { textDocument: { uri: server.openUri } }),
          rejectsWith(ErrorCodes.InternalError, /^textDocument\/documentSymbol failed: injected failure$/),
        );
      } finally {
        server.client.workspace.source = original;
      }
      const logged = await server.client.expectError(/^textDocument\/documentSymbol failed: TypeError: injected failure/);
      assert.match(logged, /\n\s+at /, 'the stack is logged');
    });

    it('passes a deliberate error through unchanged, logging nothing', async function () {
      await assert.rejects(
        server.client.request('textDocument/rename', { ...server.client.at(server.openUri, positionAfter(main.text, '<OpenSCENARIO')), newName: 'X' }),
        rejectsWith(LSPErrorCodes.RequestFailed, /^only ManeuverGroup and parameter names can be renamed$/),
      );
      assert.deepEqual(server.client.errors, []);
    });

    it('answers a custom request with bad parameters as InvalidParams, logging nothing', async function () {
      await assert.rejects(server.client.send(StructureRequest, { uri: 'http://example.com/x' }), rejectsWith(ErrorCodes.InvalidParams, /not a scenario URI/));
      assert.deepEqual(server.client.errors, []);
    });

    it('answers a cancelled request with RequestCancelled', async function () {
      // The request is held inside the workspace until the server.client has cancelled it.
      const original = server.client.workspace.referringFiles;
      let release: () => void = () => undefined;
      const held = new Promise<void>((resolve) => (release = resolve));
      let entered: () => void = () => undefined;
      const reached = new Promise<void>((resolve) => (entered = resolve));
      server.client.workspace.referringFiles = async function (this: typeof server.client.workspace) {
        entered();
        await held;
        return original.call(this);
      };
      try {
        const source = new CancellationTokenSource();
        const position = positionAfter(main.text, 'maneuverGroupName="');
        const answer = server.client.connection.sendRequest('textDocument/references', { ...server.client.at(server.openUri, position), context: { includeDeclaration: true } }, source.token);
        await reached;
        source.cancel();
        // The cancellation travels to the server before the work goes on.
        await new Promise((resolve) => setTimeout(resolve, 100));
        release();
        await assert.rejects(answer, rejectsWith(LSPErrorCodes.RequestCancelled, /textDocument\/references was cancelled/));
      } finally {
        server.client.workspace.referringFiles = original;
      }
      const locations = await server.client.request<unknown[]>('textDocument/references', { ...server.client.at(server.openUri, positionAfter(main.text, 'maneuverGroupName="')), context: { includeDeclaration: true } });
      assert.ok(locations.length > 0, 'the same request answers when not cancelled');
      assert.deepEqual(server.client.errors, []);
    });
  });
});
