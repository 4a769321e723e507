import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { PassThrough } from 'node:stream';
import { fileURLToPath, pathToFileURL } from 'node:url';
import {
  CancellationToken,
  createConnection,
  createProtocolConnection,
  Diagnostic,
  InitializeParams,
  MessageType,
  ProposedFeatures,
  ProtocolConnection,
  PublishDiagnosticsParams,
  RequestType,
  StreamMessageReader,
  StreamMessageWriter,
  TextDocumentContentChangeEvent,
} from 'vscode-languageserver/node';
import { startServer } from '../../server/src/languageServer';
import { Workspace } from '../../server/src/workspace';
import { repoRoot, serverBundle } from '../support/paths';
import { SERVER_WAIT_MS } from '../support/wait';
import { temporaryWorkspace } from '../support/workspace';

export function fileUri(filePath: string): string {
  return pathToFileURL(filePath).href;
}

export interface ClientOptions {
  root: string;
  settings?: Record<string, unknown>;
  /** Answer window/workDoneProgress/create and record $/progress (true by default). */
  progress?: boolean;
  initializationOptions?: Record<string, unknown>;
  /** Check files against the OpenSCENARIO schemas (off unless asked: the shared fixtures are minimal, not schema-valid). */
  schema?: boolean;
  /** Declare pull diagnostics (textDocument/diagnostic, with refresh), as VS Code does. */
  pullDiagnostics?: boolean;
  /** More workspace folders after `root`. */
  folders?: string[];
  /** What workspace/configuration answers for a folder (by path), instead of `settings`. */
  folderSettings?: Record<string, Record<string, unknown>>;
  /** Run the built server (dist/server.js) in a child process with this V8 heap, killed after `watchdogMs`. */
  process?: { heapMb: number; watchdogMs: number };
  /** The client's `workspace.workspaceEdit` capability (no documentChanges unless given). */
  workspaceEdit?: { documentChanges?: boolean; resourceOperations?: ('create' | 'rename' | 'delete')[] };
}

/** The settings that turn the schema check off, merged under a test's own. */
function withoutSchema(settings: Record<string, unknown> | undefined, schema: boolean | undefined): Record<string, unknown> {
  return schema ? { ...settings } : { schema: { version: 'off' }, ...settings };
}

/**
 * An LSP client over a real JSON-RPC connection to the server running in this process. Every error
 * the server logs fails the suite (in `stop`, naming the test it happened in) unless the test
 * claimed it with `expectError`.
 */
export class TestClient {
  /** Clients not yet stopped, whose logged errors are checked after every test. */
  static readonly running = new Set<TestClient>();
  readonly diagnostics = new Map<string, PublishDiagnosticsParams>();
  readonly progress: unknown[] = [];
  readonly logs: string[] = [];
  /** How often the server asked this client to pull diagnostics again. */
  refreshes = 0;
  /** What the server registered through `client/registerCapability`, in order. */
  readonly registrations: { id: string; method: string; registerOptions?: unknown }[] = [];
  /** The ids the server unregistered through `client/unregisterCapability`, in order. */
  readonly unregistrations: string[] = [];
  /** Errors the server logged during the running test that it has not claimed (yet). */
  readonly errors: string[] = [];
  /** Errors of finished tests, reported by `stop`. */
  private readonly unexpected: string[] = [];
  private readonly versions = new Map<string, number>();
  /** What the client answers to workspace/configuration; change it, then call `settingsChanged`. */
  settings: Record<string, unknown> = {};
  /** The server's capabilities, as its initialize result announced them. */
  capabilities: Record<string, unknown> = {};
  private schema: boolean | undefined;
  private readonly waiters: (() => void)[] = [];
  /**
   * The run folders of the esmini runs an in-process server answered: the server removes them when its
   * process exits (server/src/features/esminiRun.ts), which for a server in the test's process is after the run.
   */
  private readonly runFolders = new Set<string>();

  private constructor(
    readonly connection: ProtocolConnection,
    private readonly server: { dispose(): void; exited?: () => Promise<void> },
    private readonly serverWorkspace: Workspace | undefined,
  ) {}

