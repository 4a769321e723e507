import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { mainOf, storeForInputs } from '../../server/src/cli/inputs';
import { ESMINI_LIBRARY_MISSING_HELP, locateEsminiLibrary } from '../../server/src/esmini/library';
import {
  conditionReason,
  prepareScenario,
  Simulation,
  SimulationLoadError,
  StoryboardEvent,
  withPackagedFilesIn,
} from '../../server/src/debug/simulation';
import { esminiCatalogs, esminiRoads } from '../support/esmini';
import { requireEsminiLibrary } from '../support/esminiBinaries';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { temporaryFolder } from '../support/temporaryDirectory';
import { writeTwoCutIns } from '../support/debugScenarios';
import { addParameterControllers, drivingScenario, packageOf } from '../support/fixtures';
import { repoRoot } from '../support/paths';
import { twoCatalogs } from '../support/twoCatalogs';

const cutIn = path.join(openscenarioDir, 'esmini', 'cut-in.xosc');
const roadPath = [esminiRoads, path.join(esminiCatalogs, 'Vehicles')];

/** Every event of a run of the package `input` with no road folder (as a user's package needs none), which starts its Event E, completes, and writes nothing beside the package. */
async function runsPackageToItsEnd(input: string): Promise<StoryboardEvent[]> {
  const events = await runAll(input, undefined, []);
  assert.ok(
    events.some((event) => event.name === 'E' && event.state === 'running'),
    events.map((event) => `${event.time} ${event.name} ${event.state}`).join('\n'),
  );
  assert.equal(events.at(-1)?.state, 'complete');
  assert.deepEqual(fs.readdirSync(path.dirname(input)), [path.basename(input)], 'nothing written beside the package');
  return events;
}

/** Every event of a run, with the steps made when each came; `stepMany` steps by `stepMany(count, () => false)` calls. */
async function runAll(input: string, stepMany?: number, roads = roadPath): Promise<StoryboardEvent[]> {
  return (await runCounted(input, stepMany, roads)).events;
}

async function runCounted(
  input: string,
  stepMany?: number,
  roads = roadPath,
): Promise<{ events: StoryboardEvent[]; stepsAt: number[]; steps: number }> {
  const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [input], {}, roads)), mainOf(input), {
    roadPath: roads,
  });
  const simulation = new Simulation(prepared, { roadPath: roads });
  try {
    const events = simulation.start();
    const stepsAt = events.map(() => 0);
    while (!simulation.ended) {
      const reported = stepMany === undefined ? simulation.step() : simulation.stepMany(stepMany, () => false);
      events.push(...reported);
      stepsAt.push(...reported.map(() => simulation.stepsMade));
    }
    return { events, stepsAt, steps: simulation.stepsMade };
  } finally {
    simulation.close();
  }
}

