// Debugger benchmark (figures, not a timed test): simulation steps per second under the debug adapter with no
// breakpoint hit against esmini's own headless run of the same scenario at the same step, the pause latency from
// a condition firing (esmini's callback, in the adapter) to the `stopped` event read by a DAP client, and F5's first
// launch: the adapter's process started to the stop on a breakpoint (BENCH_DEBUG_LAUNCH_ONLY=1: that alone;
// BENCH_DEBUG_CODE_CACHE=1: with the session's code cache, see below).
// BENCH_DEBUG_ROAD=FILE: cut-in.xosc on that road instead of e6mini.xodr (the launch reads and checks it; on another
// road CutInEvent may never start, so the launch's breakpoint is on OverTakerStartSpeedEvent, at 0.05 s).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const require = createRequire(import.meta.url);
const { DebugClient } = require('@vscode/debugadapter-testsupport');

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
// BENCH_DEBUG_ADAPTER names another build of the adapter (the one before a change) to compare.
const adapter = path.resolve(process.env.BENCH_DEBUG_ADAPTER ?? path.join(root, 'dist', 'debugAdapter.js'));
// BENCH_ESMINI names another esmini build folder (bin/esmini, lib/libesminiLib.so), for a build with other flags.
const esminiBuild = path.resolve(process.env.BENCH_ESMINI ?? path.join(root, '.cache', 'esmini'));
const esmini = path.join(esminiBuild, 'bin', 'esmini');
const library = path.join(esminiBuild, 'lib', 'libesminiLib.so');
const corpus = path.resolve(root, '..', 'shared', 'corpus', 'openscenario', 'esmini');
const scenario = path.join(corpus, 'cut-in.xosc');
const roadPath = [path.resolve(root, '..', 'shared', 'esmini', 'xodr'), path.join(corpus, 'Catalogs', 'Vehicles')];
// A small step, so that the stepping outweighs the noise of start-up and load on a busy machine.
const step = Number(process.env.BENCH_DEBUG_STEP ?? 0.001);
const runs = Number(process.env.BENCH_RUNS ?? 7);
/** The monotonic clock, in ms: the same clock as the adapter's process.hrtime on Linux (CLOCK_MONOTONIC). */
const now = () => Number(process.hrtime.bigint()) / 1e6;

for (const needed of [adapter, esmini, library, scenario, ...roadPath])
  if (!existsSync(needed)) {
    console.log(`(debugger benchmark skipped: ${needed} is absent; npm run build, bash ../shared/esmini/build.sh .cache/esmini)`);
    process.exit(0);
  }

/** @param {number[]} values */
function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
}

// The same scenario twice, beside each other: as written, and ending at its first step (esmini's start-up and load
// alone, subtracted from the full run to give esmini's stepping time).
const folder = mkdtempSync(path.join(tmpdir(), 'm2s-bench-debugger-'));
const road = path.resolve(process.env.BENCH_DEBUG_ROAD ?? path.join(roadPath[0], 'e6mini.xodr'));
if (!existsSync(road)) throw new Error(`BENCH_DEBUG_ROAD: ${road} is absent`);
const text = readFileSync(scenario, 'utf8').replace('../xodr/e6mini.xodr', road);
const launchEvent = process.env.BENCH_DEBUG_ROAD ? 'OverTakerStartSpeedEvent' : 'CutInEvent';
// BENCH_DEBUG_CODE_CACHE=1: the session's code cache in a folder of this bench's, as the extension names its storage
// (server/src/debug/codeCache.ts): the first launch writes it as its session ends, the later ones read it.
if (process.env.BENCH_DEBUG_CODE_CACHE === '1') process.env.M2S_DEBUG_CODE_CACHE = path.join(folder, 'code-cache');
else delete process.env.M2S_DEBUG_CODE_CACHE;
const full = path.join(folder, 'cut-in.xosc');
const loadOnly = path.join(folder, 'cut-in-load-only.xosc');
writeFileSync(full, text);
const stopAtOnce =
  '<StopTrigger><ConditionGroup><Condition name="Now" delay="0" conditionEdge="none"><ByValueCondition>' +
  '<SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>';
writeFileSync(loadOnly, text.replace(/<StopTrigger>[\s\S]*<\/StopTrigger>/, stopAtOnce));

/**
 * esmini's own headless run: wall ms, CPU ms (bash's `times` for its children), and the simulated time it ended at
 * (its log's last line).
 * @param {string} file
 */
