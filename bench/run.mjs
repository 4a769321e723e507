// Benchmarks that print figures (not timed tests): the CLI against the original tool's cost (SPEC 10),
// then the language server (bench/lsp.mjs) when present.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const library = path.resolve(root, '..', 'shared', 'corpus', 'modular2simple', 'library');
const cli = path.join(root, 'dist', 'cli.js');
const peak = path.join(root, 'bench', 'peak-rss.cjs');
const runs = Number(process.env.BENCH_RUNS ?? 15);

/**
 * @param {string[]} args
 * @param {Record<string, string>} [env]
 */
function measure(args, env = {}) {
  const started = process.hrtime.bigint();
  const result = spawnSync(process.execPath, ['--require', peak, ...args], { env: { ...process.env, ...env }, encoding: 'utf8' });
  const ms = Number(process.hrtime.bigint() - started) / 1e6;
  if (result.status !== 0) throw new Error(`${args.join(' ')} failed: ${result.stderr}`);
  const kb = Number(/@@peak-rss-kb (\d+)/.exec(result.stderr)?.[1] ?? NaN);
  return { ms, mb: kb / 1024 };
}

/** @param {{ ms: number, mb: number }[]} samples */
function summary(samples) {
  const times = samples.map((s) => s.ms).sort((a, b) => a - b);
  const median = times[Math.floor(times.length / 2)];
  const p95 = times[Math.min(times.length - 1, Math.ceil(times.length * 0.95) - 1)];
  return { median, p95, peakMb: Math.max(...samples.map((s) => s.mb)) };
}

/** @param {number} n */
const fmt = (n) => n.toFixed(1).padStart(7);

if (!existsSync(cli)) {
  console.error('dist/cli.js is missing: run npm run build first');
  process.exit(1);
}
if (!existsSync(library)) {
  console.log(`(core benchmark skipped: ${library} is absent)`);
} else {
  const out = mkdtempSync(path.join(tmpdir(), 'm2s-bench-'));
  const largest = path.join(library, 'modular_hero_right_left_front_back_pedestrian', 'result.mosc');
  const env = { SCENARIO_PATH: library };
  const bare = summary(Array.from({ length: runs }, () => measure(['-e', '0'])));
  const one = summary(Array.from({ length: runs }, () => measure([cli, '-cmx', largest, path.join(out, 'largest.xosc'), '-q'], env)));
  const inputs = readdirSync(library)
    .filter((n) => n.startsWith('modular_'))
    .map((n) => path.join(library, n, 'result.mosc'));
  const all = summary(
    Array.from({ length: Math.max(5, Math.floor(runs / 3)) }, () => {
      rmSync(out, { recursive: true, force: true });
      spawnSync('mkdir', ['-p', out]);
      return measure([cli, 'flatten', ...inputs, '--out-dir', out, '-q'], env);
    }),
  );
  rmSync(out, { recursive: true, force: true });
  console.log(`core/CLI benchmark (${runs} runs each; node ${process.version}; ${process.arch})`);
  console.log('                                           median ms   p95 ms   peak MB');
  console.log(`  node -e 0 (bare start)                    ${fmt(bare.median)}  ${fmt(bare.p95)}  ${fmt(bare.peakMb)}`);
  console.log(`  flatten largest example (1,172 lines)     ${fmt(one.median)}  ${fmt(one.p95)}  ${fmt(one.peakMb)}`);
  console.log(`  flatten all ${inputs.length} examples, one run         ${fmt(all.median)}  ${fmt(all.p95)}  ${fmt(all.peakMb)}`);
  console.log(`  ratio largest / bare start: ${(one.median / bare.median).toFixed(2)}x (target <= 2x); original tool: 700 ms, 75 MB`);
  console.log(
    `  all ${inputs.length}: ${all.median < 500 ? 'within' : 'OVER'} the 500 ms target; peak memory ${Math.max(one.peakMb, all.peakMb) < 100 ? 'within' : 'OVER'} 100 MB`,
  );
}

// BENCH_CLI_ONLY=1: the CLI's figures alone (its start-up is measured without the rest's minutes).
if (process.env.BENCH_CLI_ONLY === '1') process.exit();

console.log('');
spawnSync(process.execPath, [path.join(root, 'bench', 'semantics.mjs')], { stdio: 'inherit' });

for (const name of [
  'lsp.mjs',
  'format.mjs',
  'esmini.mjs',
  'modularize.mjs',
  'variations.mjs',
  'check.mjs',
  'refactorings.mjs',
  'carla.mjs',
  'debugger.mjs',
]) {
  const bench = path.join(root, 'bench', name);
  if (!existsSync(bench)) continue;
  console.log('');
  const result = spawnSync(process.execPath, [bench], { stdio: 'inherit' });
  if (result.status !== 0) process.exitCode = result.status ?? 1;
}

const editorBench = path.join(root, 'bench', 'editorFeatures.mjs');
if (existsSync(editorBench)) {
  console.log('');
  const result = spawnSync(process.execPath, [editorBench], { stdio: 'inherit' });
  if (result.status !== 0) process.exitCode = result.status ?? 1;
}

for (const name of ['modularizeLibraries.ts', 'birdsEye.ts']) {
  const bench = path.join(root, 'bench', name);
  if (!existsSync(bench)) continue;
  console.log('');
  // tsx's compile cache would stay in the temporary directory (tsx-UID) after the benchmark: run without it, as the tests do.
  const result = spawnSync(process.execPath, ['--import', 'tsx', bench], {
    stdio: 'inherit',
    cwd: root,
    env: { ...process.env, TSX_DISABLE_CACHE: '1' },
  });
  if (result.status !== 0) process.exitCode = result.status ?? 1;
}

// The largest input each bound lets through or stops; BENCH_HOSTILE=0 leaves it out (it takes minutes).
if (process.env.BENCH_HOSTILE !== '0') {
  console.log('');
  const result = spawnSync(process.execPath, [path.join(root, 'bench', 'hostile.mjs')], { stdio: 'inherit' });
  if (result.status !== 0) process.exitCode = result.status ?? 1;
}