  /** The server's workspace (same process), for tests that inject a fault into it. */
  get workspace(): Workspace {
    if (!this.serverWorkspace) throw new Error('the server runs in a child process; its workspace is not reachable');
    return this.serverWorkspace;
  }

  /** Set for a server in a child process: how it ended (undefined while it runs). */
  exit: { code: number | null; signal: NodeJS.Signals | null; stderr: string } | undefined;

  static async start(options: ClientOptions): Promise<TestClient> {
    let connection: ProtocolConnection;
    let client: TestClient;
    if (options.process) {
      const child = spawn(process.execPath, [`--max-old-space-size=${options.process.heapMb}`, serverBundle, '--stdio'], {
        stdio: ['pipe', 'pipe', 'pipe'],
      });
      const watchdog = setTimeout(() => child.kill('SIGKILL'), options.process.watchdogMs);
      let stderr = '';
      child.stderr.on('data', (chunk: Buffer) => (stderr = (stderr + chunk.toString()).slice(-20_000)));
      connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
      const exited = new Promise<void>((resolve) => child.once('exit', () => resolve()));
      client = new TestClient(
        connection,
        {
          dispose: () => {
            clearTimeout(watchdog);
            child.kill('SIGKILL');
          },
          // Told to exit, the server removes what it keeps in the temporary directory; one that does not is killed.
          exited: () => Promise.race([exited, new Promise<void>((resolve) => setTimeout(resolve, SERVER_WAIT_MS))]),
        },
        undefined,
      );
      child.on('exit', (code, signal) => {
        clearTimeout(watchdog);
        client.exit = { code, signal, stderr };
        client.notify();
      });
    } else {
      const toServer = new PassThrough();
      const toClient = new PassThrough();
      const serverConnection = createConnection(ProposedFeatures.all, new StreamMessageReader(toServer), new StreamMessageWriter(toClient));
      const workspace = startServer(serverConnection);
      serverConnection.listen();
      connection = createProtocolConnection(new StreamMessageReader(toClient), new StreamMessageWriter(toServer));
      client = new TestClient(connection, serverConnection, workspace);
    }
    connection.onNotification('textDocument/publishDiagnostics', (params: PublishDiagnosticsParams) => {
      client.diagnostics.set(params.uri, params);
      client.notify();
    });
    connection.onNotification('$/progress', (params: unknown) => {
      client.progress.push(params);
      client.notify();
    });
    connection.onNotification('window/logMessage', (params: { type: MessageType; message: string }) => {
      client.logs.push(params.message);
      if (params.type === MessageType.Error) client.errors.push(params.message);
    });
    client.schema = options.schema;
    client.settings = withoutSchema(options.settings, options.schema);
    connection.onRequest('workspace/configuration', (params: { items: { section?: string; scopeUri?: string }[] }) =>
      params.items.map((item) => {
        const folder = item.scopeUri ? options.folderSettings?.[fileURLToPath(item.scopeUri)] : undefined;
        return folder ? withoutSchema(folder, options.schema) : client.settings;
      }),
    );
    connection.onRequest('window/workDoneProgress/create', () => null);
    connection.onRequest(
      'client/registerCapability',
      (params: { registrations: { id: string; method: string; registerOptions?: unknown }[] }) => {
        client.registrations.push(...params.registrations);
        client.notify();
        return null;
      },
    );
    // The protocol's field is misspelled `unregisterations`.
    connection.onRequest('client/unregisterCapability', (params: { unregisterations: { id: string }[] }) => {
      client.unregistrations.push(...params.unregisterations.map((each) => each.id));
      client.notify();
      return null;
    });
    connection.onRequest('workspace/diagnostic/refresh', () => {
      client.refreshes++;
      client.notify();
      return null;
    });
    connection.listen();
    TestClient.running.add(client);
    const params: InitializeParams = {
      // No process id: the server would otherwise poll it and keep the test process alive.
      processId: null,
      rootUri: fileUri(options.root),
      initializationOptions: options.initializationOptions ?? withoutSchema(undefined, options.schema),
      workspaceFolders: [options.root, ...(options.folders ?? [])].map((folder) => ({ uri: fileUri(folder), name: path.basename(folder) })),
      capabilities: {
        workspace: {
          configuration: options.progress !== false,
          didChangeWatchedFiles: { dynamicRegistration: true, relativePatternSupport: true },
          workspaceEdit: options.workspaceEdit ?? { documentChanges: false },
          workspaceFolders: true,
          ...(options.pullDiagnostics ? { diagnostics: { refreshSupport: true } } : {}),
        },
        window: { workDoneProgress: options.progress !== false },
        textDocument: {
          publishDiagnostics: { relatedInformation: true, versionSupport: true },
          ...(options.pullDiagnostics ? { diagnostic: { relatedDocumentSupport: false } } : {}),
        },
      },
    };
    const initialized = (await connection.sendRequest('initialize', params)) as { capabilities: Record<string, unknown> };
    client.capabilities = initialized.capabilities;
    await connection.sendNotification('initialized', {});
    return client;
  }

