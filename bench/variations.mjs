// Batch benchmark (figures, not a timed test): concrete scenarios per second per core on a 500-run sample of a
// 50,344-scenario distribution, against esmini run alone on the same concrete scenarios (the project's
// overhead per run: target under 10 %), and two workers through Redis against one (target at least 1.8x).
import { spawn, spawnSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { cpus, loadavg, tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const cli = path.join(root, 'dist', 'cli.js');
const esmini = path.join(root, '.cache', 'esmini', 'bin', 'esmini');
const roads = path.resolve(root, '..', 'shared', 'esmini', 'xodr');
const sample = Number(process.env.BENCH_VARIATIONS_SAMPLE ?? 500);
const queueSample = Number(process.env.BENCH_QUEUE_SAMPLE ?? 300);
const jobs = Number(process.env.BENCH_JOBS ?? cpus().length);
const now = () => Number(process.hrtime.bigint()) / 1e6;

if (!existsSync(esmini) || !existsSync(cli)) {
  console.log(`(batch benchmark skipped: ${existsSync(cli) ? esmini : cli} is absent)`);
  process.exit(0);
}

/** CPU seconds of this process's finished children and theirs (Linux): a figure the machine's load does not change. */
function childrenCpuSeconds() {
  if (!existsSync('/proc/self/stat')) return NaN;
  const fields = readFileSync('/proc/self/stat', 'utf8').split(') ')[1].split(' ');
  return (Number(fields[13]) + Number(fields[14])) / 100;
}

const folder = mkdtempSync(path.join(tmpdir(), 'm2s-bench-variations-'));
copyFileSync(path.join(root, 'test', 'fixtures', 'variations', 'follow.xosc'), path.join(folder, 'follow.xosc'));
copyFileSync(path.join(roads, 'e6mini.xodr'), path.join(folder, 'e6mini.xodr'));
/**
 * @param {string} name
 * @param {number} lower
 * @param {number} upper
 * @param {number} step
 */
const range = (name, lower, upper, step) =>
  `<DeterministicSingleParameterDistribution parameterName="${name}"><DistributionRange stepWidth="${step}"><Range lowerLimit="${lower}" upperLimit="${upper}"/></DistributionRange></DeterministicSingleParameterDistribution>`;
writeFileSync(
  path.join(folder, 'large.xosc'),
  `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-24T00:00:00" description="bench" author="m2s"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath="follow.xosc"/>
    <Deterministic>${range('EgoSpeed', 5, 60, 1)}${range('LeadSpeed', 0, 30, 1)}${range('LeadStartS', 60, 200, 5)}</Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
`,
);
const count = spawnSync(process.execPath, [cli, 'vary', 'large.xosc', '--count'], { cwd: folder, encoding: 'utf8' }).stdout.trim();

/**
 * Runs a command to its end; its wall-clock milliseconds and the CPU seconds it and its children used.
 * @param {string} program
 * @param {string[]} args
 * @param {import('node:child_process').SpawnSyncOptions} [options]
 */
function timed(program, args, options = {}) {
  const cpuBefore = childrenCpuSeconds();
  const started = now();
  const result = spawnSync(program, args, { cwd: folder, encoding: 'utf8', ...options });
  const wallMs = now() - started;
  if (result.status !== 0) throw new Error(`${program} ${args.join(' ')} failed (${result.status}): ${result.stderr}`);
  return { wallMs, cpu: childrenCpuSeconds() - cpuBefore };
}

// esmini alone: the same concrete scenarios (vary writes them), the same options, `jobs` at a time.
const concrete = path.join(folder, 'concrete');
spawnSync(process.execPath, [cli, 'vary', 'large.xosc', '--out-dir', concrete, '--sample', String(sample), '--seed', '1', '-q'], {
  cwd: folder,
});
const files = readdirSync(concrete).map((name) => path.join(concrete, name));
const alone = await (async () => {
  const cpuBefore = childrenCpuSeconds();
  const started = now();
  let next = 0;
  const lane = async () => {
    while (next < files.length) {
      const file = files[next++];
      const csv = `${file}.csv`;
      await new Promise((resolve, reject) => {
        const child = spawn(
          esmini,
          [
            '--headless',
            '--osc',
            file,
            '--fixed_timestep',
            '0.05',
            '--seed',
            '1',
            '--csv_logger',
            csv,
            '--disable_log',
            '--collision',
            '--path',
            folder,
          ],
          { stdio: 'ignore' },
        );
        child.on('error', reject);
        child.on('close', resolve);
      });
      readFileSync(csv);
    }
  };
  await Promise.all(Array.from({ length: jobs }, lane));
  return { wallMs: now() - started, cpu: childrenCpuSeconds() - cpuBefore };
})();
const batch = timed(process.execPath, [
  cli,
  'batch',
  'large.xosc',
  '--results',
  path.join(folder, 'results'),
  '--sample',
  String(sample),
  '--seed',
  '1',
  '--jobs',
  String(jobs),
  '--esmini',
  esmini,
  '-q',
]);
const rows =
  readFileSync(path.join(folder, 'results', 'results.csv'), 'utf8')
    .trim()
    .split('\n').length - 1;

/** @param {{ wallMs: number }} result */
const perCore = (result) => sample / (result.wallMs / 1000) / jobs;
/**
 * @param {number} n
 * @param {number} [digits]
 */
const fmt = (n, digits = 1) => n.toFixed(digits).padStart(8);
console.log(
  `Batch benchmark: a ${sample}-run sample of ${count} concrete scenarios (follow.xosc on e6mini, 3 s simulated at 0.05 s steps), ${jobs} at a time`,
);
console.log('                                                 runs/s/core   CPU ms/run   wall s');
console.log(
  `  esmini alone on the concrete scenarios          ${fmt(perCore(alone))}     ${fmt((alone.cpu * 1000) / sample)}   ${fmt(alone.wallMs / 1000)}`,
);
console.log(
  `  modular2simple batch (${rows} rows)               ${fmt(perCore(batch))}     ${fmt((batch.cpu * 1000) / sample)}   ${fmt(batch.wallMs / 1000)}`,
);
const cpuOverhead = (batch.cpu / alone.cpu - 1) * 100;
const wallOverhead = (batch.wallMs / alone.wallMs - 1) * 100;
console.log(
  `  overhead per run: ${cpuOverhead.toFixed(1)} % of CPU, ${wallOverhead.toFixed(1)} % of wall-clock time (target < 10 %): ${cpuOverhead < 10 ? 'within' : 'OVER'}`,
);
console.log(`  (the machine's load: ${loadavg()[0].toFixed(1)} on ${cpus().length} cores)`);

// Through Redis: one worker, then two, each running one scenario at a time.
if (spawnSync('redis-server', ['--version']).status !== 0) {
  console.log('  (queue benchmark skipped: redis-server is not installed)');
} else {
  const port = 20000 + Math.floor(Math.random() * 20000);
  const redis = spawn(
    'redis-server',
    ['--port', String(port), '--bind', '127.0.0.1', '--save', '', '--appendonly', 'no', '--dir', folder],
    { stdio: 'ignore' },
  );
  const url = `redis://127.0.0.1:${port}`;
  for (let i = 0; i < 100 && spawnSync('redis-cli', ['-p', String(port), 'ping'], { encoding: 'utf8' }).stdout.trim() !== 'PONG'; i++)
    spawnSync('sleep', ['0.05']);
  /** @param {number} workers */
  const throughQueue = async (workers) => {
    const cpuBefore = childrenCpuSeconds();
    const started = [];
    for (let i = 0; i < workers; i++)
      started.push(
        spawn(process.execPath, [cli, 'worker', '--queue', url, '--jobs', '1', '--esmini', esmini, '--idle-exit', '1', '-q'], {
          stdio: 'ignore',
        }),
      );
    const ended = started.map((child) => new Promise((resolve) => child.on('close', resolve)));
    const run = timed(process.execPath, [
      cli,
      'batch',
      'large.xosc',
      '--results',
      path.join(folder, `queued-${workers}`),
      '--sample',
      String(queueSample),
      '--seed',
      '2',
      '--queue',
      url,
      '-q',
    ]);
    await Promise.all(ended);
    return { ...run, cpu: childrenCpuSeconds() - cpuBefore };
  };
  const one = await throughQueue(1);
  const two = await throughQueue(2);
  redis.kill('SIGTERM');
  console.log(
    `  through Redis, ${queueSample} runs: one worker ${fmt(one.wallMs / 1000)} s, two workers ${fmt(two.wallMs / 1000)} s: ${(one.wallMs / two.wallMs).toFixed(2)}x (target >= 1.8x on two free cores)`,
  );
  console.log(
    `    CPU ms per run, batch and workers together: one worker ${fmt((one.cpu * 1000) / queueSample)}, two ${fmt((two.cpu * 1000) / queueSample)} (esmini alone ${fmt((alone.cpu * 1000) / sample)})`,
  );
  console.log(
    `    (the machine's load: ${loadavg()[0].toFixed(1)} on ${cpus().length} cores; with fewer free cores than workers the ratio says more about the load than the queue)`,
  );
}
rmSync(folder, { recursive: true, force: true });
