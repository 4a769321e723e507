import * as assert from 'node:assert/strict';
import { whileRunning } from '../../client/src/requestGate';

describe('client: the requests VS Code makes by itself wait for a running language server', () => {
  const document = {} as never;
  const token = {} as never;

  it('answers nothing, and sends nothing, while the server is not running (no "Starting server failed" on a window switch)', async () => {
    const gate = whileRunning(() => false);
    let sent = 0;
    const next = () => {
      sent++;
      return [];
    };
    assert.equal(await gate.provideCodeActions?.(document, {} as never, {} as never, token, next), undefined);
    assert.equal(await gate.provideCodeLenses?.(document, token, next), undefined);
    assert.equal(await gate.provideInlayHints?.(document, {} as never, token, next), undefined);
    assert.equal(await gate.provideDocumentLinks?.(document, token, next), undefined);
    assert.equal(await gate.provideDocumentSemanticTokens?.(document, token, () => (sent++, undefined)), undefined);
    assert.equal(sent, 0);
  });

  it('forwards every request, arguments unchanged, once the server runs', async () => {
    let running = false;
    const gate = whileRunning(() => running);
    const range = { start: 1 } as never;
    const context = { only: 'quickfix' } as never;
    const received: unknown[][] = [];
    const next = (...args: unknown[]) => {
      received.push(args);
      return [{ title: 'fix' }];
    };
    assert.equal(await gate.provideCodeActions?.(document, range, context, token, next), undefined);
    running = true;
    assert.deepEqual(await gate.provideCodeActions?.(document, range, context, token, next), [{ title: 'fix' }]);
    assert.deepEqual(received, [[document, range, context, token]]);
  });

  it('leaves what the user asks for (completion, rename) to the client, which says why it failed', () => {
    const gate = whileRunning(() => false);
    assert.equal(gate.provideCompletionItem, undefined);
    assert.equal(gate.provideRenameEdits, undefined);
  });
});
