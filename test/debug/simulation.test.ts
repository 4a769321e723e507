import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { mainOf, storeForInputs } from '../../server/src/cli/inputs';
import { ESMINI_LIBRARY_MISSING_HELP, locateEsminiLibrary } from '../../server/src/esmini/library';
import { conditionReason, prepareScenario, Simulation, SimulationLoadError, StoryboardEvent } from '../../server/src/debug/simulation';
import { esminiCatalogs, esminiRoads } from '../support/esmini';
import { requireEsminiLibrary } from '../support/esminiBinaries';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { temporaryFolder } from '../support/temporaryDirectory';
import { writeTwoCutIns } from '../support/debugScenarios';

const cutIn = path.join(openscenarioDir, 'esmini', 'cut-in.xosc');
const roadPath = [esminiRoads, path.join(esminiCatalogs, 'Vehicles')];

async function runAll(input: string): Promise<StoryboardEvent[]> {
  const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [input], {}, roadPath)), mainOf(input), { roadPath });
  const simulation = new Simulation(prepared, { roadPath });
  try {
    const events = simulation.start();
    while (!simulation.ended) events.push(...simulation.step());
    return events;
  } finally {
    simulation.close();
  }
}

describe('debug: a scenario run step by step in esmini library', () => {
  before(function () {
    requireEsminiLibrary(this);
    if (!fs.existsSync(cutIn)) this.skip();
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
