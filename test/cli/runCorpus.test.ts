import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { HARMLESS_MESSAGES, readEsminiLog } from '../../server/src/esmini/log';
import { withTimeLimit } from '../../server/src/esmini/timeLimit';
import { esminiBinary, esminiCatalogs, esminiRoads, readEsminiCsv, requireEsmini } from '../support/esmini';
import { runCli } from '../support/fixtures';
import { sharedDir } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const esminiScenarios = path.join(sharedDir, 'corpus', 'openscenario', 'esmini');

const DURATION = 5;

/** esmini's roads and every folder of its Catalogs, as its README has a run find them (one --path each). */
function esminiSearchPath(): string[] {
  return [
    esminiRoads,
    ...fs
      .readdirSync(esminiCatalogs, { withFileTypes: true })
      .filter((entry) => entry.isDirectory())
      .map((entry) => path.join(esminiCatalogs, entry.name)),
  ];
}

/** How esmini itself, run as its README says (every --path folder), does on a scenario. */
interface DirectRun {
  /** Exit 0: it loaded the scenario and ran it. */
  ran: boolean;
  /** Its [error] lines other than its remarks about its own roads and 3D models. */
  errors: string[];
}

function runDirectly(file: string, folder: string, searchPath: string[]): DirectRun {
  const limited = withTimeLimit(fs.readFileSync(path.join(esminiScenarios, file), 'utf8'), DURATION);
  if (limited === undefined) return { ran: false, errors: ['no Storyboard'] };
  // A copy elsewhere: nothing is written beside the corpus, and files resolve through --path alone.
  const copy = path.join(folder, file);
  fs.writeFileSync(copy, limited);
  const args = [
    '--headless',
    '--osc',
    copy,
    '--fixed_timestep',
    '0.05',
    '--seed',
    '1',
    '--disable_log',
    ...searchPath.flatMap((entry) => ['--path', entry]),
  ];
  const run = spawnSync(esminiBinary, args, { cwd: folder, encoding: 'utf8', timeout: 60_000, killSignal: 'SIGKILL' });
  const errors = readEsminiLog(`${run.stdout}\n${run.stderr}`)
    .messages.filter((message) => message.level === 'error')
    .map((message) => message.text);
  return { ran: run.status === 0, errors };
}

describe("cli: every scenario of esmini's own that esmini runs also runs through `modular2simple run`", function () {
  this.timeout(600_000);

  it('with outcome ok where esmini reports no error of its own, with its errors where it does, never with its remarks', function () {
    requireEsmini(this);
    if (!fs.existsSync(esminiScenarios)) {
      console.log(`    (skipped: ${esminiScenarios} is absent)`);
      this.skip();
    }
    const searchPath = esminiSearchPath();
    const folder = temporaryFolder('m2s-esmini-corpus-');
    const files = fs
      .readdirSync(esminiScenarios)
      .filter((name) => name.endsWith('.xosc'))
      .sort();
    const direct = new Map(files.map((file) => [file, runDirectly(file, folder, searchPath)]));
    fs.rmSync(folder, { recursive: true, force: true });
    const ran = files.filter((file) => direct.get(file)?.ran);
    assert.ok(
      ran.length >= 60,
      `esmini ran only ${ran.length} of ${files.length}: ${files.filter((file) => !ran.includes(file)).join(', ')}`,
    );

    const cli = runCli(
      ['run', ...ran, '--duration', String(DURATION), '--road-path', searchPath.join(path.delimiter), '--esmini', esminiBinary],
      { cwd: esminiScenarios },
    );
    const outcomes = new Map<string, string>();
    for (const match of cli.stderr.matchAll(/^([^\s:]+\.xosc): (?!\d)(.*)$/gm)) outcomes.set(match[1], match[2]);
    const wrong: string[] = [];
    for (const file of ran) {
      const outcome = outcomes.get(file) ?? '(no outcome printed)';
      const esminiErrors = direct.get(file)?.errors ?? [];
      if (!(esminiErrors.length === 0 ? /^esmini: 0 errors, / : /^esmini: [1-9]\d* errors?, /).test(outcome)) {
        wrong.push(`${file}: ${outcome}; esmini's own errors: ${esminiErrors.join(' | ') || 'none'}`);
      }
    }
    assert.deepEqual(wrong, [], cli.stderr.slice(-4000));
    // esmini's remarks about its own files are no problems of the scenario, at its first line or anywhere.
    const problemLines = cli.stderr.split('\n').filter((line) => /\(esmini\)( \(\d+ times\))?$/.test(line));
    assert.ok(problemLines.length > 0, 'the warnings esmini has about these scenarios are shown');
    assert.deepEqual(
      problemLines.filter((line) => HARMLESS_MESSAGES.some((pattern) => pattern.test(line.replace(/^\S+:\d+:\d+: (error|warning): /, '')))),
      [],
    );
  });
});

