// Formatter benchmark (prints figures, asserts nothing): Format Document and Format Selection on a
// generated 15,000-line scenario through the built language server, and `format --check` as a process.
import { spawn, spawnSync } from 'node:child_process';
import * as esbuild from 'esbuild';
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { createProtocolConnection, StreamMessageReader, StreamMessageWriter } from 'vscode-languageserver/node';
import { cpuMs, now, startServer, stats, uriOf } from './lspSession.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
// BENCH_SERVER: another build's server.js, to measure two builds side by side in the same minutes.
const server = process.env.BENCH_SERVER ?? path.join(root, 'dist', 'server.js');
const cli = path.join(root, 'dist', 'cli.js');
const samples = Number(process.env.BENCH_SAMPLES ?? 30);

if (!existsSync(server) || !existsSync(cli)) {
  console.error('dist/ is missing: run npm run build first');
  process.exit(1);
}

/**
 * A scenario of about `lines` lines, indented badly (every line at column 0) with long tags, comments and blank lines.
 * @param {number} lines
 */
function messyScenario(lines) {
  const parts = [
    '<?xml version="1.0" encoding="UTF-8"?>',
    '<OpenSCENARIO>',
    '<FileHeader revMajor="1" revMinor="0" date="2026-01-01T00:00:00" description="format benchmark" author="bench"/>',
    '<Storyboard>',
    '<Story name="S">',
    '<Act name="A">',
  ];
  for (let group = 0; parts.length < lines - 6; group++) {
    parts.push(
      `<ManeuverGroup name="G${group}" maximumExecutionCount="1">`,
      '<Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>',
      `<!-- maneuver ${group} -->`,
      `<Maneuver name="M${group}">`,
      `<Event name="E${group}" priority="overwrite" maximumExecutionCount="1">`,
      `<Action name="Speed${group}">`,
      '<PrivateAction><LongitudinalAction><SpeedAction>',
      '<SpeedActionDynamics dynamicsShape="sinusoidal" value="${$duration * 2}" dynamicsDimension="time" followingMode="follow"/>',
      '<SpeedActionTarget><AbsoluteTargetSpeed value="$speed"/></SpeedActionTarget>',
      '</SpeedAction></LongitudinalAction></PrivateAction>',
      '</Action>',
      '',
      '',
      '<StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="rising"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>',
      '</Event>',
      '</Maneuver>',
      '</ManeuverGroup>',
    );
  }
  parts.push('</Act>', '</Story>', '</Storyboard>', '</OpenSCENARIO>', '');
  return parts.join('\n');
}

const folder = mkdtempSync(path.join(tmpdir(), 'm2s-format-bench-'));
// The extension splits a reply of one edit into an edit per changed space before VS Code gets it (client/src/formatEdits.ts).
const split = /** @type {typeof import('../common/src/whitespaceEdits')} */ (
  await import(
    `data:text/javascript;base64,${Buffer.from(
      (
        await esbuild.build({
          entryPoints: [path.join(root, 'common', 'src', 'whitespaceEdits.ts')],
          bundle: true,
          format: 'esm',
          write: false,
          logLevel: 'warning',
        })
      ).outputFiles[0].text,
    ).toString('base64')}`
  )
);
const file = path.join(folder, 'big.xosc');
const text = messyScenario(15_000);
writeFileSync(file, text);
const inputLines = text.split('\n').length;

// The server starts as the extension starts it (bench/lspSession.mjs: its node flags, a workspace folder indexed
// first); BENCH_FORMAT_BARE=1 starts it as this bench did until 2026-11-29, a bare `node server.js` without the flags.
const bare = process.env.BENCH_FORMAT_BARE === '1';
/** @returns {Promise<{ child: import('node:child_process').ChildProcess, connection: import('vscode-languageserver-protocol').ProtocolConnection, stop: () => Promise<void> }>} */
async function start() {
  if (!bare) return startServer(server, folder);
  const child = spawn(process.execPath, [server, '--stdio'], { stdio: ['pipe', 'pipe', 'inherit'] });
  const connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
  // Every other notification is dropped: vscode-jsonrpc's catch-all handler, which ProtocolConnection's type leaves out.
  /** @type {import('vscode-jsonrpc').MessageConnection} */ (/** @type {unknown} */ (connection)).onNotification(() => {});
  connection.onRequest('workspace/configuration', (params) => params.items.map(() => ({})));
  connection.onRequest('window/workDoneProgress/create', () => null);
  connection.onRequest('client/registerCapability', () => null);
  connection.listen();
  await connection.sendRequest('initialize', { processId: process.pid, rootUri: uriOf(folder), capabilities: {} });
  await connection.sendNotification('initialized', {});
  const stop = async () => {
    await connection.sendRequest('shutdown');
    await connection.sendNotification('exit');
    connection.dispose();
  };
  return { child, connection, stop };
}
const { child, connection, stop } = await start();
const uri = uriOf(file);
await connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xosc', version: 1, text } });