describe('debug: a scenario run step by step in esmini library', () => {
  before(function () {
    requireEsminiLibrary(this);
    if (!fs.existsSync(cutIn)) this.skip();
  });

  it('leaves nothing in the temporary directory once closed, the shared parent of run folders included', async () => {
    const before = process.env.TMPDIR;
    const tmp = temporaryFolder('m2s-debug-tmpdir-');
    process.env.TMPDIR = tmp;
    try {
      await runAll(cutIn);
    } finally {
      process.env.TMPDIR = before;
    }
    assert.deepEqual(fs.readdirSync(tmp), []);
  });

  it("reports cut-in.xosc's transitions at esmini's times, each on its source line, with why each condition fired", async () => {
    const events = await runAll(cutIn);
    const cutInStart = events.find((event) => event.name === 'CutInEvent' && event.state === 'running');
    assert.ok(cutInStart, 'CutInEvent starts');
    // esmini's own log: `[6.500] [info] CutInEvent standbyState -> startTransition -> runningState`.
    assert.equal(cutInStart.time.toFixed(2), '6.50');
    assert.equal(cutInStart.element, 'CutInAndBrakeStory::CutInAndBrakeAct::CutInAndBrakeSequence::CutInManeuver::CutInEvent');
    assert.equal(cutInStart.mapped?.source.disk, cutIn);
    assert.equal(cutInStart.mapped?.range.start.line, 113, 'the line of <Event name="CutInEvent">');
    const firing = events.find((event) => event.name === 'CutInStartCondition');
    assert.deepEqual(
      {
        quantity: firing?.reason?.quantity,
        measured: firing?.reason?.measured,
        rule: firing?.reason?.rule,
        threshold: firing?.reason?.threshold,
      },
      { quantity: 'HWT', measured: 0.41, rule: '>', threshold: 0.4 },
    );
    assert.equal(firing?.mapped?.condition?.type, 'TimeHeadwayCondition');
    // The condition named by an expression in the file (`${BrakeCondition_HWT + _ + $HeadwayTime_Brake}`) finds its element.
    assert.equal(events.find((event) => event.name === 'BrakeCondition_HWT_0.7')?.mapped?.range.start.line, 161);
    assert.equal(events.at(-1)?.type, 'Storyboard');
    assert.equal(events.at(-1)?.state, 'complete');
  });

  it('steps many steps a call as one a call: the same events after the same steps, and it ends at the step that reported', async () => {
    const one = await runCounted(cutIn);
    const many = await runCounted(cutIn, 500);
    const described = (run: typeof one) =>
      run.events.map((event, index) => `${run.stepsAt[index]} ${event.time} ${event.element} ${event.state}`);
    assert.deepEqual(described(many), described(one));
    assert.equal(many.steps, one.steps);
    assert.ok(one.events.length > 20, 'cut-in.xosc reports its transitions');
  });

  it('stops stepping many at once when told it is interrupted, after the step it was told in', async () => {
    const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [cutIn], {}, roadPath)), mainOf(cutIn), {
      roadPath,
    });
    const simulation = new Simulation(prepared, { roadPath, timeStep: 0.05 });
    try {
      simulation.start();
      // To 1 s, past the transitions of the run's start: nothing is reported from there to the cut-in at 6.5 s.
      while (simulation.stepsMade < 20) simulation.step();
      let asked = 0;
      assert.equal(simulation.stepMany(40, () => ++asked === 3).length, 0);
      assert.equal(simulation.stepsMade, 23);
      assert.equal(simulation.time.toFixed(2), '1.15');
      assert.equal(simulation.stepMany(40, () => false).length, 0, 'nothing reported from 1.15 s to 3.15 s');
      assert.equal(simulation.stepsMade, 63);
    } finally {
      simulation.close();
    }
  });

  it('reaches every flattened copy of a group imported twice, each on the simple scenario line', async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder);
    const events = await runAll(path.join(folder, 'main.xosc'));
    const lane = events.filter((event) => event.name === 'ChangeLane' && event.type === 'Event' && event.state === 'running');
    assert.equal(lane.length, 2, events.map((event) => `${event.time} ${event.element} ${event.state}`).join('\n'));
    assert.notEqual(lane[0].element, lane[1].element);
    for (const event of lane) {
      assert.equal(event.mapped?.source.disk, path.join(folder, 'lane_change.xosc'));
      assert.equal(event.mapped?.range.start.line, laneChangeEventLine(folder));
    }
  });

  it('reads the measured value and threshold of the conditions esmini logs', () => {
    assert.deepEqual(conditionReason('rel_dist: 20.27 > 20.00, edge: rising'), {
      detail: 'rel_dist: 20.27 > 20.00, edge: rising',
      quantity: 'rel_dist',
      measured: 20.27,
      rule: '>',
      threshold: 20,
    });
    assert.equal(conditionReason('0.0500 > 0.0000, edge: none').quantity, 'time');
    assert.equal(conditionReason('CutInAndBrakeAct, RUNNING / START_TRANSITION == START_TRANSITION, edge: none').measured, undefined);
  });

  it("refuses a scenario esmini does not load with esmini's message on its source line", async () => {
    const folder = temporaryFolder();
    const bad = path.join(folder, 'bad-road.xosc');
    fs.writeFileSync(bad, fs.readFileSync(cutIn, 'utf8').replace('../xodr/e6mini.xodr', 'no-such-road.xodr'));
    await assert.rejects(runAll(bad), (error: unknown) => {
      assert.ok(error instanceof SimulationLoadError, String(error));
      assert.match(error.message, /esmini did not load the scenario/);
      assert.ok(error.problems.length > 0);
      return true;
    });
  });

  it("runs a package whose road it holds (issue 27): the road is written into the run's own folder, not looked for beside the package", async () => {
    const folder = temporaryFolder();
    const input = path.join(folder, 'drive.mosc');
    fs.writeFileSync(
      input,
      await packageOf({
        'main.xosc': drivingScenario('straight_500m.xodr', 'Drive'),
        'straight_500m.xodr': fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'), 'utf8'),
      }),
    );
    // No road folder, as a user's package needs none. Before: "Failed to locate OpenDRIVE file .modular2simple-debug.files/straight_500m.xodr".
    const events = await runsPackageToItsEnd(input);
    assert.equal(events.at(-1)?.type, 'Storyboard');
    assert.ok((events.at(-1)?.time ?? 0) >= 8, 'it ran to its own end at 8 s');
    // The flattened text names the road's copy among the package files: that copy is the one esmini is handed, none written besides.
    const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [input], {}, [])), mainOf(input), { roadPath: [] });
    assert.deepEqual(prepared.packagedRoad, { copy: path.join('.modular2simple-debug.files', 'straight_500m.xodr') });
    assert.deepEqual(
      prepared.packagedFiles.map((file) => file.path),
      [path.join('.modular2simple-debug.files', 'straight_500m.xodr')],
    );
  });

  it('runs a package whose road its LogicFile names through a parameter: the copy the flattening returns is the one handed, none written besides', async () => {
    const input = path.join(temporaryFolder(), 'drive.mosc');
    const main = drivingScenario('$Road', 'Drive').replace(
      '<ParameterDeclarations></ParameterDeclarations>',
      '<ParameterDeclarations><ParameterDeclaration name="Road" parameterType="string" value="straight_500m.xodr"/></ParameterDeclarations>',
    );
    assert.match(main, /name="Road"/);
    fs.writeFileSync(
      input,
      await packageOf({ 'main.xosc': main, 'straight_500m.xodr': fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'), 'utf8') }),
    );
    const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [input], {}, [])), mainOf(input), { roadPath: [] });
    assert.deepEqual(
      prepared.packagedFiles.map((file) => file.path),
      ['straight_500m.xodr'],
    );
    assert.deepEqual(prepared.packagedRoad, { copy: 'straight_500m.xodr' });
    await runsPackageToItsEnd(input);
  });

  it("writes a packed road the flattened text names no copy of into the run's folder and hands esmini that", async () => {
    const input = path.join(temporaryFolder(), 'drive.mosc');
    const road = fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'));
    fs.writeFileSync(
      input,
      await packageOf({ 'main.xosc': drivingScenario('straight_500m.xodr', 'Drive'), 'straight_500m.xodr': road.toString('utf8') }),
    );
    const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [input], {}, [])), mainOf(input), { roadPath: [] });
    // As if the flattening had returned no copy (a LogicFile it leaves as written): the road's bytes are all there is.
    const alone = { ...prepared, packagedFiles: [], packagedRoad: { name: 'straight_500m.xodr', bytes: road } };
    const simulation = new Simulation(alone, { roadPath: [] });
    try {
      simulation.start();
      while (!simulation.ended) simulation.stepMany(500, () => false);
      assert.ok(simulation.time >= 8, `it ran to its own end at 8 s, not ${simulation.time}`);
    } finally {
      simulation.close();
    }
  });

  it("runs a package holding its catalogs and road (issue 27): both are written into the run's own folder and named there", async () => {
    const folder = temporaryFolder();
    const input = path.join(folder, 'drive.mosc');
    const main = drivingScenario('straight_500m.xodr', 'Drive')
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations><VehicleCatalog><Directory path="Catalogs/Vehicles"/></VehicleCatalog></CatalogLocations>',
      )
      .replace(
        /<ScenarioObject name="Ego">.*?<\/ScenarioObject>/s,
        '<ScenarioObject name="Ego"><CatalogReference catalogName="VehicleCatalog" entryName="car_red"/></ScenarioObject>',
      );
    assert.match(main, /entryName="car_red"/);
    fs.writeFileSync(
      input,
      await packageOf({
        'main.xosc': main,
        'Catalogs/Vehicles/VehicleCatalog.xosc': twoCatalogs('car_red')['second/VehicleCatalog.xosc'],
        'straight_500m.xodr': fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'), 'utf8'),
      }),
    );
    // Before: esmini was told to read the catalog from .modular2simple-debug.files/Catalogs/Vehicles, which nobody wrote.
    await runsPackageToItsEnd(input);
  });

  it("looks a controller's File up from the main file's folder, inline or from a catalog, as Run in esmini does, and reports what esmini missed loading it (issue 27)", async () => {
    const root = temporaryFolder();
    fs.copyFileSync(path.join(repoRoot, 'test', 'fixtures', 'variations', 'follow.xosc'), path.join(root, 'follow.xosc'));
    // The ego's inline controller and the Lead's ControllerCatalog entry (in catalogs/) name inputs/*.cfg, beside follow.xosc, through $CfgFile.
    addParameterControllers(root);
    const input = path.join(root, 'follow.xosc');
    const loaded = async () => {
      const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [input], {}, roadPath)), mainOf(input), {
        roadPath,
      });
      const simulation = new Simulation(prepared, { roadPath });
      try {
        simulation.start();
        return simulation.loadProblems.filter((problem) => problem.severity === 'error').map((problem) => problem.message);
      } finally {
        simulation.close();
      }
    };
    // Before: esmini ran in the catalog's folder (the first of its search path), and missed both.
    assert.deepEqual(await loaded(), []);
    // Written as it stands in the entry and lying beside the catalog only, where esmini never looks: missed, and said so as a run says it.
    const catalog = path.join(root, 'catalogs', 'ControllerCatalog.xosc');
    fs.writeFileSync(catalog, fs.readFileSync(catalog, 'utf8').replace('filepath="$CfgFile"', 'filepath="lead.cfg"'));
    fs.writeFileSync(path.join(root, 'catalogs', 'lead.cfg'), '');
    const [missed, ...more] = await loaded();
    assert.deepEqual(more, []);
    assert.ok(
      missed?.startsWith('Failed to localize controller file lead.cfg') &&
        missed.includes(`[${path.join(root, 'catalogs', 'lead.cfg')} exists beside the catalog: esmini looks`),
      missed,
    );
  });

  it('names the packaged files by their copies in the private folder, and nothing else', () => {
    const text = `<Directory path=".modular2simple-debug.files/Catalogs/Vehicles"/><LogicFile filepath='.modular2simple-debug.files'/><File filepath="my.modular2simple-debug.files.xosc"/>`;
    assert.equal(
      withPackagedFilesIn(text, '/run/a&b'),
      `<Directory path="/run/a&amp;b/.modular2simple-debug.files/Catalogs/Vehicles"/><LogicFile filepath='/run/a&amp;b/.modular2simple-debug.files'/><File filepath="my.modular2simple-debug.files.xosc"/>`,
    );
  });

  it('names the build when the library is missing', () => {
    const folder = temporaryFolder();
    const location = locateEsminiLibrary(undefined, folder, path.join(folder, '.cache', 'esmini', 'bin'));
    assert.equal(location.found, false);
    assert.ok(!location.found && location.message.includes(ESMINI_LIBRARY_MISSING_HELP));
    assert.match(ESMINI_LIBRARY_MISSING_HELP, /bash \.\.\/shared\/esmini\/build\.sh \.cache\/esmini/);
  });
});

function laneChangeEventLine(folder: string): number {
  return fs
    .readFileSync(path.join(folder, 'lane_change.xosc'), 'utf8')
    .split('\n')
    .findIndex((line) => line.includes('<Event name="ChangeLane"'));
}