  private notify(): void {
    for (const waiter of this.waiters.splice(0)) waiter();
  }

  /** Resolves when `check` holds, re-checking on each notification; rejects after `timeout` ms. */
  async until<T>(check: () => T | undefined, what: string, timeout = SERVER_WAIT_MS): Promise<T> {
    const deadline = Date.now() + timeout;
    for (;;) {
      const value = check();
      if (value !== undefined && value !== false) return value;
      if (this.exit)
        throw new Error(
          `the server process ended (code ${this.exit.code}, signal ${this.exit.signal}) while waiting for ${what}: ${this.exit.stderr.slice(-2000)}`,
        );
      if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
      await new Promise<void>((resolve) => {
        const timer = setTimeout(resolve, 50);
        this.waiters.push(() => {
          clearTimeout(timer);
          resolve();
        });
      });
    }
  }

  /** The diagnostics of `uri` once a publication for its current version arrived. */
  async diagnosticsOf(
    uri: string,
    predicate: (diagnostics: Diagnostic[]) => boolean = () => true,
    timeout = SERVER_WAIT_MS,
  ): Promise<Diagnostic[]> {
    return this.until(
      () => {
        const published = this.diagnostics.get(uri);
        const version = this.versions.get(uri);
        if (!published || (version !== undefined && published.version !== undefined && published.version !== version)) return undefined;
        return predicate(published.diagnostics) ? published.diagnostics : undefined;
      },
      `diagnostics of ${uri}`,
      timeout,
    );
  }

  async indexed(): Promise<void> {
    await this.until(
      () => this.progress.some((entry) => (entry as { value?: { kind?: string } }).value?.kind === 'end') || undefined,
      'indexing to end',
    );
  }

  async settingsChanged(settings: Record<string, unknown>): Promise<void> {
    this.settings = withoutSchema(settings, this.schema);
    await this.connection.sendNotification('workspace/didChangeConfiguration', { settings: null });
  }

  async open(uri: string, text: string): Promise<string> {
    this.versions.set(uri, 1);
    this.diagnostics.delete(uri);
    await this.connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xml', version: 1, text } });
    return uri;
  }

  async openFile(filePath: string): Promise<string> {
    return this.open(fileUri(filePath), fs.readFileSync(filePath, 'utf8'));
  }

  async change(uri: string, changes: TextDocumentContentChangeEvent[]): Promise<void> {
    const version = (this.versions.get(uri) ?? 1) + 1;
    this.versions.set(uri, version);
    await this.connection.sendNotification('textDocument/didChange', { textDocument: { uri, version }, contentChanges: changes });
  }

  async close(uri: string): Promise<void> {
    this.versions.delete(uri);
    await this.connection.sendNotification('textDocument/didClose', { textDocument: { uri } });
  }

  async request<R>(method: string, params: unknown): Promise<R> {
    return this.noteRunFolder((await this.connection.sendRequest(method, params)) as R);
  }

  /** Sends one of the typed custom requests of server/src/protocol.ts. */
  async send<P, R>(type: RequestType<P, R, void>, params: P, token?: CancellationToken): Promise<R> {
    return this.noteRunFolder((await this.connection.sendRequest(type.method, params, token)) as R);
  }

