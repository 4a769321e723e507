import * as assert from 'node:assert/strict';
import { describeCondition, describeFiring, storyboardTimeline, type TimelineRow } from '../../common/src/storyboardTimeline';
import { followStoryboard, parseTrace, TraceFormatError, type TraceRecord } from '../../common/src/trace';
import { mainOf, storeForInputs } from '../../server/src/cli/inputs';
import { Flattener } from '../../server/src/core/flatten';
import { prepareScenario, Simulation } from '../../server/src/debug/simulation';
import { traceToEnd } from '../../server/src/debug/trace';
import { requireEsmini } from '../support/esmini';
import { requireEsminiLibrary } from '../support/esminiBinaries';
import { loggedStarts, programRun, TWO_CUT_INS_ROAD_PATH as roadPath, writeTwoCutIns } from '../support/debugScenarios';
import { temporaryFolder } from '../support/temporaryDirectory';

async function traceOf(folder: string): Promise<TraceRecord[]> {
  const prepared = await prepareScenario(new Flattener(storeForInputs([], undefined, [folder])), mainOf(folder), { roadPath, duration: 8 });
  const simulation = new Simulation(prepared, { roadPath, duration: 8 });
  try {
    return traceToEnd(simulation, simulation.start(), folder);
  } finally {
    simulation.close();
  }
}

/** Each row's bars and causes, for comparing two timelines. */
const bars = (rows: TimelineRow[]) =>
  rows.map((candidate) => ({
    element: candidate.element,
    spans: candidate.spans.map((span) => [span.start, span.end, span.cause && describeFiring(span.cause)]),
    started: candidate.started,
  }));

const row = (rows: TimelineRow[], suffix: string) => {
  const found = rows.find((candidate) => candidate.element.endsWith(suffix));
  assert.ok(found, `a row ending ${suffix} among ${rows.map((candidate) => candidate.element).join(', ')}`);
  return found;
};

describe('storyboard timeline of a real esmini run', function () {
  this.timeout(120_000);
  before(function () {
    requireEsminiLibrary(this);
    requireEsmini(this);
  });

  it('gives each copy of a reused group its own rows, at the times esmini logs, with the condition that fired each', async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder);
    const timeline = storyboardTimeline(await traceOf(folder));
    const lead = row(timeline.rows, 'CutInLead.CutIn::CutInManeuver::ChangeLane');
    const vehicle = row(timeline.rows, 'CutInVehicle.CutIn::CutInManeuver::ChangeLane');
    // The program's log has the two starts, without saying which copy is which; the library's callbacks do.
    const program = await programRun(folder);
    assert.deepEqual(
      loggedStarts(program.log, 'ChangeLane'),
      [lead.spans[0].start, vehicle.spans[0].start].sort((a, b) => a - b),
    );
    // Run in esmini's trace, read from the program's log, gives every copy the same bars as the library's callbacks.
    assert.deepEqual(bars(storyboardTimeline(program.trace, 8).rows), bars(timeline.rows));
    assert.deepEqual(
      { group: lead.group, file: lead.file, line: lead.line, spans: lead.spans.length, start: lead.spans[0].start, end: lead.spans[0].end },
      { group: 'CutInLead.CutIn', file: 'lane_change.xosc', line: 116, spans: 1, start: 2.35, end: 3.8 },
    );
    assert.equal(describeFiring(lead.spans[0].cause!), 'RelativeDistanceCondition: rel_dist 30.12 > 30');
    assert.equal(vehicle.group, 'CutInVehicle.CutIn');
    assert.equal(vehicle.spans[0].start, 4.4);
    assert.equal(describeFiring(vehicle.spans[0].cause!), 'RelativeDistanceCondition: rel_dist 12.81 > 12');
    // Both copies' SpeedUp fire in one step: each has its own copy of the condition.
    for (const group of ['CutInLead.CutIn', 'CutInVehicle.CutIn'])
      assert.equal(row(timeline.rows, `${group}::CutInManeuver::SpeedUp`).spans[0].cause?.name, 'SpeedUpStart', group);
    // Storyboard order: each row after its parent, the Action after its Event.
    const order = timeline.rows.map((candidate) => candidate.element);
    assert.ok(order.indexOf(lead.element) < order.indexOf(`${lead.element}::ChangeLane`));
    assert.ok(order.indexOf(lead.element.replace('::CutInManeuver::ChangeLane', '')) < order.indexOf(lead.element));
    assert.equal(timeline.rows[0].type, 'Story');
  });

  it('lists an element that never started with the condition that never became true', async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder, 500);
    const timeline = storyboardTimeline(await traceOf(folder), 8);
    const never = row(timeline.rows, 'CutInLead.CutIn::CutInManeuver::ChangeLane');
    assert.equal(never.started, false);
    assert.deepEqual(never.spans, []);
    assert.deepEqual(never.waitsFor?.map(describeCondition), ['RelativeDistanceCondition greaterThan 500']);
    assert.equal(row(timeline.rows, 'CutInVehicle.CutIn::CutInManeuver::ChangeLane').started, true);
    assert.equal(timeline.end, 8);
  });
});

