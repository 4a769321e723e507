import * as assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { addParameterControllers, addSumoControllerToEgo, roadParameterPackage, runCli } from '../support/fixtures';
import { cliPath, repoRoot } from '../support/paths';
import { freePort, RedisServer, requireRedis, startRedis } from '../support/redis';
import { waitUntil } from '../support/wait';
import { temporaryFolder } from '../support/temporaryDirectory';

const FIXTURES = path.join(repoRoot, 'test', 'fixtures', 'variations');

/** follow.xosc (runs of `stopTime` simulated seconds) and its 36-scenario distribution in a folder of their own. */
function batchFolder(stopTime: number): string {
  const folder = temporaryFolder('m2s-queue-');
  const scenario = fs
    .readFileSync(path.join(FIXTURES, 'follow.xosc'), 'utf8')
    .replace('name="StopTime" parameterType="double" value="3"', `name="StopTime" parameterType="double" value="${stopTime}"`);
  fs.writeFileSync(path.join(folder, 'follow.xosc'), scenario);
  fs.copyFileSync(path.join(FIXTURES, 'follow_distribution.xosc'), path.join(folder, 'd.xosc'));
  return folder;
}

/**
 * The shape of the ALKS logical scenarios: the distribution one folder above its ScenarioFile, the road a varied
 * parameter (filepath="$Road") naming files beside the scenario, a vehicle from a catalog folder of its own.
 * Six runs, stopped at 5 s by --duration (status limit), the fastest ego colliding before that.
 */
function alksShapedFolder(roads = ['./roads/e6mini.xodr', './roads/e6mini_copy.xodr']): string {
  const root = temporaryFolder('m2s-queue-alks-');
  const scenarios = path.join(root, 'scenarios');
  fs.mkdirSync(path.join(scenarios, 'roads'), { recursive: true });
  fs.mkdirSync(path.join(scenarios, 'catalogs', 'vehicles'), { recursive: true });
  for (const name of ['e6mini.xodr', 'e6mini_copy.xodr'])
    fs.copyFileSync(path.join(esminiRoads, 'e6mini.xodr'), path.join(scenarios, 'roads', name));
  const follow = fs.readFileSync(path.join(FIXTURES, 'follow.xosc'), 'utf8');
  const ego = /<Vehicle name="ego_car"[\s\S]*?<\/Vehicle>/.exec(follow)![0];
  fs.writeFileSync(
    path.join(scenarios, 'catalogs', 'vehicles', 'VehicleCatalog.xosc'),
    `<?xml version="1.0" encoding="UTF-8"?>\n<OpenSCENARIO>\n  <FileHeader revMajor="1" revMinor="2" date="2026-11-27T00:00:00" description="vehicles" author="modular2simple tests"/>\n  <Catalog name="VehicleCatalog">\n${ego}\n  </Catalog>\n</OpenSCENARIO>\n`,
  );
  const scenario = follow
    .replace('name="StopTime" parameterType="double" value="3"', 'name="StopTime" parameterType="double" value="40"')
    .replace(
      '<ParameterDeclarations>',
      '<ParameterDeclarations>\n    <ParameterDeclaration name="Road" parameterType="string" value="./roads/e6mini.xodr"/>',
    )
    .replace(
      '<CatalogLocations/>',
      '<CatalogLocations><VehicleCatalog><Directory path="./catalogs/vehicles"/></VehicleCatalog></CatalogLocations>',
    )
    .replace('<LogicFile filepath="e6mini.xodr"/>', '<LogicFile filepath="$Road"/>')
    .replace(ego, '<CatalogReference catalogName="VehicleCatalog" entryName="ego_car"/>');
  fs.writeFileSync(path.join(scenarios, 'follow.xosc'), scenario);
  fs.writeFileSync(
    path.join(root, 'd.xosc'),
    `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-27T00:00:00" description="road and ego speed" author="modular2simple tests"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath="./scenarios/follow.xosc"/>
    <Deterministic>
      <DeterministicSingleParameterDistribution parameterName="Road">
        <DistributionSet>${roads.map((road) => `<Element value="${road}"/>`).join('')}</DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="EgoSpeed">
        <DistributionSet><Element value="10"/><Element value="20"/><Element value="30"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
    </Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
`,
  );
  return root;
}

