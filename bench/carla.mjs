// `export --target carla` (issue 26): the largest esmini sample exported under 1.5x a bare `node` start (the
// issue's figure) and under 1.5x a flatten of the same file (the mapping's cost over reading the file); beside
// it, what ScenarioRunner's own loader (../shared/carla/check.py) takes for that one file.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { cpuMs, now, startServer, stats, uriOf } from './lspSession.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const shared = path.resolve(root, '..', 'shared');
const esmini = path.join(shared, 'corpus', 'openscenario', 'esmini');
const cli = path.join(root, 'dist', 'cli.js');
const peak = path.join(root, 'bench', 'peak-rss.cjs');
// CPU time beside wall time: on a machine shared with other work, wall time says more about the others.
const cpu = path.join(root, 'bench', 'cpu-time.cjs');
const runs = Number(process.env.BENCH_RUNS ?? 9);

/**
 * @param {string} command
 * @param {string[]} args
 */
function measure(command, args) {
  const started = process.hrtime.bigint();
  const result = spawnSync(command, args, { encoding: 'utf8', cwd: root });
  const ms = Number(process.hrtime.bigint() - started) / 1e6;
  if (result.status !== 0) throw new Error(`${command} ${args.join(' ')} failed (${result.status}): ${result.stderr}`);
  const kb = Number(/@@peak-rss-kb (\d+)/.exec(result.stderr)?.[1] ?? NaN);
  const cpuMs = Number(/@@cpu-ms (\d+)/.exec(result.stderr)?.[1] ?? NaN);
  return { ms, cpuMs, mb: kb / 1024, stdout: result.stdout };
}

/**
 * @param {{ ms: number, cpuMs: number }[]} samples
 * @param {'ms' | 'cpuMs'} field
 */
function median(samples, field = 'ms') {
  const times = samples.map((sample) => sample[field]).sort((a, b) => a - b);
  return times[Math.floor(times.length / 2)];
}

/** @param {number} n */
const fmt = (n) => n.toFixed(1).padStart(8);

if (!existsSync(cli)) {
  console.error('dist/cli.js is missing: run npm run build first');
  process.exit(1);
}
if (!existsSync(esmini)) {
  console.log(`(CARLA export benchmark skipped: ${esmini} is absent)`);
  process.exit(0);
}

const out = mkdtempSync(path.join(tmpdir(), 'm2s-bench-carla-'));
try {
  // parking_demo.xosc (1,113 lines) is the largest sample; its routes build in ScenarioRunner 0.9.15.
  const input = path.join(esmini, 'parking_demo.xosc');
  const output = path.join(out, 'parking_demo.xosc');
  const exportArgs = [
    ...['--require', peak, '--require', cpu, cli, 'export', input, '--target', 'carla', '--carla', '0.9.15', '-o', output, '-q'],
    ...['--road-path', path.join(shared, 'esmini', 'xodr'), '--scenario-path', path.join(esmini, 'Catalogs')],
  ];
  // flatten of the same file beside it: the export reads, models and checks it as flatten does, then maps and samples.
  const flattenArgs = [
    ...['--require', peak, '--require', cpu, cli, 'flatten', input, '-o', path.join(out, 'flat.xosc'), '-q'],
    ...['--scenario-path', path.join(esmini, 'Catalogs')],
  ];
  const bare = Array.from({ length: runs }, () => measure(process.execPath, ['--require', peak, '--require', cpu, '-e', '0']));
  const exported = [];
  const flattened = [];
  // Alternated, so that a change of the machine's load falls on both alike.
  for (let run = 0; run < runs; run++) {
    exported.push(measure(process.execPath, exportArgs));
    flattened.push(measure(process.execPath, flattenArgs));
  }
  console.log(`CARLA export benchmark (${runs} runs each; node ${process.version}; load average ${loadavg()[0].toFixed(1)})`);
  console.log('                                              median ms   CPU ms   peak MB');
  const row = (/** @type {string} */ label, /** @type {{ ms: number, cpuMs: number, mb: number }[]} */ samples) =>
    console.log(
      `  ${label.padEnd(43)}${fmt(median(samples))} ${fmt(median(samples, 'cpuMs'))}  ${fmt(Math.max(...samples.map((s) => s.mb)))}`,
    );
  row('node -e 0 (bare start)', bare);
  row('flatten, parking_demo.xosc', flattened);
  row('export --target carla, parking_demo.xosc', exported);
  const ratio = median(exported) / median(bare);
  const cpuRatio = median(exported, 'cpuMs') / median(bare, 'cpuMs');
  console.log(
    `  ratio export / bare start: ${ratio.toFixed(2)}x wall, ${cpuRatio.toFixed(2)}x CPU (target <= 1.5x: ${ratio <= 1.5 ? 'within' : 'OVER'})`,
  );
  const flattenRatio = median(exported, 'cpuMs') / median(flattened, 'cpuMs');
  console.log(
    `  ratio export / flatten of the same file: ${(median(exported) / median(flattened)).toFixed(2)}x wall, ${flattenRatio.toFixed(2)}x CPU (target <= 1.5x: ${flattenRatio <= 1.5 ? 'within' : 'OVER'})`,
  );
  // Export for CARLA… in the editor: the same export in the running language server, where no process starts.
  const server = path.join(root, 'dist', 'server.js');
  const session = await startServer(server, esmini, {
    scenarioPath: [path.join(esmini, 'Catalogs')],
    carla: { release: '0.9.15' },
    esmini: { roadPath: [path.join(shared, 'esmini', 'xodr')] },
  });
  try {
    const params = { uri: uriOf(input), outputPath: path.join(out, 'editor.xosc'), outsideWorkspace: true };
    /** @type {number[]} */
    const times = [];
    const cpuBefore = cpuMs(session.child.pid);
    // One export more than measured: the first loads the export's code into the server.
    for (let run = 0; run <= runs; run++) {
      const started = now();
      /** @type {{ written: string | null }} */
      const result = await session.connection.sendRequest('modular2simple/exportForCarla', params);
      if (!result.written) throw new Error(`the editor's export wrote nothing: ${JSON.stringify(result)}`);
      if (run > 0) times.push(now() - started);
    }
    const perExportCpu = (cpuMs(session.child.pid) - cpuBefore) / (runs + 1);
    const { median: editorMs, p95 } = stats(times);
    console.log(
      `  Export for CARLA… in the editor (the language server, after its first export): median ${editorMs.toFixed(1)} ms, p95 ${p95.toFixed(1)} ms, ` +
        `server CPU ${perExportCpu.toFixed(1)} ms an export (first included); ${(editorMs / median(bare)).toFixed(2)}x a bare start by wall`,
    );
  } finally {
    await session.stop();
  }
  const harness = path.join(shared, 'carla', 'check.py');
  if (existsSync(harness) && existsSync(path.join(root, '.cache', 'carla', 'scenario_runner'))) {
    const checked = measure('python3', [harness, '--fix-sr-bugs', output]);
    console.log(
      `  beside it, ScenarioRunner's loader on the export (check.py, one file): ${fmt(checked.ms)} ms, ${checked.stdout.split('\n')[0]}`,
    );
  } else console.log('  (the ScenarioRunner harness is not set up: python3 ../shared/carla/check.py setup)');
} finally {
  rmSync(out, { recursive: true, force: true });
}
