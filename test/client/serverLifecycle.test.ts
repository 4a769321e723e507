import * as assert from 'node:assert/strict';
import { ServerLifecycle, WindowClosingError, type StartableClient } from '../../client/src/serverLifecycle';

/**
 * A client with vscode-languageclient's start/stop contract (node_modules/vscode-languageclient/lib/common/client.js,
 * 10.x: start() joins a start under way; shutdown() throws while the client is starting and returns when it never
 * ran), whose start the test settles by hand. The real LanguageClient needs a running VS Code.
 */
class ClientWithContract implements StartableClient {
  state: 'initial' | 'starting' | 'running' | 'startFailed' | 'stopped' = 'initial';
  starts = 0;
  stops = 0;
  stopFailure: Error | undefined;
  private pending: { resolve: () => void; reject: (error: Error) => void; promise: Promise<void> } | undefined;

  start(): Promise<void> {
    if (this.state === 'running') return Promise.resolve();
    if (this.pending) return this.pending.promise;
    this.starts++;
    this.state = 'starting';
    let resolve!: () => void;
    let reject!: (error: Error) => void;
    const promise = new Promise<void>((yes, no) => {
      resolve = yes;
      reject = no;
    });
    this.pending = { resolve, reject, promise };
    return promise;
  }

  finishStart(): void {
    this.state = 'running';
    this.pending?.resolve();
    this.pending = undefined;
  }

  failStart(error: Error): void {
    this.state = 'startFailed';
    this.pending?.reject(error);
    this.pending = undefined;
  }

  async stop(): Promise<void> {
    if (this.state === 'initial' || this.state === 'stopped' || this.state === 'startFailed') return;
    if (this.state === 'starting') throw new Error("Client is not running and can't be stopped. It's current state is: starting");
    this.stops++;
    this.state = 'stopped';
    if (this.stopFailure) throw this.stopFailure;
  }

  isRunning(): boolean {
    return this.state === 'running';
  }

  /**
   * sendRequest's checks: refused unless running, then the start joined (a resolved promise once running) through the
   * awaits of its async helpers, then the connection taken, which a stop meanwhile has removed: "Starting server failed".
   */
  async sendRequest(): Promise<string> {
    if (this.state !== 'running') throw new Error('Client is not running');
    for (let hop = 0; hop < 6; hop++) await this.start();
    if (this.state !== 'running') throw new Error('Starting server failed');
    return 'answered';
  }
}

function lifecycleOn(client: ClientWithContract): { lifecycle: ServerLifecycle; failures: unknown[]; notes: string[] } {
  const failures: unknown[] = [];
  const notes: string[] = [];
  const lifecycle = new ServerLifecycle(client, { failed: (error) => failures.push(error), note: (message) => notes.push(message) });
  return { lifecycle, failures, notes };
}

const settle = () => new Promise<void>((resolve) => setImmediate(resolve));

describe('client: the language server at window close (no "Starting server failed")', () => {
  it('the contract it guards against: the client refuses to stop while it starts', async () => {
    const client = new ClientWithContract();
    void client.start();
    await assert.rejects(client.stop(), /can't be stopped.*starting/);
  });

  it('closing the window while the server starts lets the start finish, then stops it, reporting nothing', async () => {
    const client = new ClientWithContract();
    const { lifecycle, failures, notes } = lifecycleOn(client);
    const ready = lifecycle.startAtActivation();
    const closed = lifecycle.close();
    await settle();
    assert.equal(client.stops, 0, 'not stopped while starting');
    client.finishStart();
    await closed;
    await ready;
    assert.equal(client.state, 'stopped');
    assert.equal(client.stops, 1);
    assert.deepEqual(failures, []);
    assert.deepEqual(notes, []);
  });

  it('a start that fails because the window closed meanwhile is one note, not an error', async () => {
    const client = new ClientWithContract();
    const { lifecycle, failures, notes } = lifecycleOn(client);
    const ready = lifecycle.startAtActivation();
    const closed = lifecycle.close();
    client.failStart(new Error('Connection to server got closed'));
    await Promise.all([ready, closed]);
    assert.deepEqual(failures, []);
    assert.equal(notes.length, 1);
    assert.match(notes[0], /window closed while the language server was starting \(Connection to server got closed\)/);
    assert.equal(client.stops, 0, 'a server that never ran is not stopped');
  });

  it('a start that fails with the window open is reported loudly, with the error itself', async () => {
    const client = new ClientWithContract();
    const { lifecycle, failures, notes } = lifecycleOn(client);
    const ready = lifecycle.startAtActivation();
    const error = new Error('Cannot find module dist/server.js');
    client.failStart(error);
    await ready;
    assert.deepEqual(failures, [error]);
    assert.deepEqual(notes, []);
  });

  it('no request starts the server again once the window is closing', async () => {
    const client = new ClientWithContract();
    const { lifecycle } = lifecycleOn(client);
    const ready = lifecycle.startAtActivation();
    client.finishStart();
    await ready;
    await lifecycle.close();
    await assert.rejects(lifecycle.running(), WindowClosingError);
    await assert.rejects(lifecycle.start(), WindowClosingError);
    assert.equal(client.starts, 1);
  });

  it('a request with the window open starts a server that stopped (after a crash) and waits for it', async () => {
    const client = new ClientWithContract();
    const { lifecycle } = lifecycleOn(client);
    const running = lifecycle.running();
    assert.equal(client.starts, 1);
    client.finishStart();
    await running;
    await lifecycle.running();
    assert.equal(client.starts, 1, 'a running server is not started again');
  });

  it('a request VS Code sent in the same batch as the close is answered, not failed with "Starting server failed" by the stop', async () => {
    // Seen at every window reload in code-server: the extension host log's "provider FAILED ... Starting server failed".
    const client = new ClientWithContract();
    const { lifecycle, failures, notes } = lifecycleOn(client);
    const started = lifecycle.startAtActivation();
    client.finishStart();
    await started;
    const request = client.sendRequest();
    const closed = lifecycle.close();
    assert.equal(await request, 'answered');
    await closed;
    assert.equal(client.stops, 1);
    assert.deepEqual([failures, notes], [[], []]);
  });

  it('a stop that fails as the window closes is one note, and closing still ends', async () => {
    const client = new ClientWithContract();
    const { lifecycle, failures, notes } = lifecycleOn(client);
    const ready = lifecycle.startAtActivation();
    client.finishStart();
    await ready;
    client.stopFailure = new Error('Stopping the server timed out');
    await lifecycle.close();
    assert.deepEqual(failures, []);
    assert.deepEqual(notes, ['stopping the language server as the window closed: Stopping the server timed out']);
  });
});
