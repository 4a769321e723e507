// `check` over a library (issue 18 item 5): the 101 real corpus files under one second in all, and a
// folder of 1,000 files within 1.5x the peak memory of a one-file check (a folder check holds one
// file's trees at a time). Peak memory is measured as bench/run.mjs measures it (bench/peak-rss.cjs).
import { spawnSync } from 'node:child_process';
import { copyFileSync, cpSync, existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const corpus = path.resolve(root, '..', 'shared', 'corpus', 'openscenario');
const cli = path.join(root, 'dist', 'cli.js');
const peak = path.join(root, 'bench', 'peak-rss.cjs');
const cpuTime = path.join(root, 'bench', 'cpu-time.cjs');
const liveHeap = path.join(root, 'bench', 'live-heap.cjs');
const runs = Number(process.env.BENCH_RUNS ?? 5);

/**
 * Wall ms, CPU ms and peak MB of one `check` (exit 0 or 1: problems found are not a failure here).
 * @param {string[]} args
 * @param {boolean} [live] the live heap at the end instead of the peak
 */
function measure(args, live = false) {
  const started = process.hrtime.bigint();
  const preload = live
    ? ['--expose-gc', '--require', liveHeap]
    : ['--require', peak, ...(existsSync(cpuTime) ? ['--require', cpuTime] : [])];
  const result = spawnSync(process.execPath, [...preload, cli, 'check', '-q', ...args], { encoding: 'utf8', maxBuffer: 1 << 28 });
  const ms = Number(process.hrtime.bigint() - started) / 1e6;
  if (result.status !== 0 && result.status !== 1) throw new Error(`check ${args.join(' ')} failed (${result.status}): ${result.stderr}`);
  const kb = Number(/@@peak-rss-kb (\d+)/.exec(result.stderr)?.[1] ?? NaN);
  const cpu = Number(/@@cpu-ms (\d+(?:\.\d+)?)/.exec(result.stderr)?.[1] ?? NaN);
  const liveMb = Number(/@@live-heap-mb (\d+(?:\.\d+)?)/.exec(result.stderr)?.[1] ?? NaN);
  return { ms, cpu, mb: kb / 1024, liveMb };
}

/**
 * @param {Record<string, number>[]} samples
 * @param {string} key
 */
function median(samples, key) {
  const values = samples.map((sample) => sample[key]).sort((a, b) => a - b);
  return values[Math.floor(values.length / 2)];
}

/**
 * @param {string} folder
 * @returns {string[]}
 */
function scenarioFiles(folder) {
  const found = [];
  for (const entry of readdirSync(folder, { withFileTypes: true })) {
    const full = path.join(folder, entry.name);
    if (entry.isDirectory()) found.push(...scenarioFiles(full));
    else if (entry.name.endsWith('.xosc')) found.push(full);
  }
  return found;
}

/** @param {number} n */
const fmt = (n) => n.toFixed(1).padStart(8);

if (!existsSync(cli)) {
  console.error('dist/cli.js is missing: run npm run build first');
  process.exit(1);
}
if (!existsSync(corpus)) {
  console.log(`(check benchmark skipped: ${corpus} is absent)`);
  process.exit(0);
}

const files = scenarioFiles(corpus);
const largest = files.reduce((best, file) => (statSync(file).size > statSync(best).size ? file : best));
// About 1,000 files, as a library holds them: the corpus with each scenario copied beside itself under
// other names, all sharing the corpus's catalogs and road files (catalog files are not copied).
const library = mkdtempSync(path.join(tmpdir(), 'm2s-bench-check-'));
cpSync(corpus, library, { recursive: true });
const scenarios = scenarioFiles(library).filter((file) => !/<Catalog[\s>]/.test(readFileSync(file, 'utf8')));
const copies = Math.max(1, Math.round((1000 - (files.length - scenarios.length)) / scenarios.length));
for (const file of scenarios) for (let copy = 1; copy < copies; copy++) copyFileSync(file, file.replace(/\.xosc$/, `.copy${copy}.xosc`));
const libraryCount = scenarioFiles(library).length;

const corpusRuns = Array.from({ length: runs }, () => measure([corpus]));
const oneRuns = Array.from({ length: runs }, () => measure([largest]));
const libraryRuns = Array.from({ length: Math.max(3, Math.floor(runs / 2)) }, () => measure([library]));
// What stays reachable once all is checked: the trees of the files checked before must not.
const oneLive = measure([largest], true).liveMb;
const libraryLive = measure([library], true).liveMb;
rmSync(library, { recursive: true, force: true });

const corpusMs = median(corpusRuns, 'ms');
const oneMb = median(oneRuns, 'mb');
const libraryMb = median(libraryRuns, 'mb');
console.log(`check benchmark (${runs} runs each; node ${process.version}; ${process.arch})`);
console.log('                                             median ms   CPU ms   peak MB');
console.log(
  `  check the ${files.length} corpus files, one run         ${fmt(corpusMs)} ${fmt(median(corpusRuns, 'cpu'))} ${fmt(median(corpusRuns, 'mb'))}`,
);
console.log(
  `  check one file (${path.basename(largest)})`.padEnd(47) + `${fmt(median(oneRuns, 'ms'))} ${fmt(median(oneRuns, 'cpu'))} ${fmt(oneMb)}`,
);
console.log(
  `  check a folder of ${libraryCount} files`.padEnd(47) +
    `${fmt(median(libraryRuns, 'ms'))} ${fmt(median(libraryRuns, 'cpu'))} ${fmt(libraryMb)}`,
);
console.log(`  ${files.length} corpus files: ${corpusMs < 1000 ? 'within' : 'OVER'} the 1 s target`);
console.log(
  `  folder peak / one-file peak: ${(libraryMb / oneMb).toFixed(2)}x (${libraryMb / oneMb <= 1.5 ? 'within' : 'OVER'} the 1.5x target)`,
);
console.log(
  `  heap still reachable at the end (after a full collection): one file ${oneLive.toFixed(1)} MB, the folder ${libraryLive.toFixed(1)} MB`,
);
