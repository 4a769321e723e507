import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { RunEsminiRequest, RunEsminiResult } from '../../common/src/protocol';
import { SceneRequest, SceneResult } from '../../common/src/sceneProtocol';
import { Flattener } from '../../server/src/core/flatten';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { removeRunFolder, runScenario } from '../../server/src/esmini/run';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { decoyRoad, MODULAR_RUN, modularRunWorkspace } from '../support/modularRun';
import { repoRoot } from '../support/paths';
import { packageOf } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

/** Run in esmini and the bird's-eye view over JSON-RPC: one road file for both, and esmini's remarks about its own files kept apart. */
describe('language server: Run in esmini uses the road the picture draws, and reports a clean run as clean', function () {
  this.timeout(120_000);
  let root: string;
  let client: TestClient;

  beforeEach(async () => {
    root = modularRunWorkspace(temporaryWorkspace({}, 'm2s-server-roads-'));
    client = await TestClient.start({ root });
    await client.indexed();
  });
  afterEach(async () => {
    await client.stop();
    fs.rmSync(root, { recursive: true, force: true });
  });

  const mainUri = () => fileUri(path.join(root, MODULAR_RUN.main));
  const run = (roadPath: string[]) =>
    client.send(RunEsminiRequest, {
      uri: mainUri(),
      esminiPath: esminiBinary,
      roadPath,
      duration: 4,
    }) as Promise<RunEsminiResult>;
  const scene = (roadPath: string[]) =>
    client.connection.sendRequest(SceneRequest, {
      uri: mainUri(),
      roadPath: roadPath.map((folder) => path.resolve(root, folder)),
    }) as Promise<SceneResult>;

  /** Runs and draws with one roadPath; both must name `expected`, and esmini's log must say it loaded it. */
  async function sameRoad(roadPath: string[], expected: string): Promise<RunEsminiResult> {
    const [picture, result] = [await scene(roadPath), await run(roadPath)];
    assert.equal(picture.roadFile?.resolved, expected, picture.problems.join('\n'));
    const mainLines = fs.readFileSync(path.join(root, MODULAR_RUN.main), 'utf8').split('\n');
    const logicLine = mainLines.findIndex((line) => line.includes('<LogicFile '));
    assert.deepEqual(picture.roadFile?.source, {
      uri: mainUri(),
      line: logicLine,
      character: mainLines[logicLine].indexOf('../xodr/e6mini.xodr'),
    });
    assert.deepEqual(picture.problems, [], 'the picture places every entity on the road it draws');
    assert.equal(result.roadFile?.resolved, expected);
    assert.equal(
      result.roadFile?.loaded,
      expected,
      `esmini's log: ${result.log
        .split('\n')
        .filter((line) => /OpenDRIVE/.test(line))
        .join('\n')}`,
    );
    assert.equal(result.outcome, 'ok', `${result.message}\n${JSON.stringify(result.problems, null, 1)}`);
    return result;
  }

  it("a clean modular run on e6mini has 0 errors and 0 warnings; esmini's remarks on its road and 3D models are information with their source", async function () {
    requireEsmini(this);
    const result = await sameRoad([esminiRoads], path.join(root, MODULAR_RUN.road));
    assert.deepEqual(result.problems, [], 'nothing for a toast or the Problems view');
    assert.match(result.message, /^esmini: 0 errors, 0 warnings; 4\.00 s simulated/);
    assert.deepEqual(
      result.flattenProblems.filter((problem) => problem.severity === 'error'),
      [],
    );
    const remarks = new Map((result.remarks ?? []).map((remark) => [remark.message, remark]));
    const railPole = remarks.get('Unsupported object type: rail-pole - interpret as NONE');
    assert.ok(railPole, JSON.stringify(result.remarks));
    assert.equal(railPole.count, 2);
    assert.match(railPole.origin, /RoadManager\.cpp:\d+ RMObject::Str2Type/);
    const sceneGraph = remarks.get('scene graph file ../models/e6mini.osgb not located, using specified file path');
    assert.ok(sceneGraph, JSON.stringify(result.remarks));
    assert.match(sceneGraph.origin, /CommonMini\.cpp:\d+ LocateFile.*ScenarioEngine\.cpp/);
    assert.match(
      remarks.get('3D model car_white.osgb not located, using specified file path')?.origin ?? '',
      /Entities\.cpp:\d+ Object::SetModel3DFullPath/,
    );
    assert.match(
      remarks.get('Unsupported geo reference attr: +no_defs')?.origin ?? '',
      /RoadManager\.cpp:\d+ OpenDrive::ParseGeoLocalization/,
    );
    for (const remark of result.remarks ?? []) assert.ok(remark.why.length > 0, remark.message);
  });

  it('beside the scenario wins over a same-named road file in roadPath, for the run and the picture alike', async function () {
    requireEsmini(this);
    decoyRoad(path.join(root, 'roads'));
    await sameRoad(['roads'], path.join(root, MODULAR_RUN.road));
  });

  it('the file name beside the scenario comes before roadPath, also when roadPath holds the path as written', async function () {
    requireEsmini(this);
    // ../xodr/e6mini.xodr is missing beside xosc/main.xosc; xosc/e6mini.xodr is there, and so is decoy/sub/../xodr/e6mini.xodr.
    fs.renameSync(path.join(root, MODULAR_RUN.road), path.join(root, 'xosc', 'e6mini.xodr'));
    fs.mkdirSync(path.join(root, 'decoy', 'sub'), { recursive: true });
    decoyRoad(path.join(root, 'decoy', 'xodr'));
    await sameRoad(['decoy/sub'], path.join(root, 'xosc', 'e6mini.xodr'));
  });

  it('with nothing beside the scenario, both take the road from roadPath', async function () {
    requireEsmini(this);
    fs.rmSync(path.join(root, MODULAR_RUN.road));
    await sameRoad([esminiRoads], path.join(esminiRoads, 'e6mini.xodr'));
  });

  it("a road esmini finds through a catalog folder (Catalogs/../xodr, as esmini's samples lie): both take it, with no warning", async function () {
    requireEsmini(this);
    const samples = path.join(root, 'samples');
    fs.mkdirSync(path.join(samples, 'Catalogs'), { recursive: true });
    fs.renameSync(path.join(root, 'xodr'), path.join(samples, 'xodr'));
    const main = path.join(root, MODULAR_RUN.main);
    const text = fs
      .readFileSync(main, 'utf8')
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations><VehicleCatalog><Directory path="../samples/Catalogs"/></VehicleCatalog></CatalogLocations>',
      );
    fs.writeFileSync(main, text);
    await client.open(mainUri(), text);
    const result = await sameRoad([], path.join(samples, 'xodr', 'e6mini.xodr'));
    assert.deepEqual(result.problems, []);
  });
});

