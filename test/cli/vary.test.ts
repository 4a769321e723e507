import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { deterministic, distributionFile, fileHeader, runCli } from '../support/fixtures';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const DECLARED = '<ParameterDeclaration name="CutInSpeed" parameterType="double" value="27.5"/>';

/** The examples with a root parameter in main.xosc, and a distribution over it naming `scenarioFile`. */
function examplesWithDistribution(scenarioFile: string): string {
  const root = temporaryFolder('m2s-vary-modular-');
  fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
  const main = path.join(root, 'main.xosc');
  fs.writeFileSync(
    main,
    fs
      .readFileSync(main, 'utf8')
      .replace(
        '  <ParameterDeclarations/>\n  <CatalogLocations/>',
        `  <ParameterDeclarations>\n    ${DECLARED}\n  </ParameterDeclarations>\n  <CatalogLocations/>`,
      ),
  );
  fs.writeFileSync(
    path.join(root, 'd.xosc'),
    distributionFile(
      scenarioFile,
      deterministic(`      <DeterministicSingleParameterDistribution parameterName="CutInSpeed">
        <DistributionSet><Element value="20"/><Element value="30"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
`),
      fileHeader({ date: '2026-11-24T00:00:00', description: 'd', author: 'm2s' }),
    ),
  );
  return root;
}

describe('cli: vary and batch on a modular ScenarioFile (flattened per concrete scenario)', function () {
  this.timeout(120_000);
  const roots: string[] = [];
  afterEach(() => {
    for (const root of roots.splice(0)) fs.rmSync(root, { recursive: true, force: true });
  });
  const examples = (scenarioFile: string) => {
    const root = examplesWithDistribution(scenarioFile);
    roots.push(root);
    return root;
  };

  it('a modular main.xosc: each concrete scenario is the flattened main with its value', () => {
    const root = examples('main.xosc');
    assert.deepEqual([runCli(['vary', 'd.xosc', '--count'], { cwd: root }).stdout], ['2\n']);
    const flat = runCli(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(flat.status, 0, flat.stderr);
    const concrete = runCli(['vary', 'd.xosc', '--index', '1'], { cwd: root });
    assert.equal(concrete.status, 0, concrete.stderr);
    assert.doesNotMatch(concrete.stdout, /ScenarioReference/);
    assert.equal(concrete.stdout, flat.stdout.replace(DECLARED, DECLARED.replace('27.5', '30')));
  });

  it('--index I -o FILE says what it wrote, with the values it set (as --out-dir says its count); -q says nothing', () => {
    const root = examples('main.xosc');
    const written = runCli(['vary', 'd.xosc', '--index', '1', '-o', 'one.xosc'], { cwd: root });
    assert.equal(written.status, 0, written.stderr);
    assert.equal(written.stderr, 'wrote one.xosc (concrete scenario 1 of 2: CutInSpeed = 30)\n');
    assert.ok(fs.readFileSync(path.join(root, 'one.xosc'), 'utf8').includes(DECLARED.replace('27.5', '30')));
    const quiet = runCli(['vary', 'd.xosc', '--index', '0', '-o', 'zero.xosc', '-q'], { cwd: root });
    assert.equal(quiet.status, 0, quiet.stderr);
    assert.equal(quiet.stderr, '');
  });

  it('vary and export: an --index past the count is a usage error (exit 2) naming the option, the file and the range, written nowhere (issue 27: was FILE:1:1, exit 1)', () => {
    const root = examples('main.xosc');
    const usage =
      /^modular2simple: --index 2 is out of range: d\.xosc has 2 concrete scenarios, numbered 0\.\.1; give --index one of those\nRun 'modular2simple --help' for usage\.\n$/;
    const vary = runCli(['vary', 'd.xosc', '--index', '2', '-o', 'two.xosc'], { cwd: root });
    assert.equal(vary.status, 2, vary.stderr);
    assert.match(vary.stderr, usage);
    const exported = runCli(['export', 'd.xosc', '--target', 'carla', '--index', '2', '-o', 'two.xosc'], { cwd: root });
    assert.equal(exported.status, 2, exported.stderr);
    assert.match(exported.stderr, usage);
    assert.ok(!fs.existsSync(path.join(root, 'two.xosc')));
    assert.equal(
      runCli(['export', 'd.xosc', '--target', 'carla', '--index', 'x', '-o', 'two.xosc'], { cwd: root }).stderr.split('\n')[0],
      "modular2simple: --index takes a whole number, not 'x'",
    );
  });

  it('a .mosc and an unpacked folder as ScenarioFile are flattened too', () => {
    const root = examples('encounter.mosc');
    const packed = runCli(['pack', '.', '-o', 'encounter.mosc'], { cwd: root });
    assert.equal(packed.status, 0, packed.stderr);
    const concrete = runCli(['vary', 'd.xosc', '--index', '0'], { cwd: root });
    assert.equal(concrete.status, 0, concrete.stderr);
    assert.doesNotMatch(concrete.stdout, /ScenarioReference/);
    assert.ok(concrete.stdout.includes(DECLARED.replace('27.5', '20')));
    fs.writeFileSync(
      path.join(root, 'd.xosc'),
      fs.readFileSync(path.join(root, 'd.xosc'), 'utf8').replace('filepath="encounter.mosc"', 'filepath="."'),
    );
    const folder = runCli(['vary', 'd.xosc', '--index', '0'], { cwd: root });
    assert.equal(folder.status, 0, folder.stderr);
    assert.equal(folder.stdout, concrete.stdout);
  });

  it('a modular main that cannot be flattened is refused with its problems, nothing written', () => {
    const root = examples('main.xosc');
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(main, fs.readFileSync(main, 'utf8').replace('maneuverGroupName="CutIn"', 'maneuverGroupName="NoSuchGroup"'));
    const run = runCli(['vary', 'd.xosc', '--out-dir', 'out'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(
      run.stderr,
      /^d\.xosc:5:\d+: error: ScenarioFile main\.xosc .*cannot be flattened \(1 error\):\n {2}main\.xosc:\d+:\d+: error: .*NoSuchGroup/m,
    );
    assert.ok(!fs.existsSync(path.join(root, 'out')));
  });

  it('batch runs the flattened concrete scenarios of a modular main', function () {
    requireEsmini(this);
    const root = examples('main.xosc');
    const run = runCli(
      ['batch', 'd.xosc', '--results', 'results', '--duration', '1', '--jobs', '2', '--road-path', esminiRoads, '--esmini', esminiBinary],
      { cwd: root },
    );
    assert.equal(run.status, 0, run.stderr);
    const lines = fs
      .readFileSync(path.join(root, 'results', 'results.csv'), 'utf8')
      .trim()
      .split('\n');
    assert.equal(lines[0], 'index,status,collision,min_distance_m,min_ttc_s,end_time_s,CutInSpeed,reason');
    assert.deepEqual(
      lines
        .slice(1)
        .map((line) => line.split(',')[0])
        .sort(),
      ['0', '1'],
    );
    for (const line of lines.slice(1))
      assert.match(
        line,
        /^\d,(ok|limit),(true|false),[\d.]+,[\d.]*,1\.0\d0,(20|30),("stopped at the 1 s limit set by --duration, before the scenario ended by itself")?$/,
      );
  });
});
