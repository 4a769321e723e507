import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { cliInTemporaryProject } from '../support/cliProject';
import { esminiBinary, requireEsmini, esminiRoads } from '../support/esmini';
import { importedCatalogController, roadScenario, runCli } from '../support/fixtures';
import { libraryDir, repoRoot, requireCorpus } from '../support/paths';
import { listFiles } from '../support/workspace';
import { temporaryFolder } from '../support/temporaryDirectory';

function examplesWith(from?: string, to?: string): string {
  const root = temporaryFolder('m2s-run-');
  fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
  if (from !== undefined && to !== undefined) {
    const file = path.join(root, 'lane_change.xosc');
    fs.writeFileSync(file, fs.readFileSync(file, 'utf8').replace(from, to));
  }
  return root;
}

describe('cli: run in esmini', function () {
  this.timeout(120_000);

  it('wrong usage exits 2; a missing esmini exits 3 and says how to get it', () => {
    assert.equal(runCli(['run']).status, 2);
    assert.match(runCli(['run', 'examples', '--duration', 'soon']).stderr, /--duration takes a positive number/);
    assert.equal(runCli(['run', 'examples', '--bogus']).status, 2);
    const missing = runCli(['run', 'examples', '--esmini', path.join(os.tmpdir(), 'no-such-esmini')], { cwd: repoRoot });
    assert.equal(missing.status, 3);
    assert.match(missing.stderr, /esmini is not at .*build\.sh \.cache\/esmini/s);
    const withoutEsmini = cliInTemporaryProject();
    try {
      const noPath = withoutEsmini.run(['run', path.join(repoRoot, 'examples')], repoRoot, { PATH: '' });
      assert.equal(noPath.status, 3);
      assert.match(noPath.stderr, /esmini was not found/);
    } finally {
      withoutEsmini.remove();
    }
  });

  it('finds the esmini npm start built (.cache/esmini/bin of the project it runs from) with none on PATH', function () {
    requireEsmini(this);
    const withEsmini = cliInTemporaryProject(esminiBinary);
    const root = examplesWith();
    try {
      const run = withEsmini.run(['run', '.', '--check', '--duration', '1', '--road-path', esminiRoads], root, { PATH: '' });
      assert.equal(run.status, 0, run.stderr);
      assert.match(run.stderr, /esmini: 0 errors, \d+ warnings?; 1\.00 s simulated/);
    } finally {
      withEsmini.remove();
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('run --check: 0 for the examples, with the CSV kept where asked; nothing written beside the sources', function () {
    requireEsmini(this);
    const root = examplesWith();
    const out = path.join(temporaryFolder('m2s-run-out-'), 'run.csv');
    const before = listFiles(root);
    const run = runCli(['run', '.', '--check', '--duration', '4', '--road-path', esminiRoads, '--esmini', esminiBinary, '--csv', out], {
      cwd: root,
    });
    assert.equal(run.status, 0, run.stderr);
    assert.match(
      run.stderr,
      /esmini: 0 errors, \d+ warnings?; 4\.00 s simulated: stopped at the 4 s limit set by --duration, before the scenario ended by itself \(the run took \d+\.\d\d s\)/,
    );
    // The examples' vehicles drive: no word of standing still.
    assert.doesNotMatch(run.stderr, /no entity moved/);
    assert.deepEqual(listFiles(root), before);
    const csv = fs.readFileSync(out, 'utf8');
    const rows = csv.trim().split('\n').slice(7);
    assert.equal(Number(rows[rows.length - 1].split(',')[1]), 4);
    // The header named the run's private copy (/tmp/modular2simple-esmini/esmini-run-*/scenario.xosc), removed after the run.
    assert.match(csv, new RegExp(`^Scenario File Name: ${root.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}$`, 'm'));
    assert.doesNotMatch(csv, /esmini-run-/);
  });

  it("esmini's log shown when it fails names the places it looked as from the scenario, not the run's private folder", function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-run-no-road-');
    fs.mkdirSync(path.join(root, 'scenarios'));
    fs.writeFileSync(path.join(root, 'scenarios', 's.xosc'), roadScenario({ logicFile: '../roads/no-such-road.xodr', groups: [] }));
    const run = runCli(['run', 'scenarios/s.xosc', '--esmini', esminiBinary], { cwd: root });
    assert.equal(run.status, 3, run.stderr);
    assert.match(run.stderr, /esmini did not run the scenario .*Failed to locate OpenDRIVE file/);
    // It printed /tmp/modular2simple-esmini/esmini-run-*/../roads/no-such-road.xodr, a folder removed after the run.
    assert.doesNotMatch(run.stderr, /esmini-run-/);
    assert.ok(run.stderr.includes(path.join(root, 'roads', 'no-such-road.xodr')), run.stderr);
  });

  it('a scenario with no stop condition runs its default length, and the message says where to set a longer one', function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-run-no-end-');
    const init =
      '<Private entityRef="Ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="0" laneId="-1" s="10" offset="0"/></Position></TeleportAction></PrivateAction></Private>';
    fs.writeFileSync(path.join(root, 'no-end.xosc'), roadScenario({ logicFile: 'straight_500m.xodr', init, groups: [] }));
    const run = runCli(['run', 'no-end.xosc', '--road-path', esminiRoads, '--esmini', esminiBinary], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(
      run.stderr,
      /30\.00 s simulated: the scenario's StopTrigger has no condition, so it has no end of its own and runs 30 s \(set a duration with --duration to run longer\)/,
    );
    // Its Ego is placed and never driven: the run says so, and where to look.
    assert.match(run.stderr, /\(the run took \d+\.\d\d s\); no entity moved: each stood where the Init placed it for the whole run/);
  });

  it('a road named through a parameter as a relative path runs with no warning that the run may reach another road, and no note of an unused parameter (Euro NCAP, issue 27)', function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-run-road-parameter-');
    fs.mkdirSync(path.join(root, 'roads'));
    fs.mkdirSync(path.join(root, 'scenarios'));
    fs.copyFileSync(path.join(esminiRoads, 'straight_500m.xodr'), path.join(root, 'roads', 'straight_500m.xodr'));
    const init =
      '<Private entityRef="Ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="10" offset="0"/></Position></TeleportAction></PrivateAction></Private>';
    // Scenario_ID, unused (Euro NCAP's distributions set it as a label): a hint for the editor, which run does not print.
    const parameters =
      '<ParameterDeclaration name="Road" parameterType="string" value="../roads/straight_500m.xodr"/><ParameterDeclaration name="Scenario_ID" parameterType="string" value="CCRs"/>';
    fs.writeFileSync(path.join(root, 'scenarios', 's.xosc'), roadScenario({ logicFile: '$Road', parameters, init, groups: [] }));
    const run = runCli(['run', path.join('scenarios', 's.xosc'), '--duration', '1', '--esmini', esminiBinary], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /1\.00 s simulated/);
    assert.doesNotMatch(run.stderr, /: (warning|note):/, run.stderr);
  });

  it("esmini's error printed on the simple scenario's line; one that stops esmini before it runs exits 3 (it did not run), with or without --check", function () {
    requireEsmini(this);
    const root = examplesWith('dynamicsShape="linear" value="3"', 'dynamicsShape="wobbly" value="3"');
    const line =
      fs
        .readFileSync(path.join(root, 'lane_change.xosc'), 'utf8')
        .split('\n')
        .findIndex((text) => text.includes('wobbly')) + 1;
    const args = ['run', 'main.xosc', '--duration', '2', '--road-path', esminiRoads, '--esmini', esminiBinary];
    const checked = runCli([...args, '--check'], { cwd: root });
    assert.equal(checked.status, 3, checked.stderr);
    assert.match(
      checked.stderr,
      new RegExp(`^lane_change\\.xosc:${line}:\\d+: error: Dynamics shape wobbly unexpected.* \\(esmini\\)$`, 'm'),
    );
    const unchecked = runCli(args, { cwd: root });
    assert.equal(unchecked.status, 3, 'esmini refused the scenario (exit 255): a run that did not happen is not reported as done');
    assert.match(
      unchecked.stderr,
      /main\.xosc: error: esmini did not run the scenario \(exit code \d+\): Dynamics shape wobbly unexpected/,
    );
  });

  it('esmini loads the catalog the check found through SCENARIO_PATH, though an earlier SCENARIO_PATH folder holds another catalog of that name (esmini searches its last --path first)', function () {
    requireEsmini(this);
    // The corpus walk's shape: esmini's samples name ../xosc/Catalogs/..., found in esmini's Catalogs/Vehicles, while CARLA's folder holds its own VehicleCatalog.xosc.
    const root = temporaryFolder('m2s-run-catalogs-');
    try {
      const follow = fs.readFileSync(path.join(repoRoot, 'test', 'fixtures', 'variations', 'follow.xosc'), 'utf8');
      const ego = /<Vehicle name="ego_car"[\s\S]*?<\/Vehicle>/.exec(follow)![0];
      const catalog = (name: string, entry: string) =>
        `<?xml version="1.0" encoding="UTF-8"?>\n<OpenSCENARIO>\n  <FileHeader revMajor="1" revMinor="2" date="2026-11-28T00:00:00" description="vehicles" author="modular2simple tests"/>\n  <Catalog name="${name}">\n${entry}\n  </Catalog>\n</OpenSCENARIO>\n`;
      for (const folder of ['scenarios', 'esmini/Catalogs/Vehicles', 'esmini/Catalogs/Controllers', 'carla'])
        fs.mkdirSync(path.join(root, folder), { recursive: true });
      fs.writeFileSync(path.join(root, 'esmini', 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'), catalog('VehicleCatalog', ego));
      fs.writeFileSync(
        path.join(root, 'carla', 'VehicleCatalog.xosc'),
        catalog('VehicleCatalog', ego.replace('name="ego_car"', 'name="vehicle.tesla.model3"')),
      );
      fs.writeFileSync(
        path.join(root, 'scenarios', 'follow.xosc'),
        follow
          .replace(
            '<CatalogLocations/>',
            '<CatalogLocations><VehicleCatalog><Directory path="../xosc/Catalogs/Vehicles"/></VehicleCatalog><ControllerCatalog><Directory path="../xosc/Catalogs/Controllers"/></ControllerCatalog></CatalogLocations>',
          )
          .replace(ego, '<CatalogReference catalogName="VehicleCatalog" entryName="ego_car"/>'),
      );
      const scenarioPath = ['--scenario-path', `${path.join(root, 'esmini', 'Catalogs')}${path.delimiter}${path.join(root, 'carla')}`];
      const checked = runCli(['check', 'scenarios/follow.xosc', ...scenarioPath], { cwd: root });
      assert.equal(checked.status, 0, checked.stderr);
      const run = runCli(['run', 'scenarios/follow.xosc', ...scenarioPath, '--road-path', esminiRoads, '--esmini', esminiBinary], {
        cwd: root,
      });
      assert.equal(run.status, 0, run.stderr);
      assert.doesNotMatch(run.stderr, /Failed to look up entry/);
      assert.match(run.stderr, /esmini: 0 errors, \d+ warnings?; 3\.0\d s simulated/);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('leaves nothing in the temporary directory, the shared parent of run folders included, after a run and after a refusal', function () {
    requireEsmini(this);
    const root = examplesWith();
    const tmp = temporaryFolder('m2s-run-tmpdir-');
    const ran = runCli(['run', 'main.xosc', '--duration', '1', '--road-path', esminiRoads, '--esmini', esminiBinary], {
      cwd: root,
      env: { TMPDIR: tmp },
    });
    assert.equal(ran.status, 0, ran.stderr);
    assert.deepEqual(fs.readdirSync(tmp), []);
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(main, fs.readFileSync(main, 'utf8').replace('maneuverGroupName="CutIn"', 'maneuverGroupName="CutOut"'));
    const refused = runCli(['run', 'main.xosc', '--esmini', esminiBinary], { cwd: root, env: { TMPDIR: tmp } });
    assert.equal(refused.status, 1, refused.stderr);
    assert.deepEqual(fs.readdirSync(tmp), []);
  });

  it('a scenario that cannot be flattened is not run and exits 1', function () {
    requireEsmini(this);
    const root = examplesWith();
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(main, fs.readFileSync(main, 'utf8').replace('maneuverGroupName="CutIn"', 'maneuverGroupName="CutOut"'));
    const run = runCli(['run', 'main.xosc', '--esmini', esminiBinary], { cwd: root });
    assert.equal(run.status, 1);
    assert.match(run.stderr, /has no ManeuverGroup named 'CutOut'/);
    assert.match(run.stderr, /cannot be flattened; nothing was run/);
  });

  it('run takes the bounds --help lists (--max-file-size, --max-depth) and honours them for every file it reads (issue 27)', function () {
    requireEsmini(this);
    const root = examplesWith();
    const simple = path.join(root, 'lane_change.xosc');
    fs.appendFileSync(simple, `<!-- ${'x'.repeat(20_000)} -->\n`);
    const tooLarge = runCli(['run', 'main.xosc', '--max-file-size', '16K', '--esmini', esminiBinary], { cwd: root });
    assert.equal(tooLarge.status, 1, tooLarge.stderr);
    assert.match(tooLarge.stderr, /lane_change\.xosc is too large to read \(\d+ bytes; the limit is 16384, raised with --max-file-size\)/);
    assert.match(tooLarge.stderr, /cannot be flattened; nothing was run/);
    const tooDeep = runCli(['run', 'main.xosc', '--max-depth', '1', '--esmini', esminiBinary], { cwd: root });
    assert.equal(tooDeep.status, 1, tooDeep.stderr);
    assert.match(tooDeep.stderr, /references nest deeper than 1 files: main\.xosc -> lane_change\.xosc/);
    const wrong = runCli(['run', 'main.xosc', '--max-file-size', 'big'], { cwd: root });
    assert.equal(wrong.status, 2);
    assert.match(wrong.stderr, /--max-file-size takes a size such as 64M, not 'big'/);
    assert.match(runCli(['--help']).stdout, /run takes --scenario-path, --road-path,\s+the four --max-\* bounds/);
    assert.match(runCli(['run', '--help']).stdout, /--max-file-size SIZE/);
  });

  it("a controller's File named through a parameter reaches the file beside the scenario, though esmini runs a copy elsewhere (SPEC 11.6, issue 27)", function () {
    requireEsmini(this);
    const controller =
      '<ObjectController><Controller name="acc"><ParameterDeclarations><ParameterDeclaration name="CfgFile" parameterType="string" value="inputs/acc.cfg"/></ParameterDeclarations>' +
      '<Properties><Property name="esminiController" value="ACCController"/><File filepath="$CfgFile"/></Properties></Controller></ObjectController>';
    const root = examplesWith('</Vehicle>\n    </ScenarioObject>', `</Vehicle>\n      ${controller}\n    </ScenarioObject>`);
    const args = ['run', 'lane_change.xosc', '--check', '--duration', '1', '--road-path', esminiRoads, '--esmini', esminiBinary];
    const missing = runCli(args, { cwd: root });
    assert.equal(missing.status, 1, missing.stderr);
    assert.match(missing.stderr, /lane_change\.xosc:\d+:\d+: error: Failed to localize controller file inputs\/acc\.cfg/);
    fs.mkdirSync(path.join(root, 'inputs'));
    fs.writeFileSync(path.join(root, 'inputs', 'acc.cfg'), '');
    const found = runCli(args, { cwd: root });
    assert.equal(found.status, 0, found.stderr);
    // Nor the flattening's warning that the copy, left naming the parameter, may reach another file: the run hands this one.
    assert.doesNotMatch(found.stderr, /controller file|: warning:/);
    assert.match(found.stderr, /esmini: 0 errors/);
  });

  it("a catalog entry's controller File written as it stands reaches the file beside the scenario in a run; flatten elsewhere warns at the reference, as esmini looks it up from the scenario's folder, not the catalog's", function () {
    requireEsmini(this);
    const root = examplesWith(
      '</Vehicle>\n    </ScenarioObject>',
      '</Vehicle>\n      <ObjectController><CatalogReference catalogName="ControllerCatalog" entryName="acc"/></ObjectController>\n    </ScenarioObject>',
    );
    const scenario = path.join(root, 'lane_change.xosc');
    fs.writeFileSync(
      scenario,
      fs
        .readFileSync(scenario, 'utf8')
        .replace(
          '<CatalogLocations/>',
          '<CatalogLocations><ControllerCatalog><Directory path="catalogs/controllers"/></ControllerCatalog></CatalogLocations>',
        ),
    );
    fs.mkdirSync(path.join(root, 'catalogs', 'controllers'), { recursive: true });
    fs.writeFileSync(
      path.join(root, 'catalogs', 'controllers', 'ControllerCatalog.xosc'),
      '<?xml version="1.0"?>\n<OpenSCENARIO><FileHeader revMajor="1" revMinor="2" date="2026-11-29T00:00:00" description="c" author="t"/><Catalog name="ControllerCatalog">' +
        '<Controller name="acc"><Properties><Property name="esminiController" value="ACCController"/><File filepath="inputs/acc.cfg"/></Properties></Controller></Catalog></OpenSCENARIO>\n',
    );
    const args = ['run', 'lane_change.xosc', '--check', '--duration', '1', '--road-path', esminiRoads, '--esmini', esminiBinary];
    // Beside the catalog, esmini does not find it (it never looks there): the message says so.
    const besideCatalog = path.join(root, 'catalogs', 'controllers', 'inputs', 'acc.cfg');
    fs.mkdirSync(path.dirname(besideCatalog));
    fs.writeFileSync(besideCatalog, '');
    const missed = runCli(args, { cwd: root });
    assert.equal(missed.status, 1, missed.stderr);
    assert.ok(
      missed.stderr.includes(
        `error: Failed to localize controller file inputs/acc.cfg, also tried ${path.join(root, 'inputs', 'acc.cfg')} [${besideCatalog} exists beside the catalog: esmini looks`,
      ),
      missed.stderr,
    );
    fs.mkdirSync(path.join(root, 'inputs'));
    fs.writeFileSync(path.join(root, 'inputs', 'acc.cfg'), '');
    const run = runCli(args, { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /controller file|: warning:/);
    const line =
      fs
        .readFileSync(scenario, 'utf8')
        .split('\n')
        .findIndex((text) => text.includes('entryName="acc"')) + 1;
    fs.mkdirSync(path.join(root, 'out'));
    const elsewhere = runCli(['flatten', 'lane_change.xosc', '-o', path.join('out', 'flat.xosc')], { cwd: root });
    assert.equal(elsewhere.status, 0, elsewhere.stderr);
    assert.match(
      elsewhere.stderr,
      new RegExp(
        `lane_change\\.xosc:${line}:\\d+: warning: catalog entry 'acc' names its controller File 'inputs/acc\\.cfg', which esmini looks up .*\\(not the catalog's\\): from here it names ${path.join(root, 'inputs', 'acc.cfg')}; the output in ${path.join(root, 'out')} may reach another file or none`,
      ),
    );
    const beside = runCli(['flatten', 'lane_change.xosc', '-o', 'flat.xosc'], { cwd: root });
    assert.equal(beside.status, 0, beside.stderr);
    assert.doesNotMatch(beside.stderr, /warning/);
    // The same path named through the entry's parameter, its default or the value the reference assigns: warned of alike.
    const catalog = path.join(root, 'catalogs', 'controllers', 'ControllerCatalog.xosc');
    fs.writeFileSync(
      catalog,
      fs
        .readFileSync(catalog, 'utf8')
        .replace(
          '<Properties>',
          '<ParameterDeclarations><ParameterDeclaration name="CfgFile" parameterType="string" value="inputs/acc.cfg"/></ParameterDeclarations><Properties>',
        )
        .replace('filepath="inputs/acc.cfg"', 'filepath="$CfgFile"'),
    );
    fs.writeFileSync(path.join(root, 'inputs', 'other.cfg'), '');
    const assigning = fs
      .readFileSync(scenario, 'utf8')
      .replace(
        '<CatalogReference catalogName="ControllerCatalog" entryName="acc"/>',
        '<CatalogReference catalogName="ControllerCatalog" entryName="acc"><ParameterAssignments><ParameterAssignment parameterRef="CfgFile" value="inputs/other.cfg"/></ParameterAssignments></CatalogReference>',
      );
    for (const [text, value] of [
      [fs.readFileSync(scenario, 'utf8'), 'inputs/acc.cfg'],
      [assigning, 'inputs/other.cfg'],
    ]) {
      fs.writeFileSync(scenario, text);
      const flattened = runCli(['flatten', 'lane_change.xosc', '-o', path.join('out', 'flat.xosc')], { cwd: root });
      assert.equal(flattened.status, 0, flattened.stderr);
      assert.ok(
        flattened.stderr.includes(`names its controller File '$CfgFile' ('${value}'), which esmini looks up`) &&
          flattened.stderr.includes(`from here it names ${path.join(root, ...value.split('/'))};`),
        flattened.stderr,
      );
    }
  });

  it("a catalog entry's controller File used from a group the main imports reaches the file beside the main in a run, as the main's own does (issue 27)", function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-run-imported-controller-');
    importedCatalogController(root, path.join(esminiRoads, 'straight_500m.xodr'));
    fs.mkdirSync(path.join(root, 'inputs'));
    fs.writeFileSync(path.join(root, 'inputs', 'acc.cfg'), '');
    // Before: the run handed the main's own references' Files only, and esmini missed this one from the run's private folder.
    const run = runCli(['run', 'main.xosc', '--check', '--duration', '1', '--esmini', esminiBinary], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.doesNotMatch(run.stderr, /controller file|: warning:/);
    assert.match(run.stderr, /esmini: 0 errors/);
  });

  it('a distribution file or a catalog is not run as a scenario: exit 1, saying what it is and what runs it', function () {
    const root = temporaryFolder('m2s-run-kind-');
    try {
      fs.copyFileSync(path.join(repoRoot, 'test/fixtures/variations/follow.xosc'), path.join(root, 'follow.xosc'));
      fs.copyFileSync(path.join(repoRoot, 'test/fixtures/variations/follow_distribution.xosc'), path.join(root, 'distribution.xosc'));
      fs.writeFileSync(
        path.join(root, 'cars.xosc'),
        '<?xml version="1.0"?>\n<OpenSCENARIO>\n  <FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" description="" author=""/>\n' +
          '  <Catalog name="Cars"/>\n</OpenSCENARIO>\n',
      );
      const distribution = runCli(['run', 'distribution.xosc', '--esmini', esminiBinary], { cwd: root });
      assert.equal(distribution.status, 1, distribution.stderr);
      assert.match(
        distribution.stderr,
        /^distribution\.xosc: error: a ParameterValueDistribution, not a scenario: nothing was run\. Run its concrete scenarios with 'batch distribution\.xosc --results DIR', or write one with 'vary distribution\.xosc --index I -o OUT\.xosc'/m,
      );
      assert.doesNotMatch(distribution.stderr, /Storyboard/);
      const catalog = runCli(['run', 'cars.xosc', '--esmini', esminiBinary], { cwd: root });
      assert.equal(catalog.status, 1, catalog.stderr);
      assert.match(catalog.stderr, /^cars\.xosc: error: a catalog \('Cars'\), not a scenario: nothing was run/m);
      assert.deepEqual(fs.readdirSync(root).sort(), ['cars.xosc', 'distribution.xosc', 'follow.xosc']);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it("a scenario esmini refuses (a 0.9 FileHeader) did not run: esmini's message and exit 3, with or without --check (issue 27)", function () {
    requireEsmini(this);
    const root = examplesWith();
    try {
      const main = path.join(root, 'main.xosc');
      fs.writeFileSync(main, fs.readFileSync(main, 'utf8').replace('revMajor="1" revMinor="0"', 'revMajor="0" revMinor="9"'));
      for (const check of [[], ['--check']]) {
        const run = runCli(['run', 'main.xosc', '--duration', '2', '--road-path', esminiRoads, '--esmini', esminiBinary, ...check], {
          cwd: root,
        });
        assert.equal(run.status, 3, run.stderr);
        assert.match(run.stderr, /main\.xosc: error: esmini did not run the scenario \(exit code \d+\): OpenSCENARIO v0\.9 not supported/);
        assert.doesNotMatch(run.stderr, /placed no entity/);
      }
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('run --check over the whole library (every main.xosc) exits 0', function () {
    requireCorpus(this);
    requireEsmini(this);
    const mains = fs
      .readdirSync(libraryDir)
      .filter((name) => name.startsWith('modular_'))
      .map((name) => path.join(libraryDir, name, 'main.xosc'));
    const run = runCli(['run', ...mains, '--check', '-q', '--duration', '1', '--road-path', esminiRoads, '--esmini', esminiBinary], {
      env: { SCENARIO_PATH: libraryDir },
    });
    assert.equal(run.status, 0, run.stderr);
    assert.equal(run.stderr, '', 'quiet: errors only');
  });
});