const options = { tabSize: 2, insertSpaces: true };
const documentTimes = [];
const splitTimes = [];
let splitCount = 0;
/** @type {import('vscode-languageserver-protocol').TextEdit[]} */
let edits = [];
const cpuBefore = cpuMs(child.pid);
for (let i = 0; i < samples; i++) {
  const started = now();
  edits = await connection.sendRequest('textDocument/formatting', { textDocument: { uri }, options });
  documentTimes.push(now() - started);
  if (edits.length === 1) {
    // As the client does: the edit's original text, split by white space (its positions are a binary search each).
    const splitStarted = now();
    const lineStarts = lineStartsOf(text);
    const range = edits[0].range;
    const from = lineStarts[range.start.line] + range.start.character;
    splitCount = split.whitespaceEdits(text.slice(from, lineStarts[range.end.line] + range.end.character), edits[0].newText)?.length ?? -1;
    splitTimes.push(now() - splitStarted);
  }
}
const serverCpu = (cpuMs(child.pid) - cpuBefore) / samples;
const replyBytes = Buffer.byteLength(JSON.stringify(edits));
/** @param {string} text */
function lineStartsOf(text) {
  const starts = [0];
  for (let at = text.indexOf('\n'); at !== -1; at = text.indexOf('\n', at + 1)) starts.push(at + 1);
  return starts;
}
// The common case, format on save of a file already formatted: the same scenario after one pass.
const formattedUri = uriOf(path.join(folder, 'formatted.xosc'));
let formatted = text;
{
  const lines = formatted.split('\n');
  const starts = [0];
  for (const line of lines) starts.push(starts[starts.length - 1] + line.length + 1);
  /** @param {{ line: number, character: number }} position */
  const offset = (position) => starts[position.line] + position.character;
  // One pass in document order: slicing the whole text once per edit took minutes of this process's CPU.
  const pieces = [];
  let position = 0;
  for (const edit of [...edits].sort((a, b) => offset(a.range.start) - offset(b.range.start))) {
    pieces.push(formatted.slice(position, offset(edit.range.start)), edit.newText);
    position = offset(edit.range.end);
  }
  formatted = pieces.join('') + formatted.slice(position);
}
await connection.sendNotification('textDocument/didOpen', {
  textDocument: { uri: formattedUri, languageId: 'xosc', version: 1, text: formatted },
});
const cleanTimes = [];
for (let i = 0; i < samples; i++) {
  const started = now();
  const none = await connection.sendRequest('textDocument/formatting', { textDocument: { uri: formattedUri }, options });
  cleanTimes.push(now() - started);
  if (none.length !== 0) throw new Error(`a formatted document got ${none.length} edits`);
}

const rangeTimes = [];
for (let i = 0; i < samples; i++) {
  const line = 7000 + i;
  const started = now();
  await connection.sendRequest('textDocument/rangeFormatting', {
    textDocument: { uri },
    options,
    range: { start: { line, character: 0 }, end: { line: line + 40, character: 0 } },
  });
  rangeTimes.push(now() - started);
}
await stop();

const cliTimes = [];
for (let i = 0; i < Math.max(5, Math.floor(samples / 3)); i++) {
  const started = now();
  const run = spawnSync(process.execPath, [cli, 'format', '--check', '--indent', '2', file], { encoding: 'utf8' });
  cliTimes.push(now() - started);
  if (run.status !== 1) throw new Error(`format --check should report the messy file: ${run.stderr}`);
}
rmSync(folder, { recursive: true, force: true });

/** @param {number} n */
const fmt = (n) => n.toFixed(1).padStart(7);
const documentStats = stats(documentTimes);
console.log(
  `formatter benchmark (${samples} runs; a ${inputLines.toLocaleString('en-US')}-line scenario at column 0, ${edits.length.toLocaleString('en-US')} edits, ${replyBytes.toLocaleString('en-US')} bytes of JSON; server started ${bare ? "bare, without the extension's node flags" : 'as the extension starts it'})`,
);
console.log('                                              median ms   p95 ms');
console.log(`  Format Document over LSP (request to reply)   ${fmt(documentStats.median)}  ${fmt(documentStats.p95)}`);
if (splitTimes.length > 0) {
  const splitStats = stats(splitTimes);
  console.log(
    `    the client's split of the one edit into ${splitCount.toLocaleString('en-US')} edits  ${fmt(splitStats.median)}  ${fmt(splitStats.p95)}`,
  );
}
const clean = stats(cleanTimes);
console.log(`  Format Document, already formatted (no edits)  ${fmt(clean.median)}  ${fmt(clean.p95)}`);
const range = stats(rangeTimes);
console.log(`  Format Selection of 40 lines over LSP          ${fmt(range.median)}  ${fmt(range.p95)}`);
const process_ = stats(cliTimes);
console.log(`  modular2simple format --check (whole process)  ${fmt(process_.median)}  ${fmt(process_.p95)}`);
console.log(`  server CPU time per Format Document: ${serverCpu.toFixed(1)} ms (mean; the wall times above include waiting for a CPU)`);
console.log(`  Format Document: ${documentStats.p95 < 200 ? 'within' : 'OVER'} the 200 ms target (p95)`);
