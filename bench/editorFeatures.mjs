// Editor features of the semantic model over the built language server (dist/server.js, stdio): on a
// file with 1,000 parameters and 1,000 expressions, hover, definition, inlay hints, semantic tokens
// and completion after `$`, and diagnostics after an edit. Figures, not a timed test.
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createProtocolConnection, StreamMessageReader, StreamMessageWriter } from 'vscode-languageserver/node';
import { parameterScenario } from './parameterScenario.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const server = path.join(root, 'dist', 'server.js');
const samples = Number(process.env.BENCH_SAMPLES ?? 100);
// BENCH_NODE_ARGS are given to the server's node (e.g. --cpu-prof), as in bench/lsp.mjs.
// The server's node gets the extension's flags first (common/src/languageServerProcess.json), so a later one overrides them.
const serverExecArgv = JSON.parse(readFileSync(path.join(root, 'common', 'src', 'languageServerProcess.json'), 'utf8')).execArgv;
const nodeArgs = [...serverExecArgv, ...(process.env.BENCH_NODE_ARGS ?? '').split(' ').filter(Boolean)];
if (!existsSync(server)) {
  console.error('dist/server.js is missing: run npm run build first');
  process.exit(1);
}

const now = () => Number(process.hrtime.bigint()) / 1e6;
/** @param {number[]} times */
function stats(times) {
  const sorted = [...times].sort((a, b) => a - b);
  return { median: sorted[Math.floor(sorted.length / 2)], p95: sorted[Math.min(sorted.length - 1, Math.ceil(sorted.length * 0.95) - 1)] };
}
/**
 * @param {string} text
 * @param {number} offset
 */
function positionOf(text, offset) {
  const before = text.slice(0, offset);
  const line = before.split('\n').length - 1;
  return { line, character: offset - (before.lastIndexOf('\n') + 1) };
}

const workspace = realpathSync(mkdtempSync(path.join(tmpdir(), 'm2s-bench-editor-')));
const file = path.join(workspace, 'parameters.xosc');
const text = parameterScenario();
writeFileSync(file, text);
const uri = pathToFileURL(file).href;

const child = spawn(process.execPath, [...nodeArgs, server, '--stdio'], { stdio: ['pipe', 'pipe', 'inherit'] });
const connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
const waiters = new Map();
connection.onNotification('textDocument/publishDiagnostics', (params) => {
  const waiter = waiters.get(params.version);
  if (waiter) {
    waiters.delete(params.version);
    waiter(params.diagnostics);
  }
});
connection.onNotification('window/logMessage', (params) => {
  if (params.type === 1) console.error(`server error: ${params.message}`);
});
connection.onNotification('$/progress', () => {});
connection.onRequest('workspace/configuration', (params) => params.items.map(() => ({})));
connection.onRequest('window/workDoneProgress/create', () => null);
connection.onRequest('client/registerCapability', () => null);
connection.listen();
await connection.sendRequest('initialize', {
  processId: process.pid,
  rootUri: pathToFileURL(workspace).href,
  workspaceFolders: [{ uri: pathToFileURL(workspace).href, name: 'bench' }],
  // The generated file is about parameters, not a whole schema-valid scenario; bench/lsp.mjs times the schema check on its own.
  initializationOptions: { schema: { version: 'off' } },
  capabilities: {},
});
await connection.sendNotification('initialized', {});
/**
 * @param {number} version
 * @returns {Promise<import('vscode-languageserver-protocol').Diagnostic[]>}
 */
const diagnosticsOf = (version) => new Promise((resolve) => waiters.set(version, resolve));

let version = 1;
let pending = diagnosticsOf(version);
let started = now();
await connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xml', version, text } });
const first = await pending;
const openMs = now() - started;
if (first.some((diagnostic) => diagnostic.severity === 1)) throw new Error(`unexpected errors: ${first[0].message}`);

// Cursors on `$P...` uses spread over the file (in declarations and in the 1,000 event expressions).
const uses = [...text.matchAll(/\$P\d+/g)].map((match) => match.index + 2);
const cursors = Array.from({ length: samples }, (_, i) => positionOf(text, uses[Math.floor((i * uses.length) / samples)]));
const lineCount = text.split('\n').length;
/**
 * @param {string} method
 * @param {(i: number) => object} paramsOf
 */