function esminiRun(file) {
  const args = ['--headless', '--osc', file, '--fixed_timestep', String(step), '--disable_log'];
  for (const folderOfPath of roadPath) args.push('--path', folderOfPath);
  const log = path.join(folder, 'esmini.out');
  const started = now();
  const result = spawnSync('bash', ['-c', 'out=$1; shift; "$@" > "$out" || exit $?; times', 'bench', log, esmini, ...args], {
    cwd: folder,
    encoding: 'utf8',
  });
  const ms = now() - started;
  const output = readFileSync(log, 'utf8');
  if (result.status !== 0) throw new Error(`esmini failed on ${file}: ${output}${result.stderr}`);
  const children = /^(\d+)m([\d.]+)s (\d+)m([\d.]+)s$/m.exec(result.stdout.trim().split('\n')[1] ?? '');
  if (!children) throw new Error(`bash's times said ${result.stdout}`);
  const cpuMs = (Number(children[1]) * 60 + Number(children[2]) + Number(children[3]) * 60 + Number(children[4])) * 1000;
  const times = [...output.matchAll(/^\[([\d.]+)\]/gm)].map((match) => Number(match[1]));
  return { ms, cpuMs, end: Math.max(...times) };
}

/**
 * The adapter's child that runs the session (its parent process is the adapter's): read from /proc.
 * @param {number} adapterPid
 */
function sessionPid(adapterPid) {
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    try {
      // The fields after the command's closing parenthesis: state, then the parent's pid.
      const stat = readFileSync(`/proc/${name}/stat`, 'utf8');
      if (Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]) === adapterPid) return Number(name);
    } catch {
      // A process that ended meanwhile.
    }
  }
  throw new Error(`the adapter (pid ${adapterPid}) runs no session process`);
}

/**
 * CPU ms of a process's main thread so far (Linux /proc schedstat, in ns): the adapter steps esmini on it.
 * @param {number} pid
 */
function mainThreadCpuMs(pid) {
  return Number(readFileSync(`/proc/${pid}/task/${pid}/schedstat`, 'utf8').split(' ')[0]) / 1e6;
}

/**
 * A new adapter process, as VS Code starts one, with its process id (the session it runs is a child of it).
 * @returns {Promise<{ client: DebugClient, adapterPid: number }>}
 */
async function startAdapter() {
  const client = new DebugClient(process.execPath, adapter, 'modular2simple', { stdio: ['pipe', 'pipe', 'pipe'] });
  client.defaultTimeout = 120_000;
  await client.start();
  const adapterPid = /** @type {{ _adapterProcess: import('node:child_process').ChildProcess }} */ (/** @type {unknown} */ (client))
    ._adapterProcess.pid;
  if (adapterPid === undefined) throw new Error('the adapter did not start');
  return { client, adapterPid };
}

/**
 * One debug session through the protocol, as VS Code drives it: load (launch to initialized), then the run from
 * configurationDone to terminated. With `breakOn`, a breakpoint on that line: the latency from the condition's firing
 * (reported in the Output event's data) to the stopped event's arrival.
 * @param {number | undefined} breakOn
 * @param {string} [program]
 * @param {number} [timeStep]
 * @returns {Promise<{ loadMs: number, runMs: number, runCpuMs: number, ended: number, latencyMs: number }>}
 */
