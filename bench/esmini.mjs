// Run in esmini benchmark (figures, not a timed test): from the request to the finished run of the
// bundled examples, through the built language server as the VS Code command sends it, and by the CLI.
import { spawn, spawnSync } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, readFileSync, realpathSync, rmSync } from 'node:fs';
import { cpus, loadavg, tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createProtocolConnection, StreamMessageReader, StreamMessageWriter } from 'vscode-languageserver/node';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const server = path.join(root, 'dist', 'server.js');
const cli = path.join(root, 'dist', 'cli.js');
const esmini = path.join(root, '.cache', 'esmini', 'bin', 'esmini');
const roads = path.resolve(root, '..', 'shared', 'esmini', 'xodr');
const samples = Number(process.env.BENCH_RUNS ?? 10);
const now = () => Number(process.hrtime.bigint()) / 1e6;

/** @param {number[]} times */
function stats(times) {
  const sorted = [...times].sort((a, b) => a - b);
  return { median: sorted[Math.floor(sorted.length / 2)], p95: sorted[Math.min(sorted.length - 1, Math.ceil(sorted.length * 0.95) - 1)] };
}
/** @param {number} n */
const fmt = (n) => n.toFixed(0).padStart(7);

if (!existsSync(esmini) || !existsSync(roads)) {
  console.log(
    `(esmini benchmark skipped: ${existsSync(esmini) ? roads : esmini} is absent; build esmini with bash ../shared/esmini/build.sh .cache/esmini)`,
  );
  process.exit(0);
}
const folder = realpathSync(mkdtempSync(path.join(tmpdir(), 'm2s-bench-esmini-')));
cpSync(path.join(root, 'examples'), folder, { recursive: true });
const main = pathToFileURL(path.join(folder, 'main.xosc')).href;

const child = spawn(process.execPath, [server, '--stdio'], { stdio: ['pipe', 'pipe', 'inherit'] });
const connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
connection.onNotification('window/logMessage', () => {});
connection.onNotification('textDocument/publishDiagnostics', () => {});
connection.onRequest('workspace/configuration', (params) => params.items.map(() => ({})));
connection.listen();
await connection.sendRequest('initialize', {
  processId: process.pid,
  rootUri: pathToFileURL(folder).href,
  workspaceFolders: [{ uri: pathToFileURL(folder).href, name: 'bench' }],
  capabilities: {},
});
await connection.sendNotification('initialized', {});

const request = [];
const inEsmini = [];
let last;
for (let i = 0; i < samples; i++) {
  const started = now();
  last = await connection.sendRequest('modular2simple/runEsmini', { uri: main, esminiPath: esmini, roadPath: [roads] });
  request.push(now() - started);
  inEsmini.push(last.wallMs);
  if (last.outcome !== 'ok') throw new Error(`the examples did not run cleanly: ${last.message}`);
}
await connection.sendRequest('shutdown');
await connection.sendNotification('exit');
connection.dispose();

/** CPU seconds used by this process's finished children and theirs (Linux), a figure that the machine's load does not change. */
function childrenCpuSeconds() {
  if (!existsSync('/proc/self/stat')) return NaN;
  const fields = readFileSync('/proc/self/stat', 'utf8').split(') ')[1].split(' ');
  return (Number(fields[13]) + Number(fields[14])) / 100;
}

const cliTimes = [];
const cliRuns = Math.max(3, Math.floor(samples / 2));
const cpuBefore = childrenCpuSeconds();
for (let i = 0; i < cliRuns; i++) {
  const started = now();
  const run = spawnSync(process.execPath, [cli, 'run', folder, '--check', '-q', '--road-path', roads, '--esmini', esmini], {
    encoding: 'utf8',
  });
  cliTimes.push(now() - started);
  if (run.status !== 0) throw new Error(`modular2simple run failed: ${run.stderr}`);
}
const cpuPerRun = ((childrenCpuSeconds() - cpuBefore) / cliRuns) * 1000;
rmSync(folder, { recursive: true, force: true });

const [r, e, c] = [stats(request), stats(inEsmini), stats(cliTimes)];
console.log(
  `Run in esmini benchmark: bundled examples (4 entities, ${last.duration} s simulated at ${last.timeStep} s steps; ${samples} runs)`,
);
console.log('                                                   median ms   p95 ms');
console.log(`  request to finished run (language server)         ${fmt(r.median)}  ${fmt(r.p95)}`);
console.log(`    of which flatten + esmini + mapping (runner)    ${fmt(e.median)}  ${fmt(e.p95)}`);
console.log(`  modular2simple run --check (CLI, with start-up)   ${fmt(c.median)}  ${fmt(c.p95)}`);
console.log(
  `    CPU time per CLI run (node and esmini)          ${fmt(cpuPerRun)}            (independent of the machine's load: ${loadavg()[0].toFixed(1)} now, on ${cpus().length} cores)`,
);
console.log(`  target: the picture with trajectories under 2,000 ms: the run takes ${r.median < 2000 ? 'within' : 'OVER'} it`);
