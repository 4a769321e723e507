import * as assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { XMLValidator } from 'fast-xml-parser';
import { cliInTemporaryProject } from '../support/cliProject';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { addParameterControllers, addSumoControllerToEgo, runCli } from '../support/fixtures';
import { cliPath, repoRoot } from '../support/paths';
import { waitUntil } from '../support/wait';
import { temporaryFolder } from '../support/temporaryDirectory';

const FIXTURES = path.join(repoRoot, 'test', 'fixtures', 'variations');
const COLUMNS = 'index,status,collision,min_distance_m,min_ttc_s,end_time_s,EgoSpeed,LeadSpeed,LeadStartS,reason';

/** A folder with follow.xosc (its runs lasting `stopTime` simulated seconds) and its 36-scenario distribution. */
function batchFolder(stopTime = 3, distribution?: string): string {
  const folder = temporaryFolder('m2s-batch-');
  const scenario = fs
    .readFileSync(path.join(FIXTURES, 'follow.xosc'), 'utf8')
    .replace('name="StopTime" parameterType="double" value="3"', `name="StopTime" parameterType="double" value="${stopTime}"`);
  fs.writeFileSync(path.join(folder, 'follow.xosc'), scenario);
  fs.writeFileSync(path.join(folder, 'd.xosc'), distribution ?? fs.readFileSync(path.join(FIXTURES, 'follow_distribution.xosc'), 'utf8'));
  return folder;
}

/** The data lines of results.csv, after its header. */
function csvRows(folder: string): string[] {
  const text = fs.readFileSync(path.join(folder, 'results', 'results.csv'), 'utf8');
  const lines = text.split('\n');
  assert.equal(lines[0], COLUMNS);
  assert.equal(lines.pop(), '', 'results.csv ends with a whole line');
  return lines.slice(1);
}

function indicesOf(rows: string[]): number[] {
  return rows.map((row) => Number(row.split(',')[0]));
}

function assertEveryIndexOnce(rows: string[], count: number): void {
  const indices = indicesOf(rows);
  assert.equal(indices.length, count, `${count} rows`);
  assert.deepEqual(
    [...indices].sort((a, b) => a - b),
    Array.from({ length: count }, (_, i) => i),
  );
}

const BATCH_ARGS = ['batch', 'd.xosc', '--results', 'results', '--jobs', '2', '--road-path', esminiRoads, '--esmini', esminiBinary];