async function debugRun(breakOn, program = full, timeStep = step) {
  const { client, adapterPid } = await startAdapter();
  try {
    await client.initializeRequest();
    // The adapter runs the session, which steps esmini, in a child (server/src/debug/supervisor.ts): its CPU is counted.
    const pid = sessionPid(adapterPid);
    let ended = NaN;
    /** @type {Map<string, number>} */
    const firings = new Map();
    let stoppedAt = NaN;
    client.on('output', (/** @type {import('@vscode/debugprotocol').DebugProtocol.OutputEvent} */ event) => {
      const reported = event.body.data?.reportedAtMs;
      if (typeof reported === 'number') firings.set(event.body.data.element, reported);
      const end = /The scenario ended at ([\d.]+) s/.exec(event.body.output);
      if (end) ended = Number(end[1]);
    });
    client.on('stopped', () => (stoppedAt = now()));
    const started = now();
    /** @type {import('@vscode/debugprotocol').DebugProtocol.LaunchRequestArguments & Record<string, unknown>} */
    const launch = { program, roadPath, timeStep, duration: 120, esminiLibrary: library };
    const launched = client.launchRequest(launch);
    await client.waitForEvent('initialized');
    const loadMs = now() - started;
    if (breakOn !== undefined) {
      const set = await client.setBreakpointsRequest({ source: { path: full }, breakpoints: [{ line: breakOn }] });
      if (!set.body.breakpoints[0].verified) throw new Error(`the breakpoint on line ${breakOn} is not verified`);
    }
    const done = client.waitForEvent(breakOn === undefined ? 'terminated' : 'stopped');
    const running = now();
    const cpuBefore = mainThreadCpuMs(pid);
    await client.configurationDoneRequest();
    await launched;
    await done;
    const runMs = now() - running;
    const runCpuMs = mainThreadCpuMs(pid) - cpuBefore;
    if (breakOn === undefined) return { loadMs, runMs, runCpuMs, ended, latencyMs: NaN };
    const reported = [...firings.values()].at(-1);
    if (reported === undefined) throw new Error('no condition firing was reported before the stop');
    await client.terminateRequest();
    return { loadMs, runMs, runCpuMs, ended, latencyMs: stoppedAt - reported };
  } finally {
    await client.stop();
  }
}

/**
 * A Pause request in the middle of a run, as VS Code's pause button sends it: ms from sending it to the stopped event,
 * the simulated time the stop reports, and the time the run ends at after Continue (to compare with a run left alone).
 * @param {number} afterMs wall ms of running before the pause
 * @param {number} timeStep
 * @returns {Promise<{ latencyMs: number, pausedAt: number, ended: number }>}
 */
async function pauseRun(afterMs, timeStep) {
  const client = new DebugClient(process.execPath, adapter, 'modular2simple', { stdio: ['pipe', 'pipe', 'pipe'] });
  client.defaultTimeout = 120_000;
  await client.start();
  try {
    let ended = NaN;
    client.on('output', (/** @type {import('@vscode/debugprotocol').DebugProtocol.OutputEvent} */ event) => {
      const end = /The scenario ended at ([\d.]+) s/.exec(event.body.output);
      if (end) ended = Number(end[1]);
    });
    let stoppedAt = NaN;
    client.on('stopped', () => (stoppedAt = now()));
    await client.initializeRequest();
    const launched = client.launchRequest(
      /** @type {import('@vscode/debugprotocol').DebugProtocol.LaunchRequestArguments & Record<string, unknown>} */ ({
        program: full,
        roadPath,
        timeStep,
        duration: 120,
        esminiLibrary: library,
      }),
    );
    await client.waitForEvent('initialized');
    await client.configurationDoneRequest();
    await launched;
    await new Promise((resolve) => setTimeout(resolve, afterMs));
    const stopped = client.waitForEvent('stopped');
    const sent = now();
    await client.pauseRequest({ threadId: 1 });
    await stopped;
    const latencyMs = stoppedAt - sent;
    const pausedAt = Number((await client.evaluateRequest({ expression: 'time', context: 'watch' })).body.result);
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
    return { latencyMs, pausedAt, ended };
  } finally {
    await client.stop();
  }
}

/**
 * F5 as VS Code does it, from a new adapter process each time: its process started to the initialize response (the
 * adapter's two processes starting), the launch request to `initialized` (flattening, esmini loading the scenario),
 * configurationDone to the `stopped` event on a breakpoint on CutInEvent (6.5 s in, at the default step), and the
 * adapter's processes' CPU (every thread of both) until then. The first of a series is the first start of this
 * bench; the machine's file cache is not dropped.
 * @returns {Promise<{ startMs: number, loadMs: number, stopMs: number, totalMs: number, cpuMs: number }>}
 */
