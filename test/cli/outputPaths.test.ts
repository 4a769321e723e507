import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, esminiRoads, EsminiStep, readEsminiCsv, requireEsmini } from '../support/esmini';
import JSZip from 'jszip';
import { deterministic, distributionFile, fileHeader, importedCatalogController, runCli, scenario, simpleGroup } from '../support/fixtures';
import { assertSameRun, cutInWorkspace, esminiCorpus, namedPaths, runAlone } from '../support/outputPaths';
import { temporaryFolder } from '../support/temporaryDirectory';
import { temporaryWorkspace } from '../support/workspace';

/**
 * SPEC 11.6: an output reaches the files its sources reached wherever it is written. A composition of
 * esmini's cut-in (ws/xosc/main.xosc importing the group of ws/xosc/cut-in.xosc, the road in ws/xodr,
 * the catalogs in ws/xosc/Catalogs) is flattened and packed to folders of other depths, and each output
 * is run by esmini with no --path and from an unrelated working folder: it moves exactly as the original.
 */

describe('cli: outputs reach their files wherever they are written (SPEC 11.6), run in esmini', function () {
  let ws: string;
  let original: EsminiStep[];
  let expectedPaths: string[];

  before(async function () {
    requireEsmini(this);
    ws = cutInWorkspace();
    original = (await runAlone(path.join(ws, 'xosc', 'cut-in.xosc'))).steps;
    expectedPaths = [path.join(ws, 'xosc', 'Catalogs', 'Vehicles'), path.join(ws, 'xodr', 'e6mini.xodr')];
  });

  const places: [string, () => string][] = [
    ['beside the main', () => path.join(ws, 'xosc', 'flat.xosc')],
    ['one folder deeper', () => path.join(ws, 'xosc', 'deeper', 'flat.xosc')],
    ['two folders up', () => path.join(ws, '..', '..', `flat-${path.basename(path.dirname(ws))}.xosc`)],
    ['an unrelated temporary folder', () => path.join(temporaryFolder('m2s-paths-out-'), 'flat.xosc')],
  ];
  for (const [where, output] of places) {
    it(`flatten -o ${where}: loads the same road and catalogs and moves as the original`, async () => {
      const target = output();
      fs.mkdirSync(path.dirname(target), { recursive: true });
      const run = runCli(['flatten', path.join(ws, 'xosc', 'main.xosc'), '-o', target], { cwd: temporaryFolder('m2s-paths-cli-') });
      assert.equal(run.status, 0, run.stderr);
      assert.deepEqual(namedPaths(target), expectedPaths);
      assertSameRun((await runAlone(target)).steps, original, where);
    });
  }

  it('flatten --out-dir at another depth: the same road and catalogs', () => {
    const outDir = path.join(ws, 'out', 'dir', 'deeper');
    fs.mkdirSync(outDir, { recursive: true });
    const run = runCli(['flatten', path.join(ws, 'xosc', 'main.xosc'), '--out-dir', outDir], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(run.status, 0, run.stderr);
    assert.deepEqual(namedPaths(path.join(outDir, 'xosc.xosc')), expectedPaths);
  });

  it('flatten beside the main changes no path: the output is the main file with the group copied in', () => {
    const target = path.join(ws, 'xosc', 'beside.xosc');
    assert.equal(runCli(['flatten', 'xosc/main.xosc', '-o', target], { cwd: ws }).status, 0);
    assert.match(
      fs.readFileSync(target, 'utf8'),
      /<Directory path="\.\.\/xosc\/Catalogs\/Vehicles"\/>[\s\S]*<LogicFile filepath="\.\.\/xodr\/e6mini\.xodr"\/>\s*<SceneGraphFile filepath="\.\.\/models\/e6mini\.osgb"\/>/,
    );
  });

  it('flatten to standard output writes absolute paths; a path that does not resolve stays as written', async () => {
    const run = runCli(['flatten', path.join(ws, 'xosc', 'main.xosc')], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(run.status, 0, run.stderr);
    const target = path.join(temporaryFolder('m2s-paths-stdout-'), 'flat.xosc');
    fs.writeFileSync(target, run.stdout);
    assert.deepEqual(namedPaths(target), expectedPaths);
    assert.ok(run.stdout.includes(`filepath="${path.join(ws, 'xodr', 'e6mini.xodr')}"`));
    assert.ok(run.stdout.includes('<SceneGraphFile filepath="../models/e6mini.osgb"/>'));
    assertSameRun((await runAlone(target)).steps, original, 'standard output');
  });

  it('pack to another depth rebases onto the package, warns naming each file outside it, and its flattening runs', async () => {
    const target = path.join(ws, 'packages', 'deep', 'cut-in.mosc');
    fs.mkdirSync(path.dirname(target), { recursive: true });
    const run = runCli(['pack', path.join(ws, 'xosc'), '-o', target], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(run.status, 0, run.stderr);
    assert.match(
      run.stderr,
      new RegExp(`warning: the package reaches the file ${escapeRegExp(path.join(ws, 'xodr', 'e6mini.xodr'))} outside itself`),
    );
    assert.match(
      run.stderr,
      new RegExp(`warning: the package reaches the folder ${escapeRegExp(path.join(ws, 'xosc', 'Catalogs', 'Vehicles'))} outside itself`),
    );
    assert.match(run.stderr, /--self-contained/);
    // The package's catalog directory, now relative to the package's folder, resolves when the package is read.
    const check = runCli(['check', target], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(check.status, 0, check.stderr);
    assert.match(check.stderr, /checked 1 file: 0 errors/);
    // cut-in's negative deceleration rate is its only warning (a range esmini reads as a magnitude), no path of it.
    assert.deepEqual(
      check.stderr.split('\n').filter((line) => / warning: /.test(line) && !/outside the standard's range/.test(line)),
      [],
    );
    const flat = path.join(ws, 'packages', 'flat', 'cut-in.xosc');
    fs.mkdirSync(path.dirname(flat), { recursive: true });
    const flatten = runCli(['flatten', target, '-o', flat], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.deepEqual(namedPaths(flat), expectedPaths);
    assertSameRun((await runAlone(flat)).steps, original, 'flattened package');
  });

  it('pack --self-contained stores the road and catalogs; the package copied alone to a fresh folder flattens and runs the same', async () => {
    const target = path.join(ws, 'packages', 'self', 'cut-in.mosc');
    fs.mkdirSync(path.dirname(target), { recursive: true });
    const run = runCli(['pack', path.join(ws, 'xosc'), '-o', target, '--self-contained'], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /outside itself/);
    const fresh = temporaryFolder('m2s-paths-fresh-');
    fs.copyFileSync(target, path.join(fresh, 'cut-in.mosc'));
    const flatten = runCli(['flatten', 'cut-in.mosc', '-o', 'cut-in.xosc'], { cwd: fresh });
    assert.equal(flatten.status, 0, flatten.stderr);
    for (const named of namedPaths(path.join(fresh, 'cut-in.xosc')))
      assert.ok(named.startsWith(fresh + path.sep), `${named} lies in the fresh folder`);
    assertSameRun((await runAlone(path.join(fresh, 'cut-in.xosc'))).steps, original, 'self-contained package');
    // Run in esmini (the CLI's run) from a private folder, with no road path: the same steps.
    const ran = runCli(['run', 'cut-in.mosc', '--esmini', esminiBinary, '--csv', 'run.csv'], { cwd: fresh });
    assert.equal(ran.status, 0, ran.stderr);
    assertSameRun(readEsminiCsv(path.join(fresh, 'run.csv')), original, 'self-contained package run by the run command');
  });
});

/** A distribution over EgoSpeed of `scenarioFile` (index 0: the scenario's own 108), written as ws/xosc/speeds.xosc. */
function speedDistribution(ws: string, scenarioFile: string): string {
  const file = path.join(ws, 'xosc', `speeds-${path.basename(scenarioFile).replace(/\.[^.]*$/, '')}.xosc`);
  fs.writeFileSync(
    file,
    distributionFile(
      scenarioFile,
      deterministic(`      <DeterministicSingleParameterDistribution parameterName="EgoSpeed">
        <DistributionSet><Element value="108"/><Element value="100"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
`),
      fileHeader({ date: '2026-11-24T00:00:00', description: 'speeds', author: 'm2s' }),
    ),
  );
  return file;
}

/** The workspace's cut-in.xosc with its LogicFile named through a root parameter, `$Road`, of value ../xodr/e6mini.xodr. */
function roadParameterCutIn(ws: string): string {
  const text = fs
    .readFileSync(path.join(ws, 'xosc', 'cut-in.xosc'), 'utf8')
    .replace('<LogicFile filepath="../xodr/e6mini.xodr"/>', '<LogicFile filepath="$Road"/>')
    .replace(
      '<ParameterDeclarations>',
      '<ParameterDeclarations>\n      <ParameterDeclaration name="Road" parameterType="string" value="../xodr/e6mini.xodr"/>',
    );
  assert.match(text, /<LogicFile filepath="\$Road"\/>/);
  return text;
}

describe('cli: concrete scenarios of vary and batch, and the outputs of modularize, reach their files wherever they are written (SPEC 11.6), run in esmini', function () {
  let ws: string;
  let original: EsminiStep[];
  let expectedPaths: string[];

  before(async function () {
    requireEsmini(this);
    ws = cutInWorkspace();
    original = (await runAlone(path.join(ws, 'xosc', 'cut-in.xosc'))).steps;
    expectedPaths = [path.join(ws, 'xosc', 'Catalogs', 'Vehicles'), path.join(ws, 'xodr', 'e6mini.xodr')];
  });

  for (const scenarioFile of ['cut-in.xosc', 'main.xosc']) {
    it(`vary --index 0 -o other/depth/OUT.xosc of ${scenarioFile}: the same road and catalogs, and moves as the original`, async () => {
      const distribution = speedDistribution(ws, scenarioFile);
      const target = path.join(ws, 'other', 'depth', `${scenarioFile}-0.xosc`);
      fs.mkdirSync(path.dirname(target), { recursive: true });
      const run = runCli(['vary', distribution, '--index', '0', '-o', target], { cwd: temporaryFolder('m2s-paths-cli-') });
      assert.equal(run.status, 0, run.stderr);
      assert.deepEqual(namedPaths(target), expectedPaths);
      assertSameRun((await runAlone(target)).steps, original, `vary ${scenarioFile}`);
    });
  }

  it('vary --out-dir at another depth: every concrete scenario names the same road and catalogs; index 0 moves as the original', async () => {
    const distribution = speedDistribution(ws, 'cut-in.xosc');
    const outDir = path.join(temporaryFolder('m2s-paths-out-'), 'a', 'b');
    const run = runCli(['vary', distribution, '--out-dir', outDir], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(run.status, 0, run.stderr);
    assert.deepEqual(fs.readdirSync(outDir).sort(), ['cut-in_0.xosc', 'cut-in_1.xosc']);
    for (const file of fs.readdirSync(outDir)) assert.deepEqual(namedPaths(path.join(outDir, file)), expectedPaths, file);
    assert.match(fs.readFileSync(path.join(outDir, 'cut-in_1.xosc'), 'utf8'), /name="EgoSpeed" parameterType="double" value="100"/);
    assertSameRun((await runAlone(path.join(outDir, 'cut-in_0.xosc'))).steps, original, 'vary --out-dir');
  });

  it("vary --out-dir of a ScenarioFile whose LogicFile is a relative $Road: each concrete scenario's Road names the same road from where it is written, varied or not, and runs as the original", async () => {
    fs.writeFileSync(path.join(ws, 'xosc', 'cut-in-road.xosc'), roadParameterCutIn(ws));
    const roads = `      <DeterministicSingleParameterDistribution parameterName="Road">
        <DistributionSet><Element value="../xodr/e6mini.xodr"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
`;
    for (const [name, varied] of [
      ['speeds', ''],
      ['roads', roads],
    ]) {
      const distribution = path.join(ws, 'xosc', `${name}-road.xosc`);
      fs.writeFileSync(
        distribution,
        fs.readFileSync(speedDistribution(ws, 'cut-in-road.xosc'), 'utf8').replace('<Deterministic>\n', `<Deterministic>\n${varied}`),
      );
      const outDir = path.join(temporaryFolder('m2s-paths-out-'), 'a', 'b');
      const run = runCli(['vary', distribution, '--out-dir', outDir], { cwd: temporaryFolder('m2s-paths-cli-') });
      assert.equal(run.status, 0, run.stderr);
      assert.doesNotMatch(run.stderr, /warning/, name);
      for (const file of fs.readdirSync(outDir)) {
        const road = /name="Road" parameterType="string" value="([^"]*)"/.exec(fs.readFileSync(path.join(outDir, file), 'utf8'))?.[1];
        assert.equal(path.resolve(outDir, road ?? ''), path.join(ws, 'xodr', 'e6mini.xodr'), `${name}: ${file}`);
      }
      assertSameRun((await runAlone(path.join(outDir, 'cut-in-road_0.xosc'))).steps, original, `vary ${name} --out-dir`);
    }
  });

  it('vary --out-dir leaves a $Road that is also used otherwise (here the description) as it is, and says so', () => {
    const withRoad = roadParameterCutIn(ws).replace('description="Basic cut-in"', 'description="$Road"');
    assert.match(withRoad, /description="\$Road"/);
    fs.writeFileSync(path.join(ws, 'xosc', 'cut-in-road-used.xosc'), withRoad);
    const outDir = temporaryFolder('m2s-paths-out-');
    const run = runCli(['vary', speedDistribution(ws, 'cut-in-road-used.xosc'), '--out-dir', outDir], {
      cwd: temporaryFolder('m2s-paths-cli-'),
    });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /warning: '\$Road' gives the relative path '..\/xodr\/e6mini.xodr'/);
    assert.match(
      fs.readFileSync(path.join(outDir, 'cut-in-road-used_0.xosc'), 'utf8'),
      /name="Road" parameterType="string" value="..\/xodr\/e6mini.xodr"/,
    );
  });

  it('vary beside the ScenarioFile changes no path; on standard output the paths are absolute', () => {
    const distribution = speedDistribution(ws, 'cut-in.xosc');
    const target = path.join(ws, 'xosc', 'beside-0.xosc');
    assert.equal(runCli(['vary', distribution, '--index', '0', '-o', target], { cwd: ws }).status, 0);
    assert.equal(fs.readFileSync(target, 'utf8'), fs.readFileSync(path.join(ws, 'xosc', 'cut-in.xosc'), 'utf8'));
    const printed = runCli(['vary', distribution, '--index', '0'], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(printed.status, 0, printed.stderr);
    assert.ok(printed.stdout.includes(`<LogicFile filepath="${path.join(ws, 'xodr', 'e6mini.xodr')}"/>`), printed.stdout);
    assert.ok(printed.stdout.includes(`<Directory path="${path.join(ws, 'xosc', 'Catalogs', 'Vehicles')}"/>`), printed.stdout);
  });

  it('vary and batch of a self-contained .mosc copied alone to a fresh folder: the road and catalogs it holds are written beside each output, which runs as the original', async () => {
    const packed = path.join(temporaryFolder('m2s-paths-pack-'), 'cut-in.mosc');
    const pack = runCli(['pack', path.join(ws, 'xosc'), '-o', packed, '--self-contained'], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(pack.status, 0, pack.stderr);
    const fresh = temporaryFolder('m2s-paths-fresh-');
    fs.copyFileSync(packed, path.join(fresh, 'cut-in.mosc'));
    fs.mkdirSync(path.join(fresh, 'xosc'));
    const distribution = speedDistribution(fresh, '../cut-in.mosc');
    fs.mkdirSync(path.join(fresh, 'out', 'deep'), { recursive: true });
    const run = runCli(['vary', distribution, '--index', '0', '-o', 'out/deep/v0.xosc'], { cwd: fresh });
    assert.equal(run.status, 0, run.stderr);
    for (const named of namedPaths(path.join(fresh, 'out', 'deep', 'v0.xosc')))
      assert.ok(
        named.startsWith(path.join(fresh, 'out', 'deep') + path.sep) && fs.existsSync(named),
        `${named} is written beside the output`,
      );
    assertSameRun((await runAlone(path.join(fresh, 'out', 'deep', 'v0.xosc'))).steps, original, 'vary of a self-contained package');
    const all = runCli(['vary', distribution, '--out-dir', 'all'], { cwd: fresh });
    assert.equal(all.status, 0, all.stderr);
    assertSameRun((await runAlone(path.join(fresh, 'all', 'cut-in_0.xosc'))).steps, original, 'vary --out-dir of a self-contained package');
    // batch runs each in a private folder: the package's files are laid out for the runs, and no --road-path is needed.
    const batch = runCli(['batch', distribution, '--results', 'results', '--duration', '2', '--jobs', '1', '--esmini', esminiBinary], {
      cwd: fresh,
    });
    assert.equal(batch.status, 0, batch.stderr);
    const rows = fs.readFileSync(path.join(fresh, 'results', 'results.json'), 'utf8');
    const csv = fs
      .readFileSync(path.join(fresh, 'results', 'results.csv'), 'utf8')
      .trim()
      .split('\n')
      .slice(1);
    assert.deepEqual(csv.map((row) => row.split(',').slice(0, 2).join(',')).sort(), ['0,limit', '1,limit'], rows);
  });

  it('modularize to another depth, then flatten to a third: the same road and catalogs, and moves as the original', async () => {
    // Two copies of cut-in.xosc in ws/lib share their group; they name ../xodr and ../xosc/Catalogs as the original does.
    fs.mkdirSync(path.join(ws, 'lib'), { recursive: true });
    for (const name of ['a.xosc', 'b.xosc']) fs.copyFileSync(path.join(ws, 'xosc', 'cut-in.xosc'), path.join(ws, 'lib', name));
    fs.mkdirSync(path.join(ws, 'modular', 'deep'), { recursive: true });
    const modularize = runCli(['modularize', path.join(ws, 'lib'), '-o', path.join(ws, 'modular', 'deep', 'out')], {
      cwd: temporaryFolder('m2s-paths-cli-'),
    });
    assert.equal(modularize.status, 0, modularize.stderr);
    const main = path.join(ws, 'modular', 'deep', 'out', 'a.xosc');
    assert.match(fs.readFileSync(main, 'utf8'), /<ScenarioReference /);
    assert.deepEqual(namedPaths(main), expectedPaths);
    const flat = path.join(temporaryFolder('m2s-paths-out-'), 'x', 'flat.xosc');
    fs.mkdirSync(path.dirname(flat), { recursive: true });
    const flatten = runCli(['flatten', main, '-o', flat], { cwd: temporaryFolder('m2s-paths-cli-') });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.deepEqual(namedPaths(flat), expectedPaths);
    assertSameRun((await runAlone(flat)).steps, original, 'modularized and flattened');
  });

  it('vary and flatten of a scenario whose catalogs only --scenario-path finds keep the path as written and warn naming the --path esmini needs, with which the output runs as the original', async () => {
    const own = cutInWorkspace();
    const catalogs = path.join(own, 'lib', 'Catalogs');
    fs.mkdirSync(path.dirname(catalogs));
    fs.renameSync(path.join(own, 'xosc', 'Catalogs'), catalogs);
    const distribution = speedDistribution(own, 'cut-in.xosc');
    const outDir = path.join(temporaryFolder('m2s-paths-out-'), 'a');
    const run = runCli(['vary', distribution, '--out-dir', outDir, '--scenario-path', catalogs], {
      cwd: temporaryFolder('m2s-paths-cli-'),
    });
    assert.equal(run.status, 0, run.stderr);
    const vehicles = path.join(catalogs, 'Vehicles');
    const warnings = run.stderr.split('\n').filter((line) => /warning: catalog folder/.test(line));
    assert.equal(warnings.length, 1, run.stderr);
    assert.match(
      warnings[0],
      new RegExp(
        `warning: catalog folder '\\.\\./xosc/Catalogs/Vehicles' does not resolve from ${escapeRegExp(path.join(own, 'xosc'))}; it was found only through the scenario path \\(${escapeRegExp(vehicles)}\\)\\. .* only when run with --path ${escapeRegExp(vehicles)} \\(`,
      ),
    );
    const written = path.join(outDir, 'cut-in_0.xosc');
    assert.match(fs.readFileSync(written, 'utf8'), /<Directory path="\.\.\/xosc\/Catalogs\/Vehicles"\/>/);
    await assert.rejects(runAlone(written), /Couldn't locate OpenSCENARIO file VehicleCatalog/);
    assertSameRun((await runAlone(written, ['--path', vehicles])).steps, original, 'vary with the --path its warning names');
    // flatten writes the path as it stands too, and says so; -q says nothing.
    const flat = path.join(outDir, 'flat.xosc');
    const flatten = runCli(['flatten', path.join(own, 'xosc', 'cut-in.xosc'), '-o', flat, '--scenario-path', catalogs], {
      cwd: temporaryFolder('m2s-paths-cli-'),
    });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.match(
      flatten.stderr,
      new RegExp(
        `warning: catalog folder '\\.\\./xosc/Catalogs/Vehicles' does not resolve from ${escapeRegExp(outDir)}; .* only when run with --path ${escapeRegExp(vehicles)} \\(`,
      ),
    );
    assertSameRun((await runAlone(flat, ['--path', vehicles])).steps, original, 'flatten with the --path its warning names');
    const quiet = runCli(['flatten', path.join(own, 'xosc', 'cut-in.xosc'), '-o', flat, '--scenario-path', catalogs, '-q'], {
      cwd: temporaryFolder('m2s-paths-cli-'),
    });
    assert.equal(quiet.stderr, '');
  });

  it("batch with no road path runs each concrete scenario on the ScenarioFile's road and catalogs", () => {
    const distribution = speedDistribution(ws, 'cut-in.xosc');
    const results = path.join(temporaryFolder('m2s-paths-batch-'), 'results');
    const run = runCli(['batch', distribution, '--results', results, '--duration', '2', '--jobs', '1', '--esmini', esminiBinary], {
      cwd: temporaryFolder('m2s-paths-cli-'),
    });
    assert.equal(run.status, 0, run.stderr);
    const rows = fs.readFileSync(path.join(results, 'results.csv'), 'utf8').trim().split('\n').slice(1);
    assert.deepEqual(rows.map((row) => row.split(',').slice(0, 2).join(',')).sort(), ['0,limit', '1,limit']);
  });
});

function escapeRegExp(text: string): string {
  return text.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
}

describe('cli: the warnings pack prints about files a package reaches outside itself', () => {
  const withRoad = (logicFile: string) =>
    scenario(simpleGroup('Go')).replace(
      '<Entities>',
      `<ParameterDeclarations>\n    <ParameterDeclaration name="Road" parameterType="string" value="../xodr/road.xodr"/>\n  </ParameterDeclarations>\n  <RoadNetwork>\n    <LogicFile filepath="${logicFile}"/>\n  </RoadNetwork>\n  <Entities>`,
    );

  it('-cxm files: each road named, at its line, with what it is written as in the package', async () => {
    const root = temporaryWorkspace({ 'xodr/road.xodr': '<OpenDRIVE/>', 'xosc/main.xosc': withRoad('../xodr/road.xodr') });
    fs.mkdirSync(path.join(root, 'out', 'deeper'), { recursive: true });
    const run = runCli(['-cxm', 'xosc/main.xosc', 'out/deeper/pkg.mosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(
      run.stderr,
      new RegExp(
        `^xosc/main\\.xosc:\\d+:\\d+: warning: the package reaches the file ${escapeRegExp(path.join(root, 'xodr', 'road.xodr'))} outside itself \\(written '\\.\\./\\.\\./xodr/road\\.xodr', relative to the package's folder\\)`,
        'm',
      ),
    );
    const entries = await unzipped(path.join(root, 'out', 'deeper', 'pkg.mosc'));
    assert.match(entries.get('main.xosc') ?? '', /<LogicFile filepath="\.\.\/\.\.\/xodr\/road\.xodr"\/>/);
  });

  it('a path naming a parameter is left as written and said so', () => {
    const root = temporaryWorkspace({ 'xodr/road.xodr': '<OpenDRIVE/>', 'xosc/main.xosc': withRoad('$Road') });
    const run = runCli(['pack', 'xosc', '-o', 'pkg.mosc', '--self-contained'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(
      run.stderr,
      /warning: the package reaches the file .*road\.xodr outside itself; the package does not run without it\n\s*hint: '\$Road' names a parameter, so it is left as written/,
    );
  });

  it('--self-contained stores the road at a package-relative path and warns about nothing', async () => {
    const root = temporaryWorkspace({ 'xodr/road.xodr': '<OpenDRIVE/>', 'xosc/main.xosc': withRoad('../xodr/road.xodr') });
    const run = runCli(['pack', 'xosc', '-o', 'pkg.mosc', '--self-contained'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /warning/);
    const entries = await unzipped(path.join(root, 'pkg.mosc'));
    assert.deepEqual([...entries.keys()].sort(), ['files/road.xodr', 'main.xosc']);
    assert.match(entries.get('main.xosc') ?? '', /<LogicFile filepath="files\/road\.xodr"\/>/);
  });
});

describe('cli: a self-contained package whose catalogs lie in its own folder (Directory path=".")', () => {
  it('stores them at the package root, and its flattening copied alone writes them beside the output, where it names them', () => {
    const withCatalogHere = scenario('')
      .replace(
        '<Entities>',
        '<CatalogLocations>\n    <VehicleCatalog>\n      <Directory path="."/>\n    </VehicleCatalog>\n  </CatalogLocations>\n  <Entities>',
      )
      .replace(
        '<ScenarioObject name="ego"/>',
        '<ScenarioObject name="ego"><CatalogReference catalogName="VehicleCatalog" entryName="car_white"/></ScenarioObject>',
      );
    const root = temporaryWorkspace({
      'pkg/main.xosc': withCatalogHere,
      'pkg/VehicleCatalog.xosc': fs.readFileSync(path.join(esminiCorpus, 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'), 'utf8'),
    });
    assert.match(withCatalogHere, /entryName="car_white"/);
    const run = runCli(['pack', 'pkg', '-o', 'out.mosc', '--self-contained'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /wrote out\.mosc \(VehicleCatalog\.xosc, main\.xosc\)/);
    const fresh = temporaryFolder('m2s-paths-fresh-');
    fs.copyFileSync(path.join(root, 'out.mosc'), path.join(fresh, 'out.mosc'));
    const flatten = runCli(['flatten', 'out.mosc', '-o', 'flat.xosc'], { cwd: fresh });
    assert.equal(flatten.status, 0, flatten.stderr);
    assert.match(fs.readFileSync(path.join(fresh, 'flat.xosc'), 'utf8'), /<Directory path="flat\.files"\/>/);
    assert.ok(fs.existsSync(path.join(fresh, 'flat.files', 'VehicleCatalog.xosc')));
    const check = runCli(['check', 'flat.xosc'], { cwd: fresh });
    assert.equal(check.status, 0, check.stderr);
    assert.match(check.stderr, /0 errors, 0 warnings/);
  });
});

async function unzipped(file: string): Promise<Map<string, string>> {
  const zip = await JSZip.loadAsync(fs.readFileSync(file));
  const entries = new Map<string, string>();
  for (const [name, entry] of Object.entries(zip.files)) if (!entry.dir) entries.set(name, await entry.async('string'));
  return entries;
}

describe("cli: a catalog controller entry's File, used from a group a main imports, flattened elsewhere", () => {
  it('is warned of at the reference in the imported file, naming the main it is read from; beside the main, nothing (issue 27)', () => {
    const root = temporaryFolder('m2s-imported-controller-');
    const { module } = importedCatalogController(root, path.join(esminiRoads, 'straight_500m.xodr'));
    fs.mkdirSync(path.join(root, 'inputs'));
    fs.writeFileSync(path.join(root, 'inputs', 'acc.cfg'), '');
    const line =
      fs
        .readFileSync(module, 'utf8')
        .split('\n')
        .findIndex((text) => text.includes('entryName="acc"')) + 1;
    fs.mkdirSync(path.join(root, 'out'));
    const elsewhere = runCli(['flatten', 'main.xosc', '-o', path.join('out', 'flat.xosc')], { cwd: root });
    assert.equal(elsewhere.status, 0, elsewhere.stderr);
    const warnings = elsewhere.stderr.split('\n').filter((text) => text.includes(': warning:'));
    assert.equal(warnings.length, 1, elsewhere.stderr);
    assert.ok(
      warnings[0].startsWith(
        `control.xosc:${line}:${fs.readFileSync(module, 'utf8').split('\n')[line - 1].indexOf('acc"') + 1}: warning: catalog entry 'acc' names its controller File 'inputs/acc.cfg', which esmini looks up`,
      ) &&
        warnings[0].includes(
          `from the folder of ${path.join(root, 'main.xosc')}, which imports this group, it names ${path.join(root, 'inputs', 'acc.cfg')}; the output in ${path.join(root, 'out')} may reach another file or none`,
        ),
      elsewhere.stderr,
    );
    const beside = runCli(['flatten', 'main.xosc', '-o', 'flat.xosc'], { cwd: root });
    assert.equal(beside.status, 0, beside.stderr);
    assert.doesNotMatch(beside.stderr, /warning/);
  });
});

describe("cli: a catalog controller entry's File lying only beside a group's file in another folder or package", () => {
  const road = path.join(esminiRoads, 'straight_500m.xodr');
  const warningsOf = (stderr: string) => stderr.split('\n').filter((text) => text.includes(': warning:'));
  const referenceLine = (module: string) =>
    fs
      .readFileSync(module, 'utf8')
      .split('\n')
      .findIndex((text) => text.includes('entryName="acc"')) + 1;

  it('is warned of at the reference, by flatten beside the main, check and run, naming where esmini looks; beside the main, nothing', () => {
    const root = temporaryFolder('m2s-imported-controller-folder-');
    const { module } = importedCatalogController(root, road, 'modules');
    fs.mkdirSync(path.join(root, 'modules', 'inputs'));
    fs.writeFileSync(path.join(root, 'modules', 'inputs', 'acc.cfg'), '');
    const expected =
      `${path.join('modules', 'control.xosc')}:${referenceLine(module)}:` +
      `${fs.readFileSync(module, 'utf8').split('\n')[referenceLine(module) - 1].indexOf('acc"') + 1}: warning: ` +
      `catalog entry 'acc' names its controller File 'inputs/acc.cfg', which esmini looks up from the working folder, then from the folder of ` +
      `the scenario that uses the entry: from the folder of ${path.join(root, 'main.xosc')}, which imports this group, it names ` +
      `${path.join(root, 'inputs', 'acc.cfg')}, which does not exist; the file lies beside this file (${path.join(root, 'modules', 'inputs', 'acc.cfg')})`;
    for (const args of [
      ['flatten', 'main.xosc', '-o', 'flat.xosc'],
      ['check', 'main.xosc'],
      ['run', 'main.xosc', '--esmini', esminiBinary, '--duration', '0.1'],
    ]) {
      const run = runCli(args, { cwd: root });
      assert.equal(run.status, 0, `${args.join(' ')}: ${run.stderr}`);
      const warnings = warningsOf(run.stderr);
      assert.equal(warnings.length, 1, `${args.join(' ')}: ${run.stderr}`);
      assert.ok(warnings[0].startsWith(expected), `${args.join(' ')}:\n${warnings[0]}\n${expected}`);
    }
    fs.mkdirSync(path.join(root, 'inputs'));
    fs.copyFileSync(path.join(root, 'modules', 'inputs', 'acc.cfg'), path.join(root, 'inputs', 'acc.cfg'));
    const beside = runCli(['flatten', 'main.xosc', '-o', 'flat.xosc'], { cwd: root });
    assert.equal(beside.status, 0, beside.stderr);
    assert.doesNotMatch(beside.stderr, /warning/);
  });

  it('is warned of for a File inside the package the group comes from, named inside it', async () => {
    const root = temporaryFolder('m2s-imported-controller-package-');
    const { module } = importedCatalogController(root, road, 'modules');
    const zip = new JSZip();
    zip.file('main.xosc', fs.readFileSync(module));
    zip.file('catalogs/ControllerCatalog.xosc', fs.readFileSync(path.join(root, 'modules', 'catalogs', 'ControllerCatalog.xosc')));
    zip.file('inputs/acc.cfg', '');
    fs.writeFileSync(path.join(root, 'control.mosc'), await zip.generateAsync({ type: 'nodebuffer' }));
    fs.rmSync(path.join(root, 'modules'), { recursive: true });
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(
      main,
      fs.readFileSync(main, 'utf8').replace('scenarioFileName="modules/control.xosc"', 'scenarioFileName="control.mosc"'),
    );
    const flatten = runCli(['flatten', 'main.xosc', '-o', 'flat.xosc'], { cwd: root });
    assert.equal(flatten.status, 0, flatten.stderr);
    const warnings = warningsOf(flatten.stderr);
    assert.equal(warnings.length, 1, flatten.stderr);
    assert.match(
      warnings[0],
      /^control\.mosc\/main\.xosc:\d+:\d+: warning: catalog entry 'acc' names its controller File 'inputs\/acc\.cfg'/,
    );
    assert.ok(
      warnings[0].includes(
        `it names ${path.join(root, 'inputs', 'acc.cfg')}, which does not exist; the file lies beside this file (${path.join(root, 'control.mosc')}/inputs/acc.cfg)`,
      ),
      warnings[0],
    );
  });
});