interface Background {
  kill(signal: NodeJS.Signals): void;
  output(): string;
  ended: Promise<{ code: number | null; signal: string | null; output: string }>;
}

function background(args: string[], cwd: string, env: NodeJS.ProcessEnv = {}): Background {
  const child = spawn(process.execPath, [cliPath, ...args], { cwd, env: { ...process.env, ...env }, stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  child.stdout.on('data', (chunk: Buffer) => (output += chunk.toString()));
  child.stderr.on('data', (chunk: Buffer) => (output += chunk.toString()));
  const ended = new Promise<{ code: number | null; signal: string | null; output: string }>((resolve) =>
    child.on('close', (code, signal) => resolve({ code, signal, output })),
  );
  return { kill: (signal) => child.kill(signal), output: () => output, ended };
}

/** A CLI call in the background, for a test that runs something else meanwhile: its exit code and all it printed. */
async function runCliAsync(args: string[], cwd: string): Promise<{ code: number | null; output: string }> {
  const ended = await background(args, cwd).ended;
  return { code: ended.code, output: ended.output };
}

/** results.csv's data lines in `folder`, sorted (the queue's rows come in the order the workers finish them). */
function sortedRows(folder: string): string[] {
  return fs.readFileSync(path.join(folder, 'results.csv'), 'utf8').split('\n').slice(1, -1).sort();
}

/** results.csv's data lines, checked to hold each of the 36 indices exactly once. */
function everyRowOnce(folder: string): string[] {
  const lines = fs.readFileSync(path.join(folder, 'results.csv'), 'utf8').split('\n');
  assert.equal(lines.pop(), '');
  const rows = lines.slice(1);
  assert.deepEqual(
    rows.map((row) => Number(row.split(',')[0])).sort((a, b) => a - b),
    Array.from({ length: 36 }, (_, i) => i),
  );
  return rows;
}

describe('cli: batch through a Redis queue', function () {
  this.timeout(240_000);
  let redis: RedisServer | undefined;
  const folders: string[] = [];
  const workers: Background[] = [];
  afterEach(async () => {
    // Told to stop, a worker removes what it keeps in the temporary directory; one that does not stop in time is killed.
    for (const worker of workers.splice(0)) {
      worker.kill('SIGTERM');
      const timer = setTimeout(() => worker.kill('SIGKILL'), 30_000);
      await worker.ended;
      clearTimeout(timer);
    }
    await redis?.stop();
    redis = undefined;
    for (const folder of folders.splice(0)) fs.rmSync(folder, { recursive: true, force: true });
  });

  it('three workers, one killed with SIGKILL mid-batch: every row exactly once, the same rows as a local batch', async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = batchFolder(8);
    folders.push(root);
    // The workers run in a folder of their own: what they run comes through Redis.
    const elsewhere = temporaryFolder('m2s-worker-');
    folders.push(elsewhere);
    // The one killed below cannot remove its own folder: it keeps it in one of the test's.
    for (let i = 0; i < 3; i++)
      workers.push(
        background(['worker', '--queue', redis.url, '--jobs', '1', '--esmini', esminiBinary], elsewhere, {
          ...(i === 2 ? { TMPDIR: temporaryFolder('m2s-killed-worker-') } : {}),
        }),
      );
    const batch = background(['batch', 'd.xosc', '--results', 'queued', '--queue', redis.url, '--road-path', esminiRoads], root);
    const victim = workers[2];
    await waitUntil(() => /: (ok|error|timeout)/.test(victim.output()), 'the third worker to finish a run', 120_000, 10);
    victim.kill('SIGKILL');
    assert.equal((await victim.ended).signal, 'SIGKILL');
    const ended = await batch.ended;
    assert.equal(ended.code, 0, ended.output);
    assert.match(ended.output, /^36 runs \(36 ok, 0 limit, 0 timeout, 0 error; \d+ with a collision\); results in /m);
    const queued = everyRowOnce(path.join(root, 'queued'));
    const json = JSON.parse(fs.readFileSync(path.join(root, 'queued', 'results.json'), 'utf8')) as { rows: { index: string }[] };
    assert.deepEqual(
      json.rows.map((row) => Number(row.index)),
      Array.from({ length: 36 }, (_, i) => i),
    );
    // Runs repeat exactly (fixed step and seed), so the queue's rows are the local pool's, in another order.
    const local = runCli(['batch', 'd.xosc', '--results', 'local', '--jobs', '2', '--road-path', esminiRoads, '--esmini', esminiBinary], {
      cwd: root,
    });
    assert.equal(local.status, 0, local.stderr);
    assert.deepEqual([...queued].sort(), [...everyRowOnce(path.join(root, 'local'))].sort());
    for (const worker of workers.slice(0, 2)) worker.kill('SIGTERM');
    for (const worker of workers.slice(0, 2)) assert.equal((await worker.ended).code, 0);
  });

  it('the ALKS shape (road a varied parameter, catalogs beside the scenario): three workers each in an empty folder, one killed, give the local rows, status included', async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = alksShapedFolder();
    folders.push(root);
    for (let i = 0; i < 3; i++) {
      // Each in an empty folder of its own, as on machines that share no disk: what a run needs comes through Redis.
      const empty = temporaryFolder('m2s-worker-');
      folders.push(empty);
      workers.push(
        background(['worker', '--queue', redis.url, '--jobs', '1', '--esmini', esminiBinary], empty, {
          ...(i === 2 ? { TMPDIR: temporaryFolder('m2s-killed-worker-') } : {}),
        }),
      );
    }
    const args = ['batch', 'd.xosc', '--duration', '5', '--esmini', esminiBinary];
    const batch = background([...args, '--results', 'queued', '--queue', redis.url], root);
    const victim = workers[2];
    await waitUntil(() => /: (ok|limit|error|timeout)/.test(victim.output()), 'the third worker to finish a run', 120_000, 10);
    victim.kill('SIGKILL');
    const ended = await batch.ended;
    assert.equal(ended.code, 0, ended.output);
    const local = runCli([...args, '--results', 'local', '--jobs', '2'], { cwd: root });
    assert.equal(local.status, 0, local.stderr);
    const rowsOf = (folder: string) => sortedRows(path.join(root, folder));
    const localRows = rowsOf('local');
    assert.equal(localRows.length, 6);
    // Every run found its road and its catalog: stopped at the limit, the fastest ego after hitting the lead.
    for (const row of localRows) assert.match(row, /^\d,limit,(true|false),[\d.]+,[\d.]*,5\.000,\.\/roads\/e6mini(_copy)?\.xodr,/);
    assert.ok(localRows.some((row) => row.split(',')[2] === 'true'));
    assert.deepEqual(rowsOf('queued'), localRows);
  });

  it("runs esmini refuses (a varied road that is not there) come back from a worker in an empty folder as error with esmini's reason, as locally; exit 3 naming it", async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = alksShapedFolder(['./roads/e6mini.xodr', './roads/gone.xodr']);
    folders.push(root);
    const empty = temporaryFolder('m2s-worker-');
    folders.push(empty);
    workers.push(background(['worker', '--queue', redis.url, '--jobs', '2', '--esmini', esminiBinary], empty));
    const args = ['batch', 'd.xosc', '--duration', '5', '--esmini', esminiBinary];
    const queued = runCliAsync([...args, '--results', 'queued', '--queue', redis.url], root);
    const local = runCli([...args, '--results', 'local', '--jobs', '2'], { cwd: root });
    const ended = await queued;
    for (const [name, batch] of [
      ['queued', ended],
      ['local', { code: local.status, output: local.stderr }],
    ] as const) {
      assert.equal(batch.code, 3, `${name}: ${batch.output}`);
      assert.match(batch.output, /^6 runs \(0 ok, 3 limit, 0 timeout, 3 error; /m, `${name}: ${batch.output}`);
      assert.match(
        batch.output,
        new RegExp(
          `^modular2simple: error: 3 of 6 runs failed in esmini \\(status error\\); the column reason of .*${name}.results\\.csv says why for each:\\n  #3, #4, #5: esmini did not run the scenario \\(exit code 255\\): Failed to locate OpenDRIVE file \\./roads/gone\\.xodr$`,
          'm',
        ),
        `${name}: ${batch.output}`,
      );
    }
    const rowsOf = (folder: string) => sortedRows(path.join(root, folder));
    const localRows = rowsOf('local');
    assert.deepEqual(
      localRows.filter((row) => row.includes('gone.xodr')),
      ['10', '20', '30'].map(
        (speed, i) =>
          `${i + 3},error,false,,,,./roads/gone.xodr,${speed},esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file ./roads/gone.xodr`,
      ),
    );
    assert.deepEqual(rowsOf('queued'), localRows, 'the same rows, status and reason included');
  });

  it("a worker's rows name the user's files, not the worker's private folders: the reason and messages as a local batch gives them (issue 27)", async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = batchFolder(3);
    folders.push(root);
    addSumoControllerToEgo(path.join(root, 'follow.xosc'));
    const empty = temporaryFolder('m2s-worker-');
    folders.push(empty);
    workers.push(background(['worker', '--queue', redis.url, '--jobs', '2', '--esmini', esminiBinary], empty));
    const args = ['batch', 'd.xosc', '--sample', '2', '--road-path', esminiRoads, '--esmini', esminiBinary];
    const queued = await runCliAsync([...args, '--results', 'queued', '--queue', redis.url], root);
    assert.equal(queued.code, 3, queued.output);
    const local = runCli([...args, '--results', 'local'], { cwd: root });
    assert.equal(local.status, 3, local.stderr);
    const tried = path.join(path.dirname(root), 'sumo_inputs', 'e6mini.sumocfg');
    const rows = sortedRows(path.join(root, 'queued'));
    assert.equal(rows.length, 2);
    for (const row of rows)
      assert.ok(row.includes(`Failed to localize controller file ../sumo_inputs/e6mini.sumocfg, also tried ${tried}"`), row);
    assert.deepEqual(rows, sortedRows(path.join(root, 'local')), 'the same rows, reason included');
    const messagesOf = (folder: string) =>
      (JSON.parse(fs.readFileSync(path.join(root, folder, 'results.json'), 'utf8')) as { rows: { messages: unknown }[] }).rows.map(
        (row) => row.messages,
      );
    assert.deepEqual(messagesOf('queued'), messagesOf('local'));
    assert.doesNotMatch(
      queued.output + fs.readFileSync(path.join(root, 'queued', 'results.json'), 'utf8'),
      /modular2simple-worker|job-|esmini-run-/,
    );
  });

  it("a controller's File named through a parameter, inline or in a catalog entry, or written as it stands in an entry, is sent with the job: a worker in an empty folder runs it as a local batch does (issue 27)", async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = batchFolder(3);
    folders.push(root);
    addParameterControllers(root);
    // A second entry writes its File as it stands, which no assignment reaches: the run writes that entry inline (issue 27).
    const catalog = path.join(root, 'catalogs', 'ControllerCatalog.xosc');
    fs.writeFileSync(
      catalog,
      fs
        .readFileSync(catalog, 'utf8')
        .replace(
          '</Catalog>',
          '<Controller name="literal"><Properties><Property name="esminiController" value="ACCController"/><File filepath="inputs/literal.cfg"/></Properties></Controller></Catalog>',
        ),
    );
    fs.writeFileSync(path.join(root, 'inputs', 'literal.cfg'), '');
    const scenario = path.join(root, 'follow.xosc');
    fs.writeFileSync(scenario, fs.readFileSync(scenario, 'utf8').replace('entryName="lead"', 'entryName="literal"'));
    const empty = temporaryFolder('m2s-worker-');
    folders.push(empty);
    workers.push(background(['worker', '--queue', redis.url, '--jobs', '2', '--esmini', esminiBinary], empty));
    const args = ['batch', 'd.xosc', '--sample', '2', '--road-path', esminiRoads, '--esmini', esminiBinary];
    const queued = await runCliAsync([...args, '--results', 'queued', '--queue', redis.url], root);
    assert.equal(queued.code, 0, queued.output);
    const local = runCli([...args, '--results', 'local'], { cwd: root });
    assert.equal(local.status, 0, local.stderr);
    const rows = sortedRows(path.join(root, 'queued'));
    assert.equal(rows.length, 2);
    for (const row of rows) assert.equal(row.split(',')[1], 'ok', row);
    assert.deepEqual(rows, sortedRows(path.join(root, 'local')), 'the same rows, status included');
  });

  it('a package holding two roads, its $Road varied over both: a worker in an empty folder runs each on its own road, as locally', async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = temporaryFolder('m2s-queue-package-');
    folders.push(root);
    const roads = ['straight_500m.xodr', 'straight_500m_signs.xodr'];
    await roadParameterPackage(
      root,
      Object.fromEntries(roads.map((name) => [name, fs.readFileSync(path.join(esminiRoads, name))])),
      'Road',
      roads,
    );
    const empty = temporaryFolder('m2s-worker-');
    folders.push(empty);
    workers.push(background(['worker', '--queue', redis.url, '--jobs', '2', '--esmini', esminiBinary], empty));
    const queued = await runCliAsync(['batch', 'speeds.xosc', '--esmini', esminiBinary, '--results', 'queued', '--queue', redis.url], root);
    assert.equal(queued.code, 0, queued.output);
    const expected = ['0,ok,false,,,8.050,straight_500m.xodr,', '1,ok,false,,,8.050,straight_500m_signs.xodr,'];
    assert.deepEqual(sortedRows(path.join(root, 'queued')), expected);
    const local = runCli(['batch', 'speeds.xosc', '--esmini', esminiBinary, '--results', 'local'], { cwd: root });
    assert.equal(local.status, 0, local.stderr);
    assert.deepEqual(sortedRows(path.join(root, 'local')), expected);
  });

  it('a batch interrupted while the workers run collects the rest when run again, nothing twice', async function () {
    requireEsmini(this);
    requireRedis(this);
    redis = await startRedis();
    const root = batchFolder(8);
    folders.push(root);
    const args = ['batch', 'd.xosc', '--results', 'queued', '--queue', redis.url, '--road-path', esminiRoads];
    const first = background(args, root);
    workers.push(background(['worker', '--queue', redis.url, '--jobs', '2', '--esmini', esminiBinary], root));
    await waitUntil(() => /\[3\/36\]/.test(first.output()), 'three rows', 120_000, 10);
    first.kill('SIGINT');
    const stopped = await first.ended;
    assert.equal(stopped.code, 130, stopped.output);
    assert.match(stopped.output, /the rest stay on the queue: run the same command again/);
    const again = runCli(args, { cwd: root });
    assert.equal(again.status, 0, again.stderr);
    everyRowOnce(path.join(root, 'queued'));
  });

  it('a worker that stops leaves nothing in the temporary directory, the shared parent of workers included', async function () {
    requireRedis(this);
    redis = await startRedis();
    const tmp = temporaryFolder('m2s-worker-tmpdir-');
    const worker = background(['worker', '--queue', redis.url, '--idle-exit', '1', '--esmini', process.execPath], repoRoot, {
      TMPDIR: tmp,
    });
    const ended = await worker.ended;
    assert.equal(ended.code, 0, ended.output);
    assert.deepEqual(fs.readdirSync(tmp), []);
  });

  it('Redis unreachable: a clear message, exit 3, nothing written; a worker likewise', async () => {
    const root = batchFolder(3);
    folders.push(root);
    const port = await freePort();
    const batch = runCli(['batch', 'd.xosc', '--results', 'queued', '--queue', `redis://127.0.0.1:${port}`], { cwd: root });
    assert.equal(batch.status, 3, batch.stderr);
    assert.match(
      batch.stderr,
      new RegExp(
        `^modular2simple: error: cannot reach Redis at redis://127\\.0\\.0\\.1:${port}: connect ECONNREFUSED .*; nothing was written$`,
        'm',
      ),
    );
    assert.ok(!fs.existsSync(path.join(root, 'queued')));
    const worker = runCli(['worker', '--queue', `redis://127.0.0.1:${port}`, '--esmini', process.execPath]);
    assert.equal(worker.status, 3, worker.stderr);
    assert.match(worker.stderr, /cannot reach Redis at/);
    assert.equal(runCli(['worker']).status, 2);
    assert.equal(runCli(['worker', '--queue', 'localhost:6379']).status, 2);
  });
});
