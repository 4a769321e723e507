import * as assert from 'node:assert/strict';
import { CancellationTokenSource, ErrorCodes, LSPErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { StructureRequest } from '../../common/src/protocol';
import { positionAfter } from '../support/cursor';
import { DOTTED, MAIN } from './fixtures/scenarios';
import { useServer } from './harness';

function rejectsWith(code: number, message: RegExp): (error: unknown) => boolean {
  return (error: unknown) => {
    assert.ok(error instanceof ResponseError, `a JSON-RPC error, got ${String(error)}`);
    assert.equal(error.code, code, error.message);
    assert.match(error.message, message);
    return true;
  };
}
describe('language server: errors of the handlers are loud (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': DOTTED, 'main.xosc': MAIN }, 'main.xosc');

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
      server.client.request('textDocument/rename', {
        ...server.client.at(server.openUri, positionAfter(MAIN, '<OpenSCENARIO')),
        newName: 'X',
      }),
      rejectsWith(LSPErrorCodes.RequestFailed, /^only ManeuverGroup and parameter names can be renamed$/),
    );
    assert.deepEqual(server.client.errors, []);
  });

  it('answers a custom request with bad parameters as InvalidParams, logging nothing', async function () {
    await assert.rejects(
      server.client.send(StructureRequest, { uri: 'http://example.com/x' }),
      rejectsWith(ErrorCodes.InvalidParams, /not a scenario URI/),
    );
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
      const position = positionAfter(MAIN, 'maneuverGroupName="');
      const answer = server.client.connection.sendRequest(
        'textDocument/references',
        { ...server.client.at(server.openUri, position), context: { includeDeclaration: true } },
        source.token,
      );
      await reached;
      source.cancel();
      // The cancellation travels to the server before the work goes on: the answer to a later request shows it was read.
      await server.client.request('textDocument/documentSymbol', { textDocument: { uri: server.openUri } });
      release();
      await assert.rejects(answer, rejectsWith(LSPErrorCodes.RequestCancelled, /textDocument\/references was cancelled/));
    } finally {
      server.client.workspace.referringFiles = original;
    }
    const locations = await server.client.request<unknown[]>('textDocument/references', {
      ...server.client.at(server.openUri, positionAfter(MAIN, 'maneuverGroupName="')),
      context: { includeDeclaration: true },
    });
    assert.ok(locations.length > 0, 'the same request answers when not cancelled');
    assert.deepEqual(server.client.errors, []);
  });
});
