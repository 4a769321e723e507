/** A debug session's run as the bird's-eye view draws it, grown from the adapter's state events (editor-free). */
import type { DebugState } from '../../../common/src/debugState';
import type { LiveTrace } from '../../../common/src/trace';
import { startsOfTrace } from './eventList';
import type { RunTracks } from './messages';

/**
 * `run` with `state` appended (a new run when there is none, or the state is of another run of the session or goes
 * back in time: a restart). An entity
 * first seen late stands where it was first seen for the earlier times; each running element's first start is kept, by its path.
 */
export function appendDebugState(run: RunTracks | undefined, state: DebugState): RunTracks {
  const last = run?.times[run.times.length - 1];
  const sameRun = run && last !== undefined && state.time >= last && (state.run === undefined || state.run === run.sessionRun);
  const grown: RunTracks = sameRun
    ? run
    : {
        label: 'debug session',
        times: [],
        entities: [],
        starts: {},
        notes: [],
        ...(state.run !== undefined ? { sessionRun: state.run } : {}),
      };
  const index = grown.times.length;
  grown.times.push(state.time);
  for (const entity of state.entities) {
    let track = grown.entities.find((candidate) => candidate.name === entity.name);
    if (!track) {
      track = { name: entity.name, length: entity.length, width: entity.width, centerX: entity.centerX, x: [], y: [], hdg: [], speed: [] };
      grown.entities.push(track);
    }
    while (track.x.length <= index) {
      track.x.push(entity.x);
      track.y.push(entity.y);
      track.hdg.push(entity.h);
      track.speed?.push(entity.speed);
    }
  }
  // An entity gone from the state (removed from the scenario) stays where it was last.
  for (const track of grown.entities)
    while (track.x.length <= index) {
      track.x.push(track.x[track.x.length - 1]);
      track.y.push(track.y[track.y.length - 1]);
      track.hdg.push(track.hdg[track.hdg.length - 1]);
      track.speed?.push(track.speed[track.speed.length - 1]);
    }
  for (const element of state.running) grown.starts[element.path] ??= element.since;
  return grown;
}

/**
 * `run` with the starts and causes of the session's storyboard trace (its transitions, each step's), which knows the
 * elements that started and ended between two states (sent about ten times a second); a trace of another run is left out.
 */
export function withSessionTrace(run: RunTracks, trace: LiveTrace | undefined): RunTracks {
  if (!trace || trace.run !== (run.sessionRun ?? trace.run)) return run;
  const traced = startsOfTrace(trace.records);
  return { ...run, starts: { ...run.starts, ...traced.starts }, causes: { ...run.causes, ...traced.causes } };
}