async function firstLaunch() {
  const eventLine = text.split('\n').findIndex((line) => line.includes(`<Event name="${launchEvent}"`)) + 1;
  const started = now();
  const { client, adapterPid } = await startAdapter();
  try {
    await client.initializeRequest();
    const initialized = now();
    const launched = client.launchRequest(
      /** @type {import('@vscode/debugprotocol').DebugProtocol.LaunchRequestArguments & Record<string, unknown>} */ ({
        program: full,
        roadPath,
        esminiLibrary: library,
      }),
    );
    await client.waitForEvent('initialized');
    const loaded = now();
    const set = await client.setBreakpointsRequest({ source: { path: full }, breakpoints: [{ line: eventLine }] });
    if (!set.body.breakpoints[0].verified) throw new Error(`the breakpoint on line ${eventLine} is not verified`);
    const stopped = client.waitForEvent('stopped');
    await client.configurationDoneRequest();
    await launched;
    await stopped;
    const stoppedAt = now();
    const cpuMs = processCpuMs(adapterPid) + processCpuMs(sessionPid(adapterPid));
    await client.terminateRequest();
    return {
      startMs: initialized - started,
      loadMs: loaded - initialized,
      stopMs: stoppedAt - loaded,
      totalMs: stoppedAt - started,
      cpuMs,
    };
  } finally {
    await client.stop();
  }
}

/**
 * CPU ms of every thread of a process so far (Linux /proc schedstat, in ns).
 * @param {number} pid
 */
function processCpuMs(pid) {
  let ns = 0;
  for (const thread of readdirSync(`/proc/${pid}/task`))
    ns += Number(readFileSync(`/proc/${pid}/task/${thread}/schedstat`, 'utf8').split(' ')[0]);
  return ns / 1e6;
}

async function launchFigures() {
  /** @type {Awaited<ReturnType<typeof firstLaunch>>[]} */
  const launches = [];
  for (let i = 0; i < runs; i++) launches.push(await firstLaunch());
  const [first, ...rest] = launches;
  const fmt = (/** @type {number} */ n) => n.toFixed(1).padStart(7);
  /** @param {(launch: typeof first) => number} pick */
  const later = (pick) => (rest.length > 0 ? fmt(median(rest.map(pick))) : '      -');
  console.log(`  F5 to the first stop (a breakpoint on ${launchEvent}, road ${path.basename(road)}), ms:  first  later (median)`);
  console.log(`    adapter started to its initialize response          ${fmt(first.startMs)}  ${later((launch) => launch.startMs)}`);
  console.log(`    launch to initialized (flatten, esmini's load)      ${fmt(first.loadMs)}  ${later((launch) => launch.loadMs)}`);
  console.log(`    configurationDone to stopped                        ${fmt(first.stopMs)}  ${later((launch) => launch.stopMs)}`);
  console.log(`    in all (wall)                                       ${fmt(first.totalMs)}  ${later((launch) => launch.totalMs)}`);
  console.log(`    CPU of the adapter's two processes until the stop   ${fmt(first.cpuMs)}  ${later((launch) => launch.cpuMs)}`);
}

try {
  console.log(`debugger benchmark: ${path.basename(scenario)}, step ${step} s, median of ${runs} runs each (node ${process.version})`);
  // First, so that its first launch is the first start of the adapter in this bench.
  await launchFigures();
  if (process.env.BENCH_DEBUG_LAUNCH_ONLY !== '1') {
    if (process.env.BENCH_DEBUG_LATENCY_ONLY !== '1') await speedAndBreakpointLatency();
    await pauseLatency();
  }
} finally {
  rmSync(folder, { recursive: true, force: true });
}

async function pauseLatency() {
  // A fifth of the step, so that the run lasts long enough (about 110,000 steps) for a pause to land in it.
  const pauseStep = step / 5;
  const alone = await debugRun(undefined, full, pauseStep);
  /** @type {number[]} */
  const pauses = [];
  for (let i = 0; i < runs; i++) {
    const paused = await pauseRun(50 + 20 * i, pauseStep);
    if (!(paused.pausedAt > 0) || paused.ended !== alone.ended)
      throw new Error(`paused at ${paused.pausedAt} s, ended at ${paused.ended} s; alone it ends at ${alone.ended} s`);
    pauses.push(paused.latencyMs);
  }
  const sortedPauses = [...pauses].sort((a, b) => a - b);
  console.log(
    `  pause latency, a pause request mid-run (step ${pauseStep} s) to the stopped event read by the client: median ${median(pauses).toFixed(2)} ms, max ${sortedPauses[sortedPauses.length - 1].toFixed(2)} ms (each run continued to ${alone.ended} s, as the run without a pause)`,
  );
}

