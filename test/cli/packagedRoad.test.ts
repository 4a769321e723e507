import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { harnessVerdicts, requireCarlaHarness } from '../support/carla';
import { esminiBinary, esminiRoads, EsminiStep, readEsminiCsv, requireEsmini } from '../support/esmini';
import { deterministic, distributionFile, drivingScenario, outerGroup, packageOf, roadParameterPackage, runCli } from '../support/fixtures';
import { assertSameRun, namedPaths, runAlone } from '../support/outputPaths';
import { keptBesideRun } from '../../server/src/batch/runConcrete';
import { temporaryFolder } from '../support/temporaryDirectory';

/**
 * A new user's path (issue 27): a package holding a scenario and the road it drives on, packed with `pack
 * --self-contained`, and a main outside the package that imports the package's group. Each command is run as a user
 * runs it, from a working folder of its own; esmini and ScenarioRunner's loader judge the outputs.
 */

/** Ego's x at the last step. */
function lastX(steps: EsminiStep[]): number {
  return steps[steps.length - 1].positions.Ego[0];
}

describe('cli: a road packed in a .mosc beside the scenario that uses it, and a main outside the package (issue 27)', function () {
  let root: string;
  let road: Buffer;

  before(function () {
    requireEsmini(this);
    root = temporaryFolder('m2s-packed-road-');
    road = fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'));
    fs.mkdirSync(path.join(root, 'drive'));
    fs.mkdirSync(path.join(root, 'app'));
    fs.mkdirSync(path.join(root, 'roads'));
    fs.writeFileSync(path.join(root, 'drive', 'main.xosc'), drivingScenario('straight_500m.xodr', 'Drive'));
    fs.writeFileSync(path.join(root, 'drive', 'straight_500m.xodr'), road);
    fs.writeFileSync(path.join(root, 'roads', 'straight_500m.xodr'), road);
    const outer = outerGroup('Car', 'Ego', [{ file: 'drive.mosc', groups: [{ name: 'Drive', parameters: [['value', '15']] }] }]);
    fs.writeFileSync(path.join(root, 'app', 'main.xosc'), drivingScenario('../roads/straight_500m.xodr', outer));
    const pack = runCli(['pack', 'drive', '-o', 'app/drive.mosc', '--self-contained'], { cwd: root });
    assert.equal(pack.status, 0, pack.stderr);
    assert.match(pack.stderr, /wrote app\/drive\.mosc \(straight_500m\.xodr, main\.xosc\)/);
  });

  const elsewhere = () => temporaryFolder('m2s-packed-road-cwd-');

  it('pack FILE... refuses the road as an input and says how to store it; following the hint gives a package that runs', () => {
    const out = path.join(elsewhere(), 'files.mosc');
    const refused = runCli(['pack', 'drive/main.xosc', 'drive/straight_500m.xodr', '-o', out], { cwd: root });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(
      refused.stderr,
      /'straight_500m\.xodr' is neither a \.xosc scenario nor a \.mosc package\n\s*hint: .*with --self-contained, pack stores the road files/,
    );
    assert.equal(fs.existsSync(out), false);
    const pack = runCli(['pack', 'drive/main.xosc', '-o', out, '--self-contained'], { cwd: root });
    assert.equal(pack.status, 0, pack.stderr);
    const run = runCli(['run', out, '--esmini', esminiBinary, '--check'], { cwd: elsewhere() });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /esmini: 0 errors, 0 warnings; 8\.\d\d s simulated/);
  });

  it('check: no false alarm about the packed road, for esmini and by the standard; the main outside is clean too', () => {
    for (const simulator of ['asam', 'esmini']) {
      const check = runCli(['check', path.join(root, 'app', 'drive.mosc'), '--simulator', simulator], { cwd: elsewhere() });
      assert.equal(check.status, 0, check.stderr);
      assert.match(check.stderr, /checked 1 file: 0 errors, 0 warnings/, simulator);
      const outer = runCli(['check', path.join(root, 'app', 'main.xosc'), '--simulator', simulator], { cwd: elsewhere() });
      assert.equal(outer.status, 0, outer.stderr);
      assert.match(outer.stderr, /0 errors, 0 warnings/, simulator);
    }
  });

  it('run: esmini runs the package on its own road, with no warning, as its flattened file runs from another folder', async () => {
    const cwd = elsewhere();
    const run = runCli(['run', path.join(root, 'app', 'drive.mosc'), '--esmini', esminiBinary, '--check', '--csv', 'run.csv'], { cwd });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /: warning:/, 'no warning that the picture found no road');
    assert.match(run.stderr, /esmini: 0 errors, 0 warnings; 8\.\d\d s simulated/);
    const ran = readEsminiCsv(path.join(cwd, 'run.csv'));
    assert.ok(Math.abs(lastX(ran) - 90) < 2, `Ego drove 8 s at 10 m/s from x 10: ${lastX(ran)}`);
    // flatten to another folder: the road's copy goes beside the output, which esmini runs from an unrelated folder.
    const flat = path.join(elsewhere(), 'deep', 'flat.xosc');
    fs.mkdirSync(path.dirname(flat));
    const flatten = runCli(['flatten', path.join(root, 'app', 'drive.mosc'), '-o', flat], { cwd: elsewhere() });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.deepEqual(namedPaths(flat), [path.join(path.dirname(flat), 'flat.files', 'straight_500m.xodr')]);
    assert.deepEqual(fs.readFileSync(namedPaths(flat)[0]), road);
    assertSameRun((await runAlone(flat)).steps, ran, 'the flattened package');
  });

  it("the main outside the package: flattened anywhere it names its own road, runs the package's group with its override", async () => {
    const flat = path.join(elsewhere(), 'flat.xosc');
    const flatten = runCli(['flatten', path.join(root, 'app', 'main.xosc'), '-o', flat], { cwd: elsewhere() });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.deepEqual(namedPaths(flat), [path.join(root, 'roads', 'straight_500m.xodr')]);
    const alone = (await runAlone(flat)).steps;
    assert.ok(Math.abs(lastX(alone) - 130) < 2, `Ego drove 8 s at the overriding 15 m/s from x 10: ${lastX(alone)}`);
    const cwd = elsewhere();
    const run = runCli(['run', path.join(root, 'app', 'main.xosc'), '--esmini', esminiBinary, '--check', '--csv', 'run.csv'], { cwd });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /: warning:/);
    assertSameRun(readEsminiCsv(path.join(cwd, 'run.csv')), alone, 'the main outside the package, run');
  });

  it('run: a road the LogicFile names through a $parameter is found in the package too (before: esmini failed to locate it, exit 3)', async () => {
    const folder = elsewhere();
    const scenario = drivingScenario('$Road', 'Drive').replace(
      '<ParameterDeclarations></ParameterDeclarations>',
      '<ParameterDeclarations><ParameterDeclaration name="Road" parameterType="string" value="straight_500m.xodr"/></ParameterDeclarations>',
    );
    assert.match(scenario, /name="Road"/);
    fs.writeFileSync(path.join(folder, 'p.mosc'), await packageOf({ 'main.xosc': scenario, 'straight_500m.xodr': road.toString('utf8') }));
    const check = runCli(['check', 'p.mosc', '--simulator', 'esmini'], { cwd: folder });
    assert.match(check.stderr, /0 errors, 0 warnings/);
    const cwd = elsewhere();
    const run = runCli(['run', path.join(folder, 'p.mosc'), '--esmini', esminiBinary, '--check', '--csv', 'run.csv'], { cwd });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /esmini: 0 errors, 0 warnings; 8\.\d\d s simulated/);
    assert.ok(Math.abs(lastX(readEsminiCsv(path.join(cwd, 'run.csv'))) - 90) < 2);
  });

  /** `batch DISTRIBUTION --keep-runs` from a folder of its own, which must end with exit 0: its results folder and sorted rows. */
  function batchOf(distribution: string): { results: string; rows: string[] } {
    const results = path.join(elsewhere(), 'results');
    const batch = runCli(['batch', distribution, '--results', results, '--esmini', esminiBinary, '--keep-runs'], { cwd: elsewhere() });
    assert.equal(batch.status, 0, batch.stderr);
    return { results, rows: fs.readFileSync(path.join(results, 'results.csv'), 'utf8').trim().split('\n').slice(1).sort() };
  }

  it('flatten, vary and batch of a package whose $Road names its packed road: each written scenario runs from its folder (before: none found the road)', async () => {
    const folder = elsewhere();
    await roadParameterPackage(folder, { 'straight_500m.xodr': road }, 'Speed', ['5', '12']);
    // flatten: $Road stays as written (SPEC 11.6); the road's copy goes where its value names it from the output.
    const out = path.join(elsewhere(), 'flat.xosc');
    const flatten = runCli(['flatten', path.join(folder, 'p.mosc'), '-o', out], { cwd: elsewhere() });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.match(fs.readFileSync(out, 'utf8'), /<LogicFile filepath="\$Road"\/>/);
    assert.deepEqual(fs.readFileSync(path.join(path.dirname(out), 'straight_500m.xodr')), road);
    assert.ok(Math.abs(lastX((await runAlone(out)).steps) - 90) < 2);
    // A file of that name already beside the output is never replaced, and the warning says the output reaches it.
    const taken = elsewhere();
    fs.writeFileSync(path.join(taken, 'straight_500m.xodr'), 'another road');
    const refused = runCli(['flatten', path.join(folder, 'p.mosc'), '-o', path.join(taken, 'flat.xosc')], { cwd: taken });
    assert.equal(refused.status, 0, refused.stderr);
    assert.match(
      refused.stderr,
      /warning: '\$Road' names a file of the package, whose copy would go to .*straight_500m\.xodr, which holds another file/,
    );
    assert.equal(fs.readFileSync(path.join(taken, 'straight_500m.xodr'), 'utf8'), 'another road');
    // vary: every concrete scenario runs from the folder it was written to, at its own speed.
    const outDir = path.join(elsewhere(), 'concrete');
    const vary = runCli(['vary', path.join(folder, 'speeds.xosc'), '--out-dir', outDir], { cwd: elsewhere() });
    assert.equal(vary.status, 0, vary.stderr);
    assert.deepEqual(fs.readFileSync(path.join(outDir, 'straight_500m.xodr')), road);
    assert.ok(Math.abs(lastX((await runAlone(path.join(outDir, 'p_0.xosc'))).steps) - 50) < 2, 'Ego drove 8 s at 5 m/s from x 10');
    assert.ok(Math.abs(lastX((await runAlone(path.join(outDir, 'p_1.xosc'))).steps) - 106) < 2, 'Ego drove 8 s at 12 m/s from x 10');
    // A road of that name already in the folder vary writes to is kept, and said once.
    const kept = elsewhere();
    fs.writeFileSync(path.join(kept, 'straight_500m.xodr'), 'another road');
    const varyKept = runCli(['vary', path.join(folder, 'speeds.xosc'), '--out-dir', kept], { cwd: elsewhere() });
    assert.equal(varyKept.status, 0, varyKept.stderr);
    assert.equal(varyKept.stderr.match(/which holds another file/g)?.length, 1, varyKept.stderr);
    assert.equal(fs.readFileSync(path.join(kept, 'straight_500m.xodr'), 'utf8'), 'another road');
    // batch: every run esmini ran on the packed road, to the scenario's end.
    const { results, rows } = batchOf(path.join(folder, 'speeds.xosc'));
    assert.deepEqual(rows, ['0,ok,false,,,8.050,5,', '1,ok,false,,,8.050,12,']);
    for (const index of ['0', '1'])
      assert.match(fs.readFileSync(path.join(results, 'runs', index, 'esmini.log'), 'utf8'), /Loaded OpenDRIVE: .*straight_500m\.xodr/);
  });

  it('vary and batch --keep-runs of a varied $Road over two roads the package holds: each concrete scenario gets its own road (before: only the first was found), and each kept run holds it beside its scenario and reruns by itself (before: esmini failed to locate it)', async () => {
    const folder = elsewhere();
    const signs = fs.readFileSync(path.join(esminiRoads, 'straight_500m_signs.xodr'));
    await roadParameterPackage(folder, { 'straight_500m.xodr': road, 'straight_500m_signs.xodr': signs }, 'Road', [
      'straight_500m.xodr',
      'straight_500m_signs.xodr',
    ]);
    const outDir = path.join(elsewhere(), 'concrete');
    const vary = runCli(['vary', path.join(folder, 'speeds.xosc'), '--out-dir', outDir], { cwd: elsewhere() });
    assert.equal(vary.status, 0, vary.stderr);
    assert.deepEqual(fs.readFileSync(path.join(outDir, 'straight_500m_signs.xodr')), signs);
    for (const [index, name] of ['straight_500m.xodr', 'straight_500m_signs.xodr'].entries())
      assert.match((await runAlone(path.join(outDir, `p_${index}.xosc`))).log, new RegExp(`Loaded OpenDRIVE: ${outDir}/${name}`));
    const { results, rows } = batchOf(path.join(folder, 'speeds.xosc'));
    assert.deepEqual(rows, ['0,ok,false,,,8.050,straight_500m.xodr,', '1,ok,false,,,8.050,straight_500m_signs.xodr,']);
    for (const [index, name] of ['straight_500m.xodr', 'straight_500m_signs.xodr'].entries()) {
      const kept = path.join(results, 'runs', String(index));
      assert.match(fs.readFileSync(path.join(kept, 'esmini.log'), 'utf8'), new RegExp(`Loaded OpenDRIVE: (.*/)?${name}\\n`));
      assert.match(fs.readFileSync(path.join(kept, 'scenario.xosc'), 'utf8'), /<LogicFile filepath="\$Road"\/>/);
      assert.deepEqual(fs.readdirSync(kept).sort(), ['esmini.log', 'scenario.xosc', name, 'trajectories.csv'].sort());
      assert.deepEqual(fs.readFileSync(path.join(kept, name)), index === 0 ? road : signs);
      const rerun = await runAlone(path.join(kept, 'scenario.xosc'));
      assert.match(rerun.log, new RegExp(`Loaded OpenDRIVE: ${kept}/${name}`));
      assert.ok(Math.abs(lastX(rerun.steps) - 90) < 2, `kept run ${index} drove as in the batch`);
    }
  });

  it("batch --keep-runs of a package whose main names its packed road as it is: each kept run holds the road where its scenario names it, and reruns by itself (before: it named the batch's temporary copy, removed at its end)", async () => {
    const literal = elsewhere();
    const scenario = drivingScenario('straight_500m.xodr', 'Drive')
      .replace(
        '<ParameterDeclarations></ParameterDeclarations>',
        '<ParameterDeclarations><ParameterDeclaration name="Speed" parameterType="double" value="10"/></ParameterDeclarations>',
      )
      .replace('parameterAttributes="value" value="10"', 'value="$Speed"');
    fs.writeFileSync(path.join(literal, 'p.mosc'), await packageOf({ 'main.xosc': scenario, 'straight_500m.xodr': road.toString('utf8') }));
    fs.writeFileSync(
      path.join(literal, 'speeds.xosc'),
      distributionFile(
        'p.mosc',
        deterministic(
          '      <DeterministicSingleParameterDistribution parameterName="Speed">\n        <DistributionSet><Element value="12"/></DistributionSet>\n      </DeterministicSingleParameterDistribution>\n',
        ),
      ),
    );
    const { results, rows } = batchOf(path.join(literal, 'speeds.xosc'));
    assert.deepEqual(rows, ['0,ok,false,,,8.050,12,']);
    const kept = path.join(results, 'runs', '0');
    const named = /<LogicFile filepath="([^"]*)"\/>/.exec(fs.readFileSync(path.join(kept, 'scenario.xosc'), 'utf8'))?.[1] ?? '';
    assert.ok(!path.isAbsolute(named), named);
    assert.deepEqual(fs.readFileSync(path.join(kept, named)), road);
    assert.ok(Math.abs(lastX((await runAlone(path.join(kept, 'scenario.xosc'))).steps) - 106) < 2, 'the kept run drove 8 s at 12 m/s');
  });

  it('batch --keep-runs of a plain ScenarioFile whose $Road names a road beside it: the kept runs name it by its Road value, absolute, and rerun by themselves (before: as written, with a warning naming the --path a rerun needed)', async () => {
    const folder = elsewhere();
    fs.mkdirSync(path.join(folder, 'sc'));
    fs.writeFileSync(path.join(folder, 'sc', 'straight_500m.xodr'), road);
    const scenario = drivingScenario('$Road', 'Drive')
      .replace(
        '<ParameterDeclarations></ParameterDeclarations>',
        '<ParameterDeclarations><ParameterDeclaration name="Road" parameterType="string" value="straight_500m.xodr"/><ParameterDeclaration name="Speed" parameterType="double" value="10"/></ParameterDeclarations>',
      )
      .replace('parameterAttributes="value" value="10"', 'value="$Speed"');
    fs.writeFileSync(path.join(folder, 'sc', 'main.xosc'), scenario);
    fs.writeFileSync(
      path.join(folder, 'speeds.xosc'),
      distributionFile(
        'sc/main.xosc',
        deterministic(
          '      <DeterministicSingleParameterDistribution parameterName="Speed">\n        <DistributionSet><Element value="12"/><Element value="5"/></DistributionSet>\n      </DeterministicSingleParameterDistribution>\n',
        ),
      ),
    );
    const results = path.join(elsewhere(), 'results');
    const batch = runCli(['batch', path.join(folder, 'speeds.xosc'), '--results', results, '--esmini', esminiBinary, '--keep-runs'], {
      cwd: elsewhere(),
    });
    assert.equal(batch.status, 0, batch.stderr);
    const sc = path.join(folder, 'sc');
    assert.doesNotMatch(batch.stderr, /warning/);
    const kept = path.join(results, 'runs', '0', 'scenario.xosc');
    assert.match(
      fs.readFileSync(kept, 'utf8'),
      new RegExp(`name="Road" parameterType="string" value="${path.join(sc, 'straight_500m.xodr')}"`),
    );
    assert.ok(Math.abs(lastX((await runAlone(kept)).steps) - 106) < 2, 'rerun by itself');
  });

  it('pack --self-contained stores a road named through $Road where its value names it, so the package runs; a value outside the folder is left, with the warning', () => {
    const folder = elsewhere();
    fs.mkdirSync(path.join(folder, 'drive', 'roads'), { recursive: true });
    fs.writeFileSync(path.join(folder, 'drive', 'roads', 'straight_500m.xodr'), road);
    const scenario = (value: string) =>
      drivingScenario('$Road', 'Drive').replace(
        '<ParameterDeclarations></ParameterDeclarations>',
        `<ParameterDeclarations><ParameterDeclaration name="Road" parameterType="string" value="${value}"/></ParameterDeclarations>`,
      );
    fs.writeFileSync(path.join(folder, 'drive', 'main.xosc'), scenario('roads/straight_500m.xodr'));
    for (const input of ['drive', 'drive/main.xosc']) {
      const pack = runCli(['pack', input, '-o', 'p.mosc', '--self-contained'], { cwd: folder });
      assert.equal(pack.status, 0, pack.stderr);
      assert.match(pack.stderr, /wrote p\.mosc \(roads\/straight_500m\.xodr, main\.xosc\)/, input);
      assert.doesNotMatch(pack.stderr, /warning/, input);
      const run = runCli(['run', path.join(folder, 'p.mosc'), '--esmini', esminiBinary, '--check'], { cwd: elsewhere() });
      assert.equal(run.status, 0, run.stderr);
      assert.match(run.stderr, /esmini: 0 errors, 0 warnings; 8\.\d\d s simulated/);
    }
    fs.mkdirSync(path.join(folder, 'inner'));
    fs.writeFileSync(path.join(folder, 'inner', 'main.xosc'), scenario('../drive/roads/straight_500m.xodr'));
    const outside = runCli(['pack', 'inner', '-o', 'q.mosc', '--self-contained'], { cwd: folder });
    assert.equal(outside.status, 0, outside.stderr);
    assert.match(outside.stderr, /wrote q\.mosc \(main\.xosc\)/);
    assert.match(
      outside.stderr,
      /warning: the package reaches the file .*straight_500m\.xodr outside itself[\s\S]*--self-contained stores the file only where/,
    );
  });

  it("a group imported from a file whose own road esmini would not find: the main is clean for esmini and flattens (before: 'source-errors', nothing written)", async () => {
    const folder = elsewhere();
    fs.mkdirSync(path.join(folder, 'groups'));
    fs.mkdirSync(path.join(folder, 'app'));
    // As the paper's library writes its simple scenarios: a CARLA map's name, which esmini needs as a file.
    fs.writeFileSync(path.join(folder, 'groups', 'drive.xosc'), drivingScenario('Town05', 'Drive'));
    fs.writeFileSync(path.join(folder, 'app', 'straight_500m.xodr'), road);
    const outer = outerGroup('Car', 'Ego', [{ file: '../groups/drive.xosc', groups: [{ name: 'Drive' }] }]);
    fs.writeFileSync(path.join(folder, 'app', 'main.xosc'), drivingScenario('straight_500m.xodr', outer));
    const own = runCli(['check', 'groups/drive.xosc', '--simulator', 'esmini'], { cwd: folder });
    assert.equal(own.status, 1, own.stderr);
    assert.match(own.stderr, /groups\/drive\.xosc:\d+:\d+: error: road file 'Town05' is not found/, 'the file itself still says it');
    const check = runCli(['check', 'app/main.xosc', '--simulator', 'esmini'], { cwd: folder });
    assert.equal(check.status, 0, check.stderr);
    assert.match(check.stderr, /checked 1 file: 0 errors, 0 warnings/);
    const flat = path.join(elsewhere(), 'flat.xosc');
    const flatten = runCli(['flatten', 'app/main.xosc', '-o', flat, '--simulator', 'esmini'], { cwd: folder });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.ok(Math.abs(lastX((await runAlone(flat)).steps) - 90) < 2);
  });

  it("export --target carla: the package's road is written beside the export, which names it (before: refused, road not found)", async function () {
    const out = path.join(elsewhere(), 'carla', 'drive.xosc');
    fs.mkdirSync(path.dirname(out));
    const exported = runCli(['export', path.join(root, 'app', 'drive.mosc'), '--target', 'carla', '-o', out], {
      cwd: elsewhere(),
    });
    assert.equal(exported.status, 0, exported.stderr);
    assert.match(exported.stderr, /wrote drive\.files\/straight_500m\.xodr \(a file of the package the export names\)/);
    assert.match(fs.readFileSync(out, 'utf8'), /<LogicFile filepath="drive\.files\/straight_500m\.xodr"\/>/);
    assert.deepEqual(fs.readFileSync(path.join(path.dirname(out), 'drive.files', 'straight_500m.xodr')), road);
    requireCarlaHarness(this);
    const verdict = (await harnessVerdicts([out])).get(out);
    assert.equal(verdict?.status, 'OK', JSON.stringify(verdict));
  });
});

describe('batch --keep-runs: which package files a kept run holds beside its scenario', () => {
  it("never one that would replace the run's own files or lie outside its folder", () => {
    const bytes = new Uint8Array([1]);
    const { files, left } = keptBesideRun(
      [
        'straight_500m.xodr',
        'p.files/Catalogs/VehicleCatalog.xosc',
        'scenario.xosc',
        'esmini.log',
        'trajectories.csv',
        '../road.xodr',
        'a/../straight_500m.xodr',
      ].map((file) => ({ path: file, bytes })),
    );
    assert.deepEqual(
      files.map((file) => file.path),
      ['straight_500m.xodr', path.join('p.files', 'Catalogs', 'VehicleCatalog.xosc')],
    );
    assert.deepEqual(left, ['scenario.xosc', 'esmini.log', 'trajectories.csv', '../road.xodr']);
  });
});