  private noteRunFolder<R>(result: R): R {
    const scenarioFile = (result as { scenarioFile?: unknown } | null)?.scenarioFile;
    if (this.serverWorkspace && typeof scenarioFile === 'string') this.runFolders.add(path.dirname(scenarioFile));
    return result;
  }

  /** Claims a logged error the test provoked on purpose (waiting briefly for it); fails when none matches. */
  async expectError(pattern: RegExp): Promise<string> {
    const index = await this.until(
      () => {
        const found = this.errors.findIndex((error) => pattern.test(error));
        return found >= 0 ? found + 1 : undefined;
      },
      `a logged error matching ${pattern}`,
      SERVER_WAIT_MS,
    );
    return this.errors.splice(index - 1, 1)[0];
  }

  /** Files the errors logged so far under the test that just ran, so `stop` can say where each came from. */
  attributeErrors(test: string): void {
    for (const error of this.errors.splice(0)) this.unexpected.push(`after "${test}": ${error}`);
  }

  /** Throws when the server logged an error nobody expected, and forgets it so it is reported once. */
  assertNoErrors(): void {
    const errors = [...this.unexpected.splice(0), ...this.errors.splice(0)];
    if (errors.length > 0) throw new Error(`the language server logged ${errors.length} error(s) no test expected:\n${errors.join('\n')}`);
  }

  at(uri: string, position: { line: number; character: number }) {
    return { textDocument: { uri }, position };
  }

  async stop(): Promise<void> {
    TestClient.running.delete(this);
    await this.connection.sendRequest('shutdown').catch(() => undefined);
    if (this.server.exited) {
      await this.connection.sendNotification('exit').catch(() => undefined);
      await this.server.exited();
    }
    // In this process, ending the streams would make vscode-languageserver exit it, so only the connections go.
    this.connection.dispose();
    this.server.dispose();
    for (const folder of this.runFolders) fs.rmSync(folder, { recursive: true, force: true });
    this.assertNoErrors();
  }
}

/** A language server on a fresh copy of the bundled examples for the suite that calls this (in its body), stopped after it. */
export function serveExamples(): { root: () => string; client: () => TestClient } {
  let root: string | undefined;
  let client: TestClient | undefined;
  before(async function () {
    root = temporaryWorkspace({}, 'm2s-examples-');
    fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
    client = await TestClient.start({ root });
    await client.indexed();
  });
  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });
  const started = <T>(value: T | undefined): T => {
    if (value === undefined) throw new Error('the examples server has not started');
    return value;
  };
  return { root: () => started(root), client: () => started(client) };
}

/** A server on a temporary workspace, set up by `useServer` for the tests of one suite. */
export interface ServerFixture {
  root: string;
  client: TestClient;
  /** The URI of the file opened before the tests. */
  openUri: string;
}

/**
 * Registers before/after hooks of the calling suite: a temporary workspace of `files`, a server on
 * it, indexed, with `open` (relative) open and its diagnostics published; all gone after the suite.
 */
export function useServer(
  files: Record<string, string | Uint8Array>,
  open: string,
  options: Omit<ClientOptions, 'root'> = {},
): ServerFixture {
  const fixture = {} as ServerFixture;
  before(async function () {
    fixture.root = temporaryWorkspace(files, 'm2s-server-');
    fixture.client = await TestClient.start({ ...options, root: fixture.root });
    await fixture.client.indexed();
    fixture.openUri = await fixture.client.openFile(path.join(fixture.root, open));
    // A pulling client gets no diagnostics pushed; its tests ask for them.
    if (!options.pullDiagnostics) await fixture.client.diagnosticsOf(fixture.openUri);
  });
  after(async function () {
    await fixture.client?.stop();
    if (fixture.root) fs.rmSync(fixture.root, { recursive: true, force: true });
  });
  return fixture;
}

// Root hooks for every file that drives a server. A failing afterEach would abort the whole run, so
// each test's errors are only filed here and fail the suite when its client stops (or, for a client
// never stopped, at the end of the run).
if (typeof afterEach === 'function' && typeof after === 'function') {
  afterEach(function () {
    for (const client of TestClient.running) client.attributeErrors(this.currentTest?.fullTitle() ?? '(unknown test)');
  });
  after(function () {
    for (const client of TestClient.running) client.assertNoErrors();
  });
}
