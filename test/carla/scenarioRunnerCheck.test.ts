import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { runHarness } from '../../server/src/carla/harness';
import { main } from '../../server/src/cli';
import { CARLA_TOWNS } from '../../server/src/core/export/carla';
import { CheckInScenarioRunnerRequest } from '../../common/src/protocol';
import { fileUri, TestClient } from '../server/harness';
import { harnessVerdicts, lineMatching, requireCarlaHarness, scenarioRunnerFolder, scenarioRunnerPython } from '../support/carla';
import { esminiRoads } from '../support/esmini';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { libraryDir, repoRoot, requireCorpus } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';
import { SERVER_WAIT_MS, waitUntil } from '../support/wait';
import { temporaryWorkspace } from '../support/workspace';

/** esmini's samples exported as the CLI exports them (the written ones) and as they are (1.1-1.3: all refused). */
async function exportedSamples(names: string[], out: string): Promise<string[]> {
  const esmini = path.join(openscenarioDir, 'esmini');
  const written: string[] = [];
  for (const name of names) {
    const output = path.join(out, name);
    const code = await main(
      [
        'export',
        path.join(esmini, name),
        '--target',
        'carla',
        '-o',
        output,
        '--road-path',
        esminiRoads,
        '--scenario-path',
        path.join(esmini, 'Catalogs'),
        '-q',
      ],
      { out: () => {}, err: () => {} },
    );
    if (code === 0) written.push(output);
  }
  return written;
}

function processGone(pid: number): boolean {
  try {
    process.kill(pid, 0);
    return false;
  } catch {
    return true;
  }
}