/** Starts a batch in the background; resolves with its exit code and standard error when it ends. */
function startBatch(folder: string, args: string[] = BATCH_ARGS, env: NodeJS.ProcessEnv = {}) {
  const child = spawn(process.execPath, [cliPath, ...args], {
    cwd: folder,
    env: { ...process.env, ...env },
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  let stderr = '';
  child.stderr.on('data', (chunk: Buffer) => (stderr += chunk.toString()));
  const ended = new Promise<{ code: number | null; signal: string | null; stderr: string }>((resolve) =>
    child.on('close', (code, signal) => resolve({ code, signal, stderr })),
  );
  return { child, ended };
}

function rowsSoFar(folder: string): number {
  try {
    return fs.readFileSync(path.join(folder, 'results', 'results.csv'), 'utf8').split('\n').length - 2;
  } catch {
    return 0;
  }
}

describe('cli: batch', function () {
  this.timeout(180_000);
  const folders: string[] = [];
  afterEach(() => {
    for (const folder of folders.splice(0)) fs.rmSync(folder, { recursive: true, force: true });
  });
  const folder = (stopTime?: number, distribution?: string) => {
    const made = batchFolder(stopTime, distribution);
    folders.push(made);
    return made;
  };

  it('runs 36 concrete scenarios with --jobs 2: one row each, collisions where the gap closes, results.json with esmini messages', function () {
    requireEsmini(this);
    const root = folder();
    const run = runCli(BATCH_ARGS, { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /^36 runs \(36 ok, 0 limit, 0 timeout, 0 error; \d+ with a collision\); results in /m);
    const rows = csvRows(root);
    assertEveryIndexOnce(rows, 36);
    const byIndex = new Map(rows.map((row) => [Number(row.split(',')[0]), row.split(',')]));
    // Index 0: ego 10 m/s, lead 5 m/s, 15 m apart: they touch at 3 s. Index 8: lead faster and 65 m ahead.
    assert.deepEqual(byIndex.get(0)?.slice(1, 5), ['ok', 'true', '0.000', '0.000']);
    assert.deepEqual(byIndex.get(0)?.slice(6), ['10', '5.000000', '70', ''], 'an ok run has no reason');
    assert.equal(byIndex.get(8)?.[2], 'false');
    assert.ok(Number(byIndex.get(8)?.[3]) > 60);
    assert.equal(byIndex.get(8)?.[4], '', 'no time to collision when the gap never closes');
    for (const cells of byIndex.values()) {
      if (cells[2] === 'true') assert.equal(cells[3], '0.000', `a collision has no gap: ${cells.join(',')}`);
      assert.equal(cells[5], '3.050');
    }
    const json = JSON.parse(fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8')) as {
      columns: string[];
      rows: { index: string; collision: boolean; messages: { text: string }[] }[];
    };
    assert.deepEqual(json.columns, COLUMNS.split(','));
    assert.deepEqual(
      json.rows.map((row) => Number(row.index)),
      Array.from({ length: 36 }, (_, i) => i),
    );
    assert.ok(json.rows[0].collision);
    assert.ok(json.rows[0].messages.some((message) => message.text === 'Collision between Ego and Lead'));
    const again = runCli(BATCH_ARGS, { cwd: root });
    assert.equal(again.status, 0, again.stderr);
    assert.match(again.stderr, /^0 runs .*, 36 already in /m);
    assert.deepEqual(csvRows(root), rows, 'a finished batch run again changes nothing');
  });

  it("--jobs past 10 (a machine with more cores) prints no node warning of a listener leak, only the batch's own lines", function () {
    requireEsmini(this);
    const root = folder();
    const args = BATCH_ARGS.map((arg, index) => (BATCH_ARGS[index - 1] === '--jobs' ? '12' : arg));
    const run = runCli([...args, '--sample', '12'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /MaxListenersExceededWarning|memory leak|--trace-warnings/);
    assert.match(run.stderr, /^12 runs \(12 ok/m);
    assert.equal(csvRows(root).length, 12);
  });

  for (const signal of ['SIGINT', 'SIGKILL'] as const) {
    it(`a batch stopped by ${signal} mid-way and run again: every index exactly once, the first rows kept`, async function () {
      requireEsmini(this);
      const root = folder(8);
      // Killed with SIGKILL, the batch cannot remove the run folders in flight: it keeps them in a folder of the test's.
      const first = startBatch(root, BATCH_ARGS, signal === 'SIGKILL' ? { TMPDIR: temporaryFolder('m2s-killed-batch-') } : {});
      await waitUntil(() => rowsSoFar(root) >= 4, 'four rows in results.csv', 60_000, 5);
      first.child.kill(signal);
      const ended = await first.ended;
      if (signal === 'SIGINT') {
        assert.equal(ended.code, 130, ended.stderr);
        assert.match(ended.stderr, /interrupted after .*run the same command again/);
      } else assert.equal(ended.signal, 'SIGKILL');
      const before = csvRows(root);
      assert.ok(before.length >= 4 && before.length < 36, `stopped mid-way (${before.length} rows)`);
      assert.equal(new Set(indicesOf(before)).size, before.length, 'no index twice');
      const resumed = runCli(BATCH_ARGS, { cwd: root });
      assert.equal(resumed.status, 0, resumed.stderr);
      const progressLines = resumed.stderr.split('\n').filter((line) => /^\[\d+\/\d+\] /.test(line));
      assert.equal(progressLines.length, 36 - before.length, 'only the missing runs ran');
      const after = csvRows(root);
      assertEveryIndexOnce(after, 36);
      assert.deepEqual(
        indicesOf(after),
        [...indicesOf(after)].sort((a, b) => a - b),
        'results.csv in index order',
      );
      for (const row of before) assert.ok(after.includes(row), `the row kept as it was: ${row}`);
      const json = JSON.parse(fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8')) as { rows: { index: string }[] };
      assert.deepEqual(
        json.rows.map((row) => Number(row.index)),
        Array.from({ length: 36 }, (_, i) => i),
      );
    });
  }

  it('a row cut short by a kill is dropped and its run made again', function () {
    requireEsmini(this);
    const root = folder();
    assert.equal(runCli([...BATCH_ARGS, '--sample', '5', '--seed', '3'], { cwd: root }).status, 0);
    const csv = path.join(root, 'results', 'results.csv');
    const whole = fs.readFileSync(csv, 'utf8');
    const lines = whole.split('\n');
    // The last row half written, as a kill during its write would leave it.
    fs.writeFileSync(csv, lines.slice(0, -2).join('\n') + '\n' + lines[lines.length - 2].slice(0, 7));
    const resumed = runCli([...BATCH_ARGS, '--sample', '5', '--seed', '3'], { cwd: root });
    assert.equal(resumed.status, 0, resumed.stderr);
    assert.match(resumed.stderr, /^1 run .*, 4 already in /m);
    assert.equal(csvRows(root).length, 5);
    assert.deepEqual(new Set(csvRows(root)), new Set(whole.split('\n').slice(1, -1)));
  });

  it('results.csv lists its rows in index order, as results.json, though runs end in another order (a resumed batch: issue 27)', function () {
    requireEsmini(this);
    const root = folder();
    const args = [...BATCH_ARGS, '--sample', '5', '--seed', '3'];
    assert.equal(runCli(args, { cwd: root }).status, 0);
    const whole = csvRows(root);
    const indices = indicesOf(whole);
    assert.deepEqual(
      indices,
      [...indices].sort((a, b) => a - b),
      'a whole batch: in index order',
    );
    // The two lowest indices not done: the batch runs them again after the three others were written.
    const csv = path.join(root, 'results', 'results.csv');
    fs.writeFileSync(csv, [COLUMNS, ...whole.slice(2)].join('\n') + '\n');
    const resumed = runCli(args, { cwd: root });
    assert.equal(resumed.status, 0, resumed.stderr);
    assert.match(resumed.stderr, /^2 runs .*, 3 already in /m);
    assert.deepEqual(csvRows(root), whole);
    const json = JSON.parse(fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8')) as { rows: { index: string }[] };
    assert.deepEqual(
      json.rows.map((row) => Number(row.index)),
      indices,
    );
  });

  it("a combination that breaks the scenario's ValueConstraintGroups keeps its index: a row of status discarded, with its values, not run", function () {
    requireEsmini(this);
    const root = folder();
    const scenarioFile = path.join(root, 'follow.xosc');
    // The lead at most half the ego's speed: (10, 10), (10, 15) and (20, 15) break it, at each of the 3 gaps.
    fs.writeFileSync(
      scenarioFile,
      fs
        .readFileSync(scenarioFile, 'utf8')
        .replace(
          '<ParameterDeclaration name="LeadSpeed" parameterType="double" value="10"/>',
          '<ParameterDeclaration name="LeadSpeed" parameterType="double" value="10"><ConstraintGroup><ValueConstraint rule="lessOrEqual" value="${$EgoSpeed / 2}"/></ConstraintGroup></ParameterDeclaration>',
        ),
    );
    const run = runCli(BATCH_ARGS, { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(
      run.stderr,
      /^27 runs \(27 ok, 0 limit, 0 timeout, 0 error; \d+ with a collision\), 9 discarded by the scenario's ValueConstraintGroups; results in /m,
    );
    const rows = csvRows(root);
    assertEveryIndexOnce(rows, 36);
    for (const row of rows) {
      const cells = row.split(',');
      const [ego, lead] = [Number(cells[6]), Number(cells[7])];
      const breaks = lead > ego / 2;
      assert.equal(cells[1], breaks ? 'discarded' : 'ok', row);
      if (breaks) assert.deepEqual(cells.slice(2, 6), ['false', '', '', ''], `a discarded row has no measure: ${row}`);
    }
    const json = JSON.parse(fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8')) as {
      rows: { index: string; status: string; message: string }[];
    };
    const discarded = json.rows.filter((row) => row.status === 'discarded');
    assert.equal(discarded.length, 9);
    assert.match(discarded[0].message, /^discarded: parameter 'LeadSpeed' = '10.000000' breaks its ValueConstraintGroups$/);
    assert.match(fs.readFileSync(path.join(root, 'results', 'results.html'), 'utf8'), /discarded \(9\)/);
  });

  it("runs each scenario to its own end, past the editor's old 30 s; --duration before that end warns first and gives status limit", function () {
    requireEsmini(this);
    // StopTime 40: the StopTrigger ends every run at 40 s, as ALKS scenarios end at 40-370 s.
    const root = folder(40);
    // An unused Scenario_ID (Euro NCAP's label): a hint for the editor, not printed before the batch.
    const scenario = path.join(root, 'follow.xosc');
    fs.writeFileSync(
      scenario,
      fs
        .readFileSync(scenario, 'utf8')
        .replace(
          '<ParameterDeclarations>',
          '<ParameterDeclarations><ParameterDeclaration name="Scenario_ID" parameterType="string" value="follow"/>',
        ),
    );
    const own = runCli([...BATCH_ARGS, '--sample', '2'], { cwd: root });
    assert.equal(own.status, 0, own.stderr);
    assert.doesNotMatch(own.stderr, /warning|note/);
    for (const cells of csvRows(root).map((row) => row.split(','))) {
      assert.equal(cells[1], 'ok', cells.join(','));
      assert.equal(cells[5], '40.050', 'the scenario ran to its StopTrigger (the first step past 40 s)');
    }
    const cut = folder(40);
    const limited = runCli([...BATCH_ARGS, '--sample', '2', '--duration', '5'], { cwd: cut });
    assert.equal(limited.status, 0, limited.stderr);
    const warning = limited.stderr.indexOf(
      "d.xosc: warning: the scenario's StopTrigger ends all 2 runs after the --duration limit of 5 s (at up to 40 s): they will stop at 5 s with status limit",
    );
    assert.ok(warning >= 0, limited.stderr);
    assert.ok(warning < limited.stderr.indexOf('[1/2]'), 'the warning comes before the runs');
    assert.match(limited.stderr, /^2 runs \(0 ok, 2 limit, 0 timeout, 0 error; /m);
    for (const cells of csvRows(cut).map((row) => row.split(','))) assert.deepEqual([cells[1], cells[5]], ['limit', '5.000']);
    for (const row of csvRows(cut))
      assert.ok(row.endsWith(',"stopped at the 5 s limit set by --duration, before the scenario ended by itself"'), row);
  });

  it('--fail-if criteria: a verdict column, exit 5 naming the failed runs (again on a resume), JUnit XML for CI', function () {
    requireEsmini(this);
    const root = folder();
    const args = [...BATCH_ARGS, '--sample', '8', '--fail-if', 'collision', '--fail-if', 'min_distance_m < 30', '--junit', 'junit.xml'];
    const run = runCli(args, { cwd: root });
    const text = fs.readFileSync(path.join(root, 'results', 'results.csv'), 'utf8');
    const [header, ...lines] = text.trim().split('\n');
    assert.equal(header, 'index,status,collision,min_distance_m,min_ttc_s,end_time_s,verdict,EgoSpeed,LeadSpeed,LeadStartS,reason');
    const rows = lines.map((line) => line.split(','));
    const failing = rows.filter((cells) => cells[2] === 'true' || Number(cells[3]) < 30);
    for (const cells of rows) assert.equal(cells[6], failing.includes(cells) ? 'fail' : 'pass', cells.join(','));
    assert.ok(failing.length > 0 && failing.length < 8, `some runs fail, some pass: ${failing.length}`);
    assert.equal(run.status, 5, run.stderr);
    const named = new RegExp(
      `^modular2simple: ${failing.length} runs? failed the criteria \\(collision; min_distance_m < 30\\): #\\d+: `,
      'm',
    );
    assert.match(run.stderr, named);
    const junit = fs.readFileSync(path.join(root, 'junit.xml'), 'utf8');
    assert.equal(XMLValidator.validate(junit), true);
    assert.match(
      junit,
      new RegExp(`<testsuites name="modular2simple batch" tests="8" failures="${failing.length}" errors="0" skipped="0">`),
    );
    assert.equal((junit.match(/<testcase /g) ?? []).length, 8);
    assert.match(junit, /<failure type="criteria" message="(collision|min_distance_m &lt; 30)/);
    const again = runCli(args, { cwd: root });
    assert.equal(again.status, 5, 'a resumed batch still fails for the runs of before');
    assert.match(again.stderr, named);
    const refused = runCli([...BATCH_ARGS, '--fail-if', 'min_ttc < 1'], { cwd: root });
    assert.equal(refused.status, 2);
    assert.match(
      refused.stderr,
      /--fail-if takes 'collision' or 'METRIC OP NUMBER' with METRIC one of min_ttc_s, min_distance_m, end_time_s/,
    );
  });

  it("a colour esmini logs as an error and skips (CARLA's 'R,G,B') is no failed run, as run counts it (before: every row error, exit 3)", function () {
    requireEsmini(this);
    const root = folder();
    const scenario = fs.readFileSync(path.join(root, 'follow.xosc'), 'utf8');
    const coloured = scenario.replace('<Properties/>', '<Properties><Property name="color" value="255,0,0"/></Properties>');
    assert.notEqual(coloured, scenario);
    fs.writeFileSync(path.join(root, 'follow.xosc'), coloured);
    const run = runCli(['run', 'follow.xosc', '--road-path', esminiRoads, '--esmini', esminiBinary, '--check'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /warning: Property: color format invalid, shall be #RRGGBB, skipping \(esmini\)/);
    const batch = runCli([...BATCH_ARGS, '--sample', '4'], { cwd: root });
    assert.equal(batch.status, 0, batch.stderr);
    assert.match(batch.stderr, /^4 runs \(4 ok, 0 limit, 0 timeout, 0 error; /m);
    const messages = (
      JSON.parse(fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8')) as {
        rows: { messages: { level: string; text: string }[] }[];
      }
    ).rows[0].messages;
    assert.ok(
      messages.some((message) => message.level === 'error' && /color format invalid/.test(message.text)),
      "esmini's own level is kept",
    );
  });

  it("a row's reason and messages name no private run folder: a path esmini tried from there is said from the ScenarioFile's folder (issue 27)", function () {
    requireEsmini(this);
    const root = folder();
    addSumoControllerToEgo(path.join(root, 'follow.xosc'));
    for (const keep of [[], ['--keep-runs']]) {
      fs.rmSync(path.join(root, 'results'), { recursive: true, force: true });
      const batch = runCli([...BATCH_ARGS, '--sample', '1', ...keep], { cwd: root });
      assert.equal(batch.status, 3, batch.stderr);
      const [row] = csvRows(root);
      const tried = path.join(path.dirname(root), 'sumo_inputs', 'e6mini.sumocfg');
      assert.ok(row.includes(`Failed to localize controller file ../sumo_inputs/e6mini.sumocfg, also tried ${tried}`), row);
      const json = fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8');
      assert.ok(json.includes(`also tried ${tried}`), json.slice(0, 2000));
      assert.doesNotMatch(`${row}\n${json}\n${batch.stderr}`, /esmini-run-|modular2simple-esmini|\.running/);
    }
  });

  it("a controller's File named through a parameter, inline or in a catalog entry, reaches the file beside the ScenarioFile, as in run (issue 27)", function () {
    requireEsmini(this);
    const root = folder();
    addParameterControllers(root);
    const batch = runCli([...BATCH_ARGS, '--sample', '2'], { cwd: root });
    assert.equal(batch.status, 0, batch.stderr);
    const rows = csvRows(root);
    assert.equal(rows.length, 2);
    for (const row of rows) assert.equal(row.split(',')[1], 'ok', row);
    assert.doesNotMatch(batch.stderr, /controller file/);
  });

  it("a batch whose runs esmini refuses is no batch done: each row has esmini's reason (progress, summary, CSV, JSON, JUnit), exit 3, again on a resume", function () {
    requireEsmini(this);
    const root = folder();
    // Without --road-path esmini finds no e6mini.xodr and runs nothing; the scenario itself has no error.
    const args = [...'batch d.xosc --results results --jobs 2 --sample 3 --junit junit.xml'.split(' '), '--esmini', esminiBinary];
    const run = runCli(args, { cwd: root });
    assert.equal(run.status, 3, run.stderr);
    const reason = 'esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr';
    const rows = csvRows(root);
    assert.equal(rows.length, 3);
    for (const row of rows) assert.match(row, new RegExp(`^\\d+,error,false,,,,[^,]+,[^,]+,[^,]+,${reason.replace(/[().]/g, '\\$&')}$`));
    const indices = indicesOf(rows).sort((a, b) => a - b);
    const progress = run.stderr.split('\n').filter((line) => /^\[\d\/3\] /.test(line));
    assert.equal(progress.length, 3);
    for (const line of progress) assert.match(line, /^\[\d\/3\] \d+: error: esmini did not run the scenario .*e6mini\.xodr$/);
    assert.match(run.stderr, /^3 runs \(0 ok, 0 limit, 0 timeout, 3 error; 0 with a collision\); results in /m);
    const summary = `modular2simple: error: 3 of 3 runs failed in esmini (status error); the column reason of ${path.join(fs.realpathSync(root), 'results', 'results.csv')} says why for each:\n  ${indices.map((index) => `#${index}`).join(', ')}: ${reason}\n`;
    assert.ok(run.stderr.endsWith(summary), run.stderr);
    const json = JSON.parse(fs.readFileSync(path.join(root, 'results', 'results.json'), 'utf8')) as {
      columns: string[];
      rows: { status: string; reason: string; messages: { level: string; text: string }[] }[];
    };
    assert.equal(json.columns.at(-1), 'reason');
    for (const row of json.rows) {
      assert.deepEqual([row.status, row.reason], ['error', reason]);
      assert.ok(
        row.messages.some((message) => message.level === 'error' && message.text === 'Failed to locate OpenDRIVE file e6mini.xodr'),
      );
    }
    const junit = fs.readFileSync(path.join(root, 'junit.xml'), 'utf8');
    assert.match(junit, /tests="3" failures="0" errors="3" skipped="0"/);
    assert.equal(junit.split(`<error type="error" message="${reason}"/>`).length, 4);
    assert.match(fs.readFileSync(path.join(root, 'results', 'results.html'), 'utf8'), /Failed to locate OpenDRIVE file e6mini\.xodr/);
    // Run again, nothing runs: the rows of before still make the batch one that did not happen.
    const again = runCli(args, { cwd: root });
    assert.equal(again.status, 3, again.stderr);
    assert.match(again.stderr, /^0 runs .*, 3 already in /m);
    assert.ok(again.stderr.endsWith(summary), again.stderr);
  });

  it('checks a plain ScenarioFile as run does: one with errors is refused on its line with what to do, nothing run; --force runs it, esmini saying why each run failed', function () {
    const root = folder();
    // As esmini's own samples write it: a catalog folder of esmini's repository, absent here.
    const scenarioFile = path.join(root, 'follow.xosc');
    const follow = fs.readFileSync(scenarioFile, 'utf8');
    const ego = /<Vehicle name="ego_car"[\s\S]*?<\/Vehicle>/.exec(follow)![0];
    fs.writeFileSync(
      scenarioFile,
      follow
        .replace(
          '<CatalogLocations/>',
          '<CatalogLocations><VehicleCatalog><Directory path="../xosc/Catalogs/Vehicles"/></VehicleCatalog></CatalogLocations>',
        )
        .replace(ego, '<CatalogReference catalogName="VehicleCatalog" entryName="car_white"/>'),
    );
    const args = [...BATCH_ARGS, '--sample', '2', '-q'];
    const refused = runCli(args, { cwd: root });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(
      refused.stderr,
      /^follow\.xosc:11:\d+: error: the VehicleCatalog directory '\.\.\/xosc\/Catalogs\/Vehicles' does not exist beside this file.*\n {2}hint: .*--scenario-path/m,
    );
    assert.match(refused.stderr, /^follow\.xosc: the scenario has 1 error; nothing was run \(--force runs it anyway\)$/m);
    assert.ok(!fs.existsSync(path.join(root, 'results')), 'nothing run, nothing written');
    requireEsmini(this);
    const forced = runCli([...args, '--force'], { cwd: root });
    assert.equal(forced.status, 3, forced.stderr);
    assert.match(forced.stderr, /^follow\.xosc: the scenario has 1 error; running anyway \(--force\)$/m);
    const rows = csvRows(root);
    assert.equal(rows.length, 2);
    const reason = "esmini did not run the scenario (exit code 255): Couldn't locate OpenSCENARIO file VehicleCatalog";
    for (const row of rows) assert.ok(row.startsWith(`${row.split(',')[0]},error,`) && row.endsWith(`,${reason}`), row);
    assert.match(
      forced.stderr,
      /^modular2simple: error: 2 of 2 runs failed in esmini \(status error\); .*\n {2}#\d+, #\d+: esmini did not run the scenario .*VehicleCatalog$/m,
    );
  });

  it('refuses bad input before running anything, leaving no results folder', () => {
    const root = folder();
    const results = path.join(root, 'results');
    const refused = (args: string[], code: number, message: RegExp) => {
      const run = runCli(args, { cwd: root });
      assert.equal(run.status, code, run.stderr);
      assert.match(run.stderr, message);
      assert.ok(!fs.existsSync(results), `nothing written for ${args.join(' ')}`);
    };
    refused(['batch', 'd.xosc'], 2, /batch needs --results DIR/);
    refused(['batch', 'd.xosc', '--results', 'results', '--jobs', '0'], 2, /--jobs takes at least 1/);
    refused(['batch', 'd.xosc', '--results', 'results', '--duration', '0'], 2, /--duration takes a positive number/);
    refused(['batch', 'missing.xosc', '--results', 'results'], 1, /missing\.xosc: no such file/);
    const distribution = fs.readFileSync(path.join(root, 'd.xosc'), 'utf8');
    fs.writeFileSync(path.join(root, 'd.xosc'), distribution.replace('filepath="follow.xosc"', 'filepath="gone.xosc"'));
    refused(['batch', 'd.xosc', '--results', 'results'], 1, /^d\.xosc:\d+:\d+: error: ScenarioFile gone\.xosc .*no such file/m);
    fs.writeFileSync(path.join(root, 'd.xosc'), distribution.replace('parameterName="LeadSpeed"', 'parameterName="LeadMass"'));
    refused(['batch', 'd.xosc', '--results', 'results'], 1, /^d\.xosc:\d+:\d+: error: parameter 'LeadMass' is not declared/m);
    fs.writeFileSync(path.join(root, 'd.xosc'), distribution.replace('stepWidth="5"', 'stepWidth="0"'));
    refused(['batch', 'd.xosc', '--results', 'results'], 1, /^d\.xosc:\d+:\d+: error: .*step/m);
    refused(['batch', 'd.xosc', '--results', 'results', '--queue', 'http://localhost:1'], 2, /--queue takes redis:\/\/HOST:PORT/);
    fs.writeFileSync(path.join(root, 'd.xosc'), distribution);
    refused(['batch', 'd.xosc', '--results', 'results', '--esmini', path.join(root, 'no-esmini')], 3, /esmini is not at /);
  });

  it('--queue without the queue packages (bullmq, ioredis) says what to install and exits 3, writing nothing; worker likewise', () => {
    const root = folder();
    // A stand-in where npm start builds esmini: nothing runs, as the queue's packages are looked for first.
    const stub = path.join(root, 'esmini-stub');
    fs.writeFileSync(stub, '#!/bin/sh\nexit 9\n', { mode: 0o755 });
    const withoutQueue = cliInTemporaryProject(stub);
    try {
      const queued = withoutQueue.run(['batch', 'd.xosc', '--results', 'results', '--queue', 'redis://127.0.0.1:1'], root);
      assert.equal(queued.status, 3, queued.stderr);
      assert.match(
        queued.stderr,
        /--queue needs the npm packages bullmq and ioredis, and bullmq is not installed: run 'npm install bullmq@6 ioredis@6'/,
      );
      assert.ok(!fs.existsSync(path.join(root, 'results')));
      const worker = withoutQueue.run(['worker', '--queue', 'redis://127.0.0.1:1'], root);
      assert.equal(worker.status, 3, worker.stderr);
      assert.match(worker.stderr, /--queue needs the npm packages bullmq and ioredis/);
      assert.doesNotMatch(queued.stderr + worker.stderr, /internal error|    at /);
    } finally {
      withoutQueue.remove();
    }
  });

  it('refuses 10^9 combinations before running anything unless --sample; --sample N runs N', function () {
    const ranges = ['EgoSpeed', 'LeadSpeed', 'LeadStartS']
      .map(
        (name) => `      <DeterministicSingleParameterDistribution parameterName="${name}">
        <DistributionRange stepWidth="1"><Range lowerLimit="1" upperLimit="1000"/></DistributionRange>
      </DeterministicSingleParameterDistribution>`,
      )
      .join('\n');
    const distribution = fs
      .readFileSync(path.join(FIXTURES, 'follow_distribution.xosc'), 'utf8')
      .replace(/<Deterministic>[\s\S]*<\/Deterministic>/, `<Deterministic>\n${ranges}\n    </Deterministic>`);
    const root = folder(1, distribution);
    const refused = runCli(BATCH_ARGS, { cwd: root });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(refused.stderr, /1000000000 combinations are more than --max-combinations 1000000; nothing was run/);
    assert.ok(!fs.existsSync(path.join(root, 'results')));
    requireEsmini(this);
    const sampled = runCli([...BATCH_ARGS, '--sample', '4', '--seed', '7', '--duration', '1'], { cwd: root });
    assert.equal(sampled.status, 0, sampled.stderr);
    const rows = csvRows(root);
    assert.equal(rows.length, 4);
    for (const row of rows) assert.ok(Number(row.split(',')[0]) < 1e9);
  });

  it('a stochastic distribution: each row holds the values vary draws for its index', function () {
    requireEsmini(this);
    const stochastic = fs.readFileSync(path.join(FIXTURES, 'follow_distribution.xosc'), 'utf8').replace(
      /<Deterministic>[\s\S]*<\/Deterministic>/,
      `<Stochastic numberOfTestRuns="6" randomSeed="5">
      <StochasticDistribution parameterName="EgoSpeed"><NormalDistribution expectedValue="20" variance="9"/></StochasticDistribution>
      <StochasticDistribution parameterName="LeadSpeed"><UniformDistribution><Range lowerLimit="5" upperLimit="15"/></UniformDistribution></StochasticDistribution>
    </Stochastic>`,
    );
    const root = folder(3, stochastic);
    const run = runCli(BATCH_ARGS, { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const lines = fs
      .readFileSync(path.join(root, 'results', 'results.csv'), 'utf8')
      .trim()
      .split('\n');
    assert.equal(lines[0], 'index,status,collision,min_distance_m,min_ttc_s,end_time_s,EgoSpeed,LeadSpeed,reason');
    assert.equal(lines.length, 7);
    for (const line of lines.slice(1)) {
      const cells = line.split(',');
      const concrete = runCli(['vary', 'd.xosc', '--index', cells[0]], { cwd: root }).stdout;
      assert.ok(concrete.includes(`name="EgoSpeed" parameterType="double" value="${cells[6]}"`), line);
      assert.ok(concrete.includes(`name="LeadSpeed" parameterType="double" value="${cells[7]}"`), line);
    }
  });

  it('refuses a results folder that holds another batch, changing nothing in it', function () {
    requireEsmini(this);
    const root = folder();
    assert.equal(runCli([...BATCH_ARGS, '--sample', '2'], { cwd: root }).status, 0);
    const before = fs.readFileSync(path.join(root, 'results', 'results.csv'), 'utf8');
    const other = runCli([...BATCH_ARGS, '--sample', '3', '--seed', '1'], { cwd: root });
    assert.equal(other.status, 3, other.stderr);
    assert.match(other.stderr, /holds another batch's results \(it differs in sample, seed\)/);
    assert.equal(fs.readFileSync(path.join(root, 'results', 'results.csv'), 'utf8'), before);
  });
});