describe('storyboard trace files', () => {
  it('reads run --trace lines and names the line that is not a record', () => {
    const records = parseTrace('{"time":0,"element":"S","type":"Story","state":"running"}\n\n', 'run.jsonl');
    assert.equal(records.length, 1);
    assert.throws(
      () => parseTrace('{"time":0,"element":"S","type":"Story","state":"running"}\n{"time":', 'run.jsonl'),
      (error: Error) => {
        assert.ok(error instanceof TraceFormatError);
        assert.match(error.message, /^run\.jsonl:2: not JSON/);
        return true;
      },
    );
    assert.throws(() => parseTrace('{"time":"0","element":"S"}', 'run.jsonl'), /run\.jsonl:1: not a trace record/);
  });

  it('a condition firing while its element runs (a StopTrigger) starts nothing; a restart is a second bar', () => {
    const timeline = storyboardTimeline([
      { time: 0, element: 'S', type: 'Story', state: 'running' },
      { time: 0, element: 'S::A', type: 'Act', state: 'standby' },
      { time: 1, element: 'S::A::Go', type: 'Condition', state: 'true', condition: 'SimulationTimeCondition', measured: 1, threshold: 1 },
      { time: 1, element: 'S::A', type: 'Act', state: 'running' },
      { time: 2, element: 'S::A::Halt', type: 'Condition', state: 'true' },
      { time: 2, element: 'S::A', type: 'Act', state: 'complete' },
      { time: 3, element: 'S::A', type: 'Act', state: 'running' },
    ]);
    const act = row(timeline.rows, 'S::A');
    assert.deepEqual(act.spans, [
      { start: 1, end: 2, cause: { name: 'Go', time: 1, condition: 'SimulationTimeCondition', measured: 1, threshold: 1 } },
      { start: 3 },
    ]);
    assert.equal(timeline.end, 3);
  });
});

describe("storyboard timeline of a debug session (the panel's model)", () => {
  const record = (time: number, element: string, state: string): TraceRecord => ({ time, element, type: 'Event', state });

  it('keeps a restarted run apart from the run before it, however their times compare', () => {
    let trace = followStoryboard(undefined, { records: [record(0, 'S::A::G::M::E', 'standby')], time: 0, run: 1 });
    trace = followStoryboard(trace, { records: [record(2, 'S::A::G::M::E', 'running')], time: 2, run: 1 });
    assert.equal(trace.records.length, 2);
    // The restart: its first event is later than the first run's last one; it still starts the trace again.
    const restarted = followStoryboard(trace, { records: [record(3, 'S::A::G::M::E', 'running')], time: 3, run: 2 });
    assert.deepEqual(restarted.records, [record(3, 'S::A::G::M::E', 'running')]);
    assert.equal(restarted.run, 2);
    const row = storyboardTimeline(restarted.records, restarted.time).rows[0];
    assert.deepEqual(
      row.spans.map((span) => span.start),
      [3],
    );
    // A stop (no records) keeps the run and moves its time.
    assert.equal(followStoryboard(restarted, { records: [], time: 4, run: 2 }).time, 4);
    assert.equal(followStoryboard(restarted, { records: [], time: 4, run: 2 }).records.length, 1);
  });
});