describe('esmini: a road found in a catalog folder (esmini searches its --path folders)', function () {
  this.timeout(120_000);

  it('is the road the run hands esmini and the one esmini loads: no warning that the picture found none', async function () {
    requireEsmini(this);
    const root = modularRunWorkspace(temporaryWorkspace({}, 'm2s-road-elsewhere-'));
    const catalogs = path.join(root, 'xosc', 'cats');
    fs.mkdirSync(catalogs);
    fs.renameSync(path.join(root, MODULAR_RUN.road), path.join(catalogs, 'e6mini.xodr'));
    const file = path.join(root, MODULAR_RUN.simple);
    fs.writeFileSync(
      file,
      fs
        .readFileSync(file, 'utf8')
        .replace('<LogicFile filepath="../xodr/e6mini.xodr"/>', '<LogicFile filepath="e6mini.xodr"/>')
        .replace('<CatalogLocations/>', '<CatalogLocations><VehicleCatalog><Directory path="cats"/></VehicleCatalog></CatalogLocations>'),
    );
    const result = await runScenario(new Flattener(new ScenarioStore({ root })), diskRef(file), { esminiPath: esminiBinary, duration: 2 });
    try {
      assert.equal(result.roadFile?.resolved, path.join(catalogs, 'e6mini.xodr'));
      assert.equal(result.roadFile?.loaded, path.join(catalogs, 'e6mini.xodr'));
      assert.deepEqual(result.problems, []);
    } finally {
      removeRunFolder(result);
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});

describe('esmini: the bundled examples run without a warning', function () {
  this.timeout(180_000);

  it('each example (a main, simple scenarios, an unpacked and a packed package) runs with no problem at all', async function () {
    requireEsmini(this);
    const examples = path.join(repoRoot, 'examples');
    const store = new ScenarioStore({ root: examples });
    for (const [file, main] of [
      ['main.xosc', diskRef(path.join(examples, 'main.xosc'))],
      ['lane_change.xosc', diskRef(path.join(examples, 'lane_change.xosc'))],
      ['crossing.xosc', diskRef(path.join(examples, 'crossing.xosc'))],
      ['pedestrian/main.xosc', diskRef(path.join(examples, 'pedestrian', 'main.xosc'))],
      ['braking.mosc', childRef(diskRef(path.join(examples, 'braking.mosc')), 'main.xosc')],
    ] as const) {
      const result = await runScenario(new Flattener(store), main, { esminiPath: esminiBinary, roadPath: [esminiRoads], duration: 20 });
      try {
        assert.equal(result.outcome, 'ok', `${file}: ${result.message}`);
        assert.deepEqual(
          result.problems.map((problem) => `${problem.severity}: ${problem.message}`),
          [],
          file,
        );
        assert.equal(result.roadFile?.loaded, path.join(esminiRoads, 'Town05'), file);
      } finally {
        removeRunFolder(result);
      }
    }
  });
});

describe("language server: a road packed in the scenario's .mosc (a self-contained package)", function () {
  this.timeout(120_000);
  let root: string;
  let client: TestClient;

  beforeEach(async () => {
    // The package holds its scenario (esmini's cut-in on e6mini) and the road beside it; beside the package on disk lies a
    // decoy of that name (a straight road, on which the cut-in's positions fail), which flattening never reaches.
    const scenario = fs
      .readFileSync(path.join(repoRoot, 'test', 'fixtures', 'modularRun', MODULAR_RUN.simple), 'utf8')
      .replace('<LogicFile filepath="../xodr/e6mini.xodr"/>', '<LogicFile filepath="e6mini.xodr"/>');
    assert.match(scenario, /<LogicFile filepath="e6mini\.xodr"\/>/);
    root = temporaryWorkspace(
      {
        'pkg.mosc': await packageOf({
          'main.xosc': scenario,
          'e6mini.xodr': fs.readFileSync(path.join(esminiRoads, 'e6mini.xodr'), 'utf8'),
        }),
      },
      'm2s-server-packed-road-',
    );
    client = await TestClient.start({ root });
    await client.indexed();
  });
  afterEach(async () => {
    await client.stop();
    fs.rmSync(root, { recursive: true, force: true });
  });

  const uri = () => `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`;
  const packagedRoad = () => `${path.join(root, 'pkg.mosc')}/e6mini.xodr`;

  for (const decoy of [false, true])
    it(`the picture draws the package's road and Run in esmini loads its copy, with no warning${decoy ? ' (a same-named road beside the package is not taken)' : ''}`, async function () {
      requireEsmini(this);
      if (decoy) decoyRoad(root);
      const picture = (await client.connection.sendRequest(SceneRequest, { uri: uri(), roadPath: [] })) as SceneResult;
      assert.deepEqual(picture.problems, [], 'the picture places every entity on the road it draws');
      assert.equal(picture.roadFile?.resolved, packagedRoad());
      assert.equal(picture.roadFile?.roadCount, 1);
      assert.ok(picture.sections.length > 0, 'the road is drawn');
      const result = (await client.send(RunEsminiRequest, {
        uri: uri(),
        esminiPath: esminiBinary,
        roadPath: [],
        duration: 4,
      })) as RunEsminiResult;
      assert.equal(result.outcome, 'ok', `${result.message}\n${JSON.stringify(result.problems, null, 1)}`);
      assert.deepEqual(
        result.problems.map((problem) => problem.message),
        [],
      );
      assert.match(result.message, /^esmini: 0 errors, 0 warnings; 4\.00 s simulated/);
      assert.match(
        result.roadFile?.loaded ?? '',
        /^\/.*\/scenario\.files\/e6mini\.xodr$/,
        "the package's copy the flattened text names, in the run folder, by its absolute path",
      );
      assert.equal(result.roadFile?.packaged, packagedRoad());
    });
});