async function measure(method, paramsOf) {
  const times = [];
  let last;
  for (let i = 0; i < samples; i++) {
    const params = paramsOf(i);
    const begun = now();
    last = await connection.sendRequest(method, params);
    times.push(now() - begun);
  }
  return { ...stats(times), last };
}
/** @param {number} i */
const at = (i) => ({ textDocument: { uri }, position: cursors[i] });
const hover = await measure('textDocument/hover', at);
const definition = await measure('textDocument/definition', at);
// A visible screen of 60 lines around each cursor, as an editor asks; and the whole file.
const screen = await measure('textDocument/inlayHint', (i) => ({
  textDocument: { uri },
  range: { start: { line: Math.max(0, cursors[i].line - 30), character: 0 }, end: { line: cursors[i].line + 30, character: 0 } },
}));
const whole = await measure('textDocument/inlayHint', () => ({
  textDocument: { uri },
  range: { start: { line: 0, character: 0 }, end: { line: lineCount, character: 0 } },
}));
const tokens = await measure('textDocument/semanticTokens/full', () => ({ textDocument: { uri } }));
const completion = await measure('textDocument/completion', at);
if (!hover.last || definition.last.length !== 1 || whole.last.length !== 1500 || completion.last.length !== 1000)
  throw new Error('the features did not answer as expected');

// Edits of a declaration's value (as typing does), each followed by its diagnostics.
/** @type {number[]} */
const edits = [];
const declarations = [...text.matchAll(/name="P(\d*[02468])" parameterType="double" value="/g)].map(
  (match) => match.index + match[0].length,
);
// The first edits after the file opened run code V8 has not compiled yet: timed apart from the steady state.
const warmUp = 10;
/** @type {number[]} */
const coldEdits = [];
for (let i = 0; i < warmUp + Math.min(samples, 60); i++) {
  const position = positionOf(text, declarations[(i * 37) % declarations.length]);
  version++;
  pending = diagnosticsOf(version);
  started = now();
  await connection.sendNotification('textDocument/didChange', {
    textDocument: { uri, version },
    contentChanges: [
      { range: { start: position, end: { line: position.line, character: position.character + 1 } }, text: String((i % 9) + 1) },
    ],
  });
  await pending;
  (i < warmUp ? coldEdits : edits).push(now() - started);
}
const edit = stats(edits);
if (process.env.BENCH_TIMES) console.log([...coldEdits, ...edits].map((t) => t.toFixed(0)).join(' '));
// After an edit, the first request also waits for the file's new analysis.
version++;
await connection.sendNotification('textDocument/didChange', {
  textDocument: { uri, version },
  contentChanges: [{ range: { start: cursors[0], end: cursors[0] }, text: '' }],
});
started = now();
await connection.sendRequest('textDocument/hover', at(1));
const hoverAfterEdit = now() - started;

await connection.sendRequest('shutdown');
await connection.sendNotification('exit');
connection.dispose();
rmSync(workspace, { recursive: true, force: true });

/** @param {number} n */
const fmt = (n) => n.toFixed(2).padStart(8);
/**
 * @param {string} label
 * @param {{ median: number, p95: number }} figures
 * @param {number} [target]
 */
const row = (label, figures, target) =>
  console.log(
    `  ${label.padEnd(44)}${fmt(figures.median)}  ${fmt(figures.p95)}${target ? `   ${figures.p95 < target ? 'within' : 'OVER'} ${target} ms` : ''}`,
  );
console.log(
  `editor features over the language server: ${(text.length / 1024).toFixed(0)} KB, ${lineCount} lines, 1,000 parameters, 1,000 expressions (${samples} samples)`,
);
console.log('                                                median ms    p95 ms');
console.log(`  open to first diagnostics                 ${fmt(openMs)}`);
row('hover on $name / ${...}', hover, 20);
row('definition of $name', definition, 20);
row('inlay hints, 60 visible lines', screen, 20);
row('inlay hints, whole file (1,500)', whole, 20);
row('semantic tokens, whole file', tokens);
row('completion after $ (1,000 items)', completion);
row(`edit -> diagnostics, all ${coldEdits.length + edits.length} edits`, stats([...coldEdits, ...edits]), 30);
console.log(`    the first ${warmUp} after opening (V8 compiling)  ${fmt(stats(coldEdits).median)}  ${fmt(Math.max(...coldEdits))} (max)`);
row('  the edits after them', edit, 30);
console.log(`  first hover right after an edit (waits for the analysis): ${hoverAfterEdit.toFixed(1)} ms`);
