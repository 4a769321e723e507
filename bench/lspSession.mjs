// The language server driven over stdio as the editor drives it, for the benchmarks (bench/lsp.mjs, bench/carla.mjs).
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createProtocolConnection, StreamMessageReader, StreamMessageWriter } from 'vscode-languageserver/node';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
// The server's node gets the extension's flags first (common/src/languageServerProcess.json), so a later one overrides them.
const serverExecArgv = JSON.parse(readFileSync(path.join(root, 'common', 'src', 'languageServerProcess.json'), 'utf8')).execArgv;
const nodeArgs = [...serverExecArgv, ...(process.env.BENCH_NODE_ARGS ?? '').split(' ').filter(Boolean)];

export const now = () => Number(process.hrtime.bigint()) / 1e6;
/** @param {string} file */
export const uriOf = (file) => pathToFileURL(file).href;

/** @param {number[]} times */
export function stats(times) {
  const sorted = [...times].sort((a, b) => a - b);
  return { median: sorted[Math.floor(sorted.length / 2)], p95: sorted[Math.min(sorted.length - 1, Math.ceil(sorted.length * 0.95) - 1)] };
}

/** @param {number | undefined} pid */
export function residentMb(pid) {
  const status = readFileSync(`/proc/${pid}/status`, 'utf8');
  /** @param {string} field */
  const kb = (field) => Number(new RegExp(`${field}:\\s+(\\d+)`).exec(status)?.[1] ?? NaN);
  return { rss: kb('VmRSS') / 1024, peak: kb('VmHWM') / 1024 };
}

/**
 * The CPU time a process has used, in ms (user and system, from /proc): on a shared machine an edit's
 * wall time says more about the other processes than about the server.
 * @param {number | undefined} pid
 */
export function cpuMs(pid) {
  const fields = readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' ');
  return ((Number(fields[11]) + Number(fields[12])) * 1000) / 100;
}

/**
 * Starts a built server.js over stdio with a workspace folder; resolves once indexing reported its end.
 * @param {string} server
 * @param {string} folder
 * @param {Record<string, unknown>} [settings]
 * @param {Record<string, unknown>} [workspaceCapabilities] beside `configuration` (a refactoring's `workspaceEdit`)
 */
export async function startServer(server, folder, settings = {}, workspaceCapabilities = {}) {
  const child = spawn(process.execPath, [...nodeArgs, server, '--stdio'], { stdio: ['pipe', 'pipe', 'inherit'] });
  const connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
  /** @type {Map<string, { version: number, resolve: (diagnostics: import('vscode-languageserver-protocol').Diagnostic[]) => void }>} */
  const diagnosticsWaiters = new Map();
  /** @type {(at: number) => void} */
  let indexEnd;
  /** @type {Promise<number>} */
  const indexed = new Promise((resolve) => (indexEnd = resolve));
  connection.onNotification('textDocument/publishDiagnostics', (params) => {
    const waiter = diagnosticsWaiters.get(params.uri);
    if (waiter && (params.version === undefined || params.version >= waiter.version)) {
      diagnosticsWaiters.delete(params.uri);
      waiter.resolve(params.diagnostics);
    }
  });
  connection.onNotification('$/progress', (params) => {
    if (params.value?.kind === 'end') indexEnd(now());
  });
  connection.onNotification('window/logMessage', () => {});
  connection.onRequest('workspace/configuration', (params) => params.items.map(() => settings));
  connection.onRequest('window/workDoneProgress/create', () => null);
  connection.onRequest('client/registerCapability', () => null);
  connection.listen();
  await connection.sendRequest('initialize', {
    processId: process.pid,
    rootUri: uriOf(folder),
    workspaceFolders: [{ uri: uriOf(folder), name: 'bench' }],
    capabilities: { workspace: { configuration: true, ...workspaceCapabilities }, window: { workDoneProgress: true } },
  });
  const started = now();
  await connection.sendNotification('initialized', {});
  const indexMs = (await indexed) - started;
  /**
   * @param {string} uri
   * @param {number} version
   * @returns {Promise<import('vscode-languageserver-protocol').Diagnostic[]>}
   */
  const diagnosticsFor = (uri, version) => new Promise((resolve) => diagnosticsWaiters.set(uri, { version, resolve }));
  const stop = async () => {
    await connection.sendRequest('shutdown');
    await connection.sendNotification('exit');
    connection.dispose();
  };
  return { child, connection, indexMs, diagnosticsFor, stop };
}
