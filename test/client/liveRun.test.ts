import * as assert from 'node:assert/strict';
import type { DebugState } from '../../common/src/debugState';
import { appendDebugState, withSessionTrace } from '../../client/src/birdsEye/liveRun';
import type { TraceRecord } from '../../common/src/trace';

const car = (name: string, x: number) => ({ name, x, y: -1.5, h: 0, speed: 10, length: 4.5, width: 2, centerX: 1.4 });
const state = (time: number, entities: DebugState['entities'], running: DebugState['running'] = []): DebugState => ({
  time,
  entities,
  running,
  paused: false,
});

describe("client: the bird's-eye view following a debug session", () => {
  it('grows one run from the states, keeping each running element from the time it started', () => {
    let run = appendDebugState(undefined, state(0, [car('Ego', 0)], [{ name: 'CutInStory', path: 'CutInStory', type: 'Story', since: 0 }]));
    run = appendDebugState(
      run,
      state(
        0.5,
        [car('Ego', 5), car('Lead', 50)],
        [{ name: 'CutInEvent', path: 'CutInStory::CutInAct::G::M::CutInEvent', type: 'Event', since: 0.45 }],
      ),
    );
    run = appendDebugState(
      run,
      state(1, [car('Ego', 10)], [{ name: 'CutInEvent', path: 'CutInStory::CutInAct::G::M::CutInEvent', type: 'Event', since: 0.45 }]),
    );
    assert.deepEqual(run.times, [0, 0.5, 1]);
    const ego = run.entities.find((track) => track.name === 'Ego');
    const lead = run.entities.find((track) => track.name === 'Lead');
    assert.deepEqual(ego?.x, [0, 5, 10]);
    // First seen at 0.5 s: there from the start; gone at 1 s: stays where it was last.
    assert.deepEqual(lead?.x, [50, 50, 50]);
    assert.deepEqual(run.starts, { CutInStory: 0, 'CutInStory::CutInAct::G::M::CutInEvent': 0.45 });
    assert.equal(ego?.centerX, 1.4);
  });

  it('starts a new run when the session goes back in time (a restart)', () => {
    const first = appendDebugState(appendDebugState(undefined, state(0, [car('Ego', 0)])), state(3, [car('Ego', 30)]));
    const restarted = appendDebugState(
      first,
      state(0, [car('Ego', 0)], [{ name: 'CutInStory', path: 'CutInStory', type: 'Story', since: 0 }]),
    );
    assert.deepEqual(restarted.times, [0]);
    assert.deepEqual(restarted.entities[0].x, [0]);
    assert.deepEqual(restarted.starts, { CutInStory: 0 });
  });

  it('starts a new run for a restarted session whose first state comes later than the last run got', () => {
    // The last run stopped at 0.5 s; the restarted run's first sample (about every 100 ms of wall time) is at 3 s.
    const first = appendDebugState(appendDebugState(undefined, { ...state(0, [car('Ego', 0)]), run: 1 }), {
      ...state(0.5, [car('Ego', 5)]),
      run: 1,
    });
    const restarted = appendDebugState(first, { ...state(3, [car('Ego', 30)]), run: 2 });
    assert.deepEqual(restarted.times, [3]);
    assert.deepEqual(restarted.entities[0].x, [30]);
    assert.equal(restarted.sessionRun, 2);
    // The same run grows.
    assert.deepEqual(appendDebugState(restarted, { ...state(3.5, [car('Ego', 35)]), run: 2 }).times, [3, 3.5]);
  });

  it("takes the starts of the session's storyboard trace: an event that started and ended between two states is started, not 'not started yet'", () => {
    const event = (name: string) => `S::A::G::M::${name}`;
    const states = {
      ...state(6.5, [car('Ego', 65)], [{ name: 'CutInEvent', path: event('CutInEvent'), type: 'Event', since: 6.5 }]),
      run: 1,
    };
    const run = appendDebugState(appendDebugState(undefined, { ...state(0, [car('Ego', 0)]), run: 1 }), states);
    assert.equal(run.starts[event('SpeedEvent')], undefined);
    const records: TraceRecord[] = [
      { time: 0.05, element: event('SpeedEvent'), type: 'Event', state: 'running' },
      { time: 6.5, element: event('SpeedEvent'), type: 'Event', state: 'complete' },
      { time: 6.5, element: event('CutInEvent'), type: 'Event', state: 'running' },
    ];
    const traced = withSessionTrace(run, { run: 1, records, time: 6.5 });
    assert.equal(traced.starts[event('SpeedEvent')], 0.05);
    assert.equal(traced.starts[event('CutInEvent')], 6.5);
    // A restarted session's trace (run 2) says nothing of run 1.
    assert.equal(withSessionTrace(run, { run: 2, records, time: 6.5 }).starts[event('SpeedEvent')], undefined);
  });
});