describe("Check in CARLA ScenarioRunner: the project's harness (server/python) against ../shared/carla's verdicts", function () {
  // One ScenarioRunner import per file (2 to 5 s idle), on a loaded 2-core machine: generous.
  this.timeout(1_800_000);
  let folder: string;

  before(function () {
    requireCorpus(this);
    requireCarlaHarness(this);
    folder = temporaryFolder('m2s-carla-check-');
  });
  after(() => {
    if (folder) fs.rmSync(folder, { recursive: true, force: true });
  });

  it('agrees with check.py on which files ScenarioRunner 0.9.16 builds and which it refuses, and at which stage a build fails', async () => {
    const examples = path.join(scenarioRunnerFolder, 'srunner', 'examples');
    const esmini = path.join(openscenarioDir, 'esmini');
    const asWritten = ['cut-in.xosc', 'highway_merge.xosc', 'follow_ghost.xosc', 'lane_change_simple.xosc'];
    const exported = await exportedSamples(
      [
        'cut-in.xosc',
        'highway_merge.xosc',
        'lane_change_simple.xosc',
        'synchronize.xosc',
        'pedestrian.xosc',
        'ltap-od.xosc',
        'acc-test.xosc',
      ],
      folder,
    );
    assert.ok(exported.length >= 5, `only ${exported.length} exports written`);
    const files = [
      ...fs
        .readdirSync(examples)
        .filter((name) => name.endsWith('.xosc'))
        .map((name) => path.join(examples, name)),
      ...asWritten.map((name) => path.join(esmini, name)),
      ...exported,
      path.join(libraryDir, 'modular_hero_front', 'main.xosc'),
    ].filter((file) => fs.existsSync(file));
    const oracle = await harnessVerdicts(files, { timeoutSeconds: 120 });
    const python = scenarioRunnerPython(folder);
    const disagreements: string[] = [];
    let built = 0;
    let refused = 0;
    for (const file of files) {
      const run = await runHarness({
        python,
        scenarioRunner: scenarioRunnerFolder,
        scenario: file,
        towns: CARLA_TOWNS,
        timeLimitMs: 300_000,
      });
      assert.equal(run.kind, 'verdict', `${file}: ${JSON.stringify(run)}`);
      if (run.kind !== 'verdict') continue;
      const expected = oracle.get(path.resolve(file));
      const ours = run.verdict;
      const agree =
        (expected?.status === 'OK' && ours.status === 'built') ||
        (expected?.status === 'FAIL' && ours.status === 'refused' && (expected.stage !== 'build') === (ours.stage !== 'build'));
      if (!agree)
        disagreements.push(
          `${path.relative(repoRoot, file)}: check.py ${expected?.status} ${expected?.stage} ${expected?.reason}; ours ${ours.status} ${ours.stage} ${ours.reason}`,
        );
      if (ours.status === 'built') built++;
      if (ours.status === 'refused') refused++;
    }
    assert.deepEqual(disagreements, []);
    // Both kinds are in the set: 14 of ScenarioRunner's examples and the exports build; the 1.1-1.3 files and the route crash do not.
    assert.ok(built >= 14 + exported.length - 1, `${built} built`);
    assert.ok(refused >= asWritten.length + 3, `${refused} refused`);
  });

  it('names the element ScenarioRunner failed on: the route crash at its AcquirePositionAction', async () => {
    const example = path.join(scenarioRunnerFolder, 'srunner', 'examples', 'IntersectionCollisionAvoidance.xosc');
    const run = await runHarness({
      python: scenarioRunnerPython(folder),
      scenarioRunner: scenarioRunnerFolder,
      scenario: example,
      towns: CARLA_TOWNS,
      timeLimitMs: 300_000,
    });
    assert.equal(run.kind, 'verdict');
    if (run.kind !== 'verdict') return;
    assert.equal(run.verdict.status, 'refused');
    assert.equal(run.verdict.stage, 'build');
    assert.match(run.verdict.reason ?? '', /NoneType' has no len/);
    assert.match(run.verdict.where ?? '', /atomic_behaviors\.py:\d+ __init__/);
    // The element is the position of the AcquirePositionAction: the n-th element in document order.
    const text = fs.readFileSync(example, 'utf8');
    const elements = [...text.replace(/<!--[\s\S]*?-->/g, '').matchAll(/<([A-Za-z]\w*)[\s/>]/g)].map((match) => match[1]);
    const index = run.verdict.element?.index ?? -1;
    assert.equal(elements[index], run.verdict.element?.tag);
    assert.equal(elements[index - 1], 'AcquirePositionAction');
  });

  it('says what is wrong: a Python without the requirements, no Python, a folder that is not ScenarioRunner', async () => {
    const scenario = path.join(scenarioRunnerFolder, 'srunner', 'examples', 'FollowLeadingVehicle.xosc');
    const bare = await runHarness({
      python: scenarioRunnerPython(folder, true),
      scenarioRunner: scenarioRunnerFolder,
      scenario,
      towns: CARLA_TOWNS,
      timeLimitMs: 300_000,
    });
    assert.equal(bare.kind, 'verdict');
    if (bare.kind === 'verdict') {
      assert.equal(bare.verdict.status, 'requirements');
      assert.match(bare.verdict.reason ?? '', /No module named/);
    }
    const none = await runHarness({
      python: path.join(folder, 'no-such-python'),
      scenarioRunner: scenarioRunnerFolder,
      scenario,
      towns: CARLA_TOWNS,
      timeLimitMs: 60_000,
    });
    assert.equal(none.kind, 'no-python');
    const notScenarioRunner = await runHarness({
      python: scenarioRunnerPython(folder),
      scenarioRunner: path.join(repoRoot, 'examples'),
      scenario,
      towns: CARLA_TOWNS,
      timeLimitMs: 300_000,
    });
    assert.equal(notScenarioRunner.kind, 'verdict');
    if (notScenarioRunner.kind === 'verdict') {
      assert.equal(notScenarioRunner.verdict.status, 'not-scenario-runner');
      assert.match(notScenarioRunner.verdict.reason ?? '', /is not a ScenarioRunner folder: it has no scenario_runner\.py/);
    }
  });

  it('stops a harness that hangs at the time limit and kills its processes', async () => {
    const pids = path.join(folder, 'pids');
    const hanging = path.join(folder, 'python-hangs');
    // A "Python" that starts a child and never answers, as an interpreter stuck importing would.
    fs.writeFileSync(hanging, `#!/bin/sh\necho $$ > '${pids}'\nsleep 600 &\necho $! >> '${pids}'\nwait\n`, { mode: 0o755 });
    const run = await runHarness({
      python: hanging,
      scenarioRunner: scenarioRunnerFolder,
      scenario: path.join(scenarioRunnerFolder, 'srunner', 'examples', 'FollowLeadingVehicle.xosc'),
      towns: CARLA_TOWNS,
      // Long enough for the stand-in to start its child and write both pids on a loaded machine, before the kill.
      timeLimitMs: 5000,
    });
    assert.equal(run.kind, 'timeout');
    const started = fs.readFileSync(pids, 'utf8').trim().split('\n').map(Number);
    assert.equal(started.length, 2, 'the stand-in started its child');
    // The kill is asynchronous: wait (bounded) until both are reaped.
    await waitUntil(() => started.every(processGone), 'the processes of the check to end', SERVER_WAIT_MS, 100).catch(() => undefined);
    assert.deepEqual(
      started.filter((pid) => !processGone(pid)),
      [],
      'every process of the check is killed',
    );
  });
});

describe('Check in CARLA ScenarioRunner over JSON-RPC', function () {
  this.timeout(600_000);
  let root = '';
  let python = '';
  let client: TestClient | undefined;

  before(async function () {
    requireCarlaHarness(this);
    root = temporaryWorkspace({}, 'm2s-carla-check-examples-');
    fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
    python = scenarioRunnerPython(root);
    // Under 0.9.15's facts the export keeps crossing.xosc's AcquirePositionAction, on which ScenarioRunner 0.9.16 crashes.
    client = await TestClient.start({ root, settings: { carla: { release: '0.9.15' } } });
    await client.indexed();
  });
  after(async () => {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  const check = (file: string, extra: { scenarioRunnerPath?: string; python?: string; timeLimitSeconds?: number } = {}) =>
    (client as TestClient).send(CheckInScenarioRunnerRequest, {
      uri: fileUri(path.join(root, file)),
      scenarioRunnerPath: scenarioRunnerFolder,
      python,
      ...extra,
    });

  it("builds an example's export: the verdict of ScenarioRunner's loader, nothing left behind", async () => {
    const result = await check('lane_change.xosc');
    assert.equal(result.outcome, 'built', result.message + '\n' + result.log);
    assert.match(result.message, /built its behaviour tree \(\d+ nodes, on Town05\)/);
    assert.deepEqual(result.problems, []);
    assert.ok(result.command?.includes('--scenario-runner'));
  });

  it("takes a relative Python as one in ScenarioRunner's folder, not in the language server's working directory", async () => {
    // A ScenarioRunner folder of its own (its code linked from the unpacked one) with the Python inside it, as a venv is.
    const own = path.join(root, 'own-scenario-runner');
    fs.mkdirSync(path.join(own, 'venv', 'bin'), { recursive: true });
    for (const entry of ['scenario_runner.py', 'srunner', 'requirements.txt'])
      fs.symlinkSync(path.join(scenarioRunnerFolder, entry), path.join(own, entry));
    fs.renameSync(scenarioRunnerPython(path.join(own, 'venv', 'bin')), path.join(own, 'venv', 'bin', 'python'));
    const result = await check('lane_change.xosc', { scenarioRunnerPath: own, python: 'venv/bin/python' });
    assert.equal(result.outcome, 'built', result.message + '\n' + result.log);
    assert.equal(result.command?.[0], path.join(own, 'venv', 'bin', 'python'));
    // Relative to the workspace folder, where the setting's ScenarioRunner folder is resolved from.
    const relative = await check('lane_change.xosc', { scenarioRunnerPath: 'own-scenario-runner', python: 'venv/bin/python' });
    assert.equal(relative.outcome, 'built', relative.message + '\n' + relative.log);
  });

  it("places ScenarioRunner's refusal at the source line of the element it failed on, in the simple scenario of an imported group", async () => {
    const result = await check('main.xosc');
    assert.equal(result.outcome, 'refused', result.message + '\n' + result.log);
    assert.match(result.message, /while building its behaviour tree: TypeError: object of type 'NoneType' has no len\(\)/);
    assert.equal(result.problems.length, 1);
    const [problem] = result.problems;
    assert.equal(problem.uri, fileUri(path.join(root, 'crossing.xosc')));
    assert.equal(problem.severity, 'error');
    // The position inside the AcquirePositionAction, the line after it.
    assert.equal(problem.line, lineMatching(path.join(root, 'crossing.xosc'), /<AcquirePositionAction/) + 1);
    assert.match(problem.message, /<(Position|LanePosition|WorldPosition)>: TypeError/);
  });

  it('explains each setting that stands in the way, and a time limit that passed', async () => {
    const unset = await check('lane_change.xosc', { scenarioRunnerPath: '' });
    assert.equal(unset.outcome, 'no-scenario-runner');
    assert.match(unset.message, /set modular2simple\.carla\.scenarioRunnerPath/);
    const wrongFolder = await check('lane_change.xosc', { scenarioRunnerPath: root });
    assert.equal(wrongFolder.outcome, 'no-scenario-runner');
    assert.match(wrongFolder.message, /is not a ScenarioRunner folder: it has no scenario_runner\.py/);
    const bare = await check('lane_change.xosc', { python: scenarioRunnerPython(root, true) });
    assert.equal(bare.outcome, 'requirements');
    assert.match(bare.message, /lacks ScenarioRunner's requirements \(ModuleNotFoundError: No module named '\w+'\)/);
    assert.match(bare.message, /pip install -r .*requirements\.txt/);
    const missing = await check('lane_change.xosc', { python: path.join(root, 'no-python-here') });
    assert.equal(missing.outcome, 'no-python');
    assert.match(missing.message, /set modular2simple\.carla\.python/i);
    // A road that is no CARLA town: the export refuses it, ScenarioRunner is not asked, the refusal is at the LogicFile.
    const noTown = path.join(root, 'no_town.xosc');
    fs.writeFileSync(
      noTown,
      fs.readFileSync(path.join(root, 'lane_change.xosc'), 'utf8').replace(/(<LogicFile filepath=")[^"]*"/, '$1Town99"'),
    );
    const notExported = await check('no_town.xosc');
    assert.equal(notExported.outcome, 'not-exported');
    assert.match(
      notExported.message,
      /was not exported \(with the facts of ScenarioRunner 0\.9\.15, setting modular2simple\.carla\.release\)/,
    );
    assert.equal(notExported.problems[0]?.line, lineMatching(noTown, /<LogicFile/));
    assert.equal(notExported.command, undefined, 'ScenarioRunner was not run');
    const hanging = path.join(root, 'python-hangs');
    fs.writeFileSync(hanging, '#!/bin/sh\nsleep 600\n', { mode: 0o755 });
    const stopped = await check('lane_change.xosc', { python: hanging, timeLimitSeconds: 1 });
    assert.equal(stopped.outcome, 'timeout');
    assert.match(
      stopped.message,
      /no answer within 1 s \(modular2simple\.carla\.timeLimit\); the check was stopped and its processes killed/,
    );
  });
});