describe("cli: run, with esmini's Catalogs as the scenario path, takes the road where esmini finds it (Catalogs/../xodr)", function () {
  this.timeout(180_000);
  // esmini's scenarios name ../xodr/NAME; beside /work/shared/esmini/Catalogs lies xodr/, which a run hands esmini as a --path folder.
  const scenario = 'acc-test.xosc';
  let folder: string;
  beforeEach(function () {
    requireEsmini(this);
    if (!fs.existsSync(path.join(esminiScenarios, scenario))) {
      console.log(`    (skipped: ${esminiScenarios} is absent)`);
      this.skip();
    }
    folder = temporaryFolder('m2s-road-catalogs-');
  });
  afterEach(() => folder && fs.rmSync(folder, { recursive: true, force: true }));

  const run = (scenarioPath: string) =>
    runCli(
      [
        'run',
        path.join(esminiScenarios, scenario),
        '--scenario-path',
        scenarioPath,
        '--duration',
        '2',
        '--esmini',
        esminiBinary,
        '--csv',
        'out.csv',
      ],
      { cwd: folder },
    );

  it('without a warning that the road was not found, and with the trajectory on that road', () => {
    const ran = run(esminiCatalogs);
    assert.equal(ran.status, 0, ran.stderr);
    assert.doesNotMatch(ran.stderr, /found none|is the road esmini loaded|road file .* is found neither/, ran.stderr);
    // The ego starts on road 0 of straight_500m.xodr and drives on it: positions a missing road could not give.
    const steps = readEsminiCsv(path.join(folder, 'out.csv'));
    assert.ok(steps.length > 10, `${steps.length} steps`);
    const ego = steps[steps.length - 1].positions.Ego;
    assert.ok(ego && ego[0] > steps[0].positions.Ego[0], JSON.stringify(ego));
  });

  it('with the warning still where no folder holds the road (the corpus has no xodr beside its Catalogs)', () => {
    const ran = run(path.join(esminiScenarios, 'Catalogs'));
    assert.equal(ran.status, 3, ran.stderr);
    assert.match(ran.stderr, /warning: road file '\.\.\/xodr\/straight_500m\.xodr' is found neither beside this file/);
    assert.match(ran.stderr, /Failed to locate OpenDRIVE file/);
    assert.equal(fs.existsSync(path.join(folder, 'out.csv')), false, 'no CSV of a run that did not happen');
  });
});

describe("cli: run says where two entities collide in esmini's samples, and not where the scenario means them to overlap", function () {
  this.timeout(180_000);

  it('a pedestrian hit is said with its time and placed on the entity; trailers, a ghost and entities placed on each other are not', function () {
    requireEsmini(this);
    if (!fs.existsSync(esminiScenarios)) this.skip();
    const searchPath = esminiSearchPath();
    // Each with a collision esmini's detection logs at t=0 or along the run, and the ones the sample means.
    const files = [
      'pedestrian_collision.xosc',
      'truck_with_rotating_axle.xosc',
      'follow_reference.xosc',
      'long_dist_action_with_jerk.xosc',
    ];
    const cli = runCli(['run', ...files, '--duration', '12', '--road-path', searchPath.join(path.delimiter), '--esmini', esminiBinary], {
      cwd: esminiScenarios,
    });
    assert.equal(cli.status, 0, cli.stderr);
    const outcome = (file: string) => new RegExp(`^${file.replace('.', '\\.')}: esmini: .*$`, 'm').exec(cli.stderr)?.[0] ?? '';
    // The sample is named after it: the ego hits the pedestrian, and esmini drives on through it; each named where declared.
    assert.match(
      outcome('pedestrian_collision.xosc'),
      /^pedestrian_collision\.xosc: esmini: 0 errors, \d+ warnings?; .*; Ego \(pedestrian_collision\.xosc:\d+\) and pedestrian_adult \(pedestrian_collision\.xosc:\d+\) collide at t=5\.45 s \(their bounding boxes overlap;/,
    );
    // No complaint of esmini's about the scenario: no warning of its own.
    assert.doesNotMatch(cli.stderr, /warning: Collision between/);
    // Two cars the Init puts on one spot are no collision; they are one where they meet again later, each keeping its distance.
    assert.match(outcome('long_dist_action_with_jerk.xosc'), /; Ego \(\S+\) and ego jerk \(\S+\) collide at t=10\.45 s \(/);
    // A truck and the trailers esmini makes of it (Truck+, Truck++), a car and the ghost it follows.
    for (const file of files.slice(1, 3)) {
      assert.match(outcome(file), /^\S+: esmini: /, `${file}: no outcome\n${cli.stderr}`);
      assert.doesNotMatch(outcome(file), /collide/, file);
    }
  });
});