async function speedAndBreakpointLatency() {
  /** @typedef {{ wall: number[], cpu: number[] }} Samples */
  /** @returns {Samples} */
  const samples = () => ({ wall: [], cpu: [] });
  const esminiFull = samples();
  const esminiLoad = samples();
  const debugRuns = samples();
  const debugEmpty = samples();
  /** @type {number[]} */
  const debugLoad = [];
  let esminiEnd = NaN;
  let debugEnd = NaN;
  // Interleaved, so that the machine's load weighs on both alike.
  for (let i = 0; i < runs; i++) {
    const run = esminiRun(full);
    esminiFull.wall.push(run.ms);
    esminiFull.cpu.push(run.cpuMs);
    esminiEnd = run.end;
    const load = esminiRun(loadOnly);
    esminiLoad.wall.push(load.ms);
    esminiLoad.cpu.push(load.cpuMs);
    const debug = await debugRun(undefined);
    debugLoad.push(debug.loadMs);
    debugRuns.wall.push(debug.runMs);
    debugRuns.cpu.push(debug.runCpuMs);
    debugEnd = debug.ended;
    const empty = await debugRun(undefined, loadOnly);
    debugEmpty.wall.push(empty.runMs);
    debugEmpty.cpu.push(empty.runCpuMs);
  }
  const conditionLine = text.split('\n').findIndex((line) => line.includes('<Condition name="CutInStartCondition"')) + 1;
  /** @type {number[]} */
  const latencies = [];
  for (let i = 0; i < runs; i++) latencies.push((await debugRun(conditionLine)).latencyMs);

  const esminiSteps = Math.round(esminiEnd / step);
  const debugSteps = Math.round(debugEnd / step);
  const fmt = (/** @type {number} */ n, digits = 1) => n.toFixed(digits).padStart(8);
  const rate = (/** @type {number} */ steps, /** @type {number} */ ms) => steps / (ms / 1000);
  console.log('                                                          wall ms     CPU ms');
  console.log(
    `  esmini --headless, whole run (${esminiSteps} steps to ${esminiEnd} s) ${fmt(median(esminiFull.wall))}   ${fmt(median(esminiFull.cpu))}`,
  );
  console.log(`  esmini --headless, start-up and load alone              ${fmt(median(esminiLoad.wall))}   ${fmt(median(esminiLoad.cpu))}`);
  const esminiWall = median(esminiFull.wall) - median(esminiLoad.wall);
  const esminiCpu = median(esminiFull.cpu) - median(esminiLoad.cpu);
  console.log(`  esmini stepping (the difference)                        ${fmt(esminiWall)}   ${fmt(esminiCpu)}`);
  console.log(`  debug adapter, launch to initialized (flatten, load)    ${fmt(median(debugLoad))}`);
  console.log(`  debug adapter, configurationDone to terminated          ${fmt(median(debugRuns.wall))}   ${fmt(median(debugRuns.cpu))}`);
  console.log(`  debug adapter, the same for the scenario ending at once ${fmt(median(debugEmpty.wall))}   ${fmt(median(debugEmpty.cpu))}`);
  const debugWall = median(debugRuns.wall) - median(debugEmpty.wall);
  const debugCpu = median(debugRuns.cpu) - median(debugEmpty.cpu);
  console.log(`  debugger stepping (the difference; ${debugSteps} steps to ${debugEnd} s) ${fmt(debugWall)}   ${fmt(debugCpu)}`);
  console.log(`    (no breakpoint hit; the CPU is the main thread's of the adapter's session process, which steps esmini)`);
  const wallRatio = rate(debugSteps, debugWall) / rate(esminiSteps, esminiWall);
  const cpuRatio = rate(debugSteps, debugCpu) / rate(esminiSteps, esminiCpu);
  console.log(
    `  steps/s: esmini ${fmt(rate(esminiSteps, esminiCpu), 0)} (CPU), ${fmt(rate(esminiSteps, esminiWall), 0)} (wall); debugger ${fmt(rate(debugSteps, debugCpu), 0)} (CPU), ${fmt(rate(debugSteps, debugWall), 0)} (wall)`,
  );
  console.log(
    `  ratio debugger / esmini steps per second: ${cpuRatio.toFixed(2)}x by CPU time, ${wallRatio.toFixed(2)}x by wall time (goal >= 0.8x): ${cpuRatio >= 0.8 ? 'within' : 'BELOW'}`,
  );
  const sorted = [...latencies].sort((a, b) => a - b);
  console.log(
    `  pause latency, CutInStartCondition firing (esmini's callback) to the stopped event read by the client: median ${median(latencies).toFixed(2)} ms, max ${sorted[sorted.length - 1].toFixed(2)} ms`,
  );
}
