import { strict as assert } from 'node:assert';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { LibraryModule, listLibraries } from '../../server/src/core/library';
import { insertModuleGroup, moduleRoles } from '../../server/src/core/libraryInsert';
import { nodeFileSystem } from '../../server/src/core/sources';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { builtInLibraryFolder, libraryFolders } from '../../server/src/libraries';
import { harnessVerdicts, requireCarlaHarness } from '../support/carla';
import { EsminiRun } from '../../common/src/esminiCsv';
import { runExample } from '../../scripts/library-pictures';
import { esminiBinary, requireEsmini } from '../support/esmini';
import { RecordedEnvironment, recordedEnvironments } from '../support/esminiDat';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

/**
 * Every module of the built-in library, verified (issue 28): schema-valid with no warning under `check`, its example
 * main flattened and run in esmini with the behaviour asserted on esmini's own trajectories, from the parameters the
 * module documents (so a changed default is checked as it now is), and its CARLA export built by ScenarioRunner's loader.
 */

type Track = { time: number; x: number; y: number }[];

/** Vehicles of the library: the bounding box's front is 3.75 m ahead of the reference point, its rear 0.75 m behind. */
const FRONT = 3.75;
const REAR = 0.75;
const STEP = 0.05;

function parameter(module: LibraryModule, name: string): number {
  const found = module.parameters.find((candidate) => candidate.name === name);
  assert.ok(found?.defaultValue !== undefined, `${module.name} documents no parameter '${name}' with a default`);
  return Number(found.defaultValue);
}

function trackOf(tracks: Map<string, Track>, name: string): Track {
  const track = tracks.get(name);
  assert.ok(track && track.length > 2, `esmini logged no track for ${name}`);
  return track;
}

/** Speed along x between two consecutive steps. */
function speedAt(track: Track, index: number): number {
  return (track[index + 1].x - track[index].x) / (track[index + 1].time - track[index].time);
}

/** The first step at which the track leaves its first y (a lane change or a crossing starts). */
function lateralStart(track: Track): number {
  const index = track.findIndex((point) => Math.abs(point.y - track[0].y) > 1e-5);
  assert.ok(index > 0, 'the entity never moved sideways');
  return index - 1;
}

function tracksOf(run: EsminiRun): Map<string, Track> {
  return new Map(
    run.entities.map((entity) => [entity.name, Array.from(run.times, (time, index) => ({ time, x: entity.x[index], y: entity.y[index] }))]),
  );
}

const sameTime = (track: Track, time: number) => track.findIndex((point) => point.time >= time - 1e-6);

/** Each sideways move of a track: the step before y starts changing and the first step at which it stops. */
function lateralMoves(track: Track): { start: number; end: number }[] {
  const moves: { start: number; end: number }[] = [];
  for (let index = 0; index < track.length - 1; index++) {
    const moving = Math.abs(track[index + 1].y - track[index].y) > 1e-5;
    const last = moves[moves.length - 1];
    if (moving && last && last.end === index) last.end = index + 1;
    else if (moving) moves.push({ start: index, end: index + 1 });
  }
  return moves;
}

/** The gap between the front of one vehicle and the rear of the vehicle ahead of it, along x. */
const gapAhead = (behind: Track, ahead: Track, index: number) => ahead[index].x - REAR - (behind[index].x + FRONT);

/** What each module's example must show in esmini, from the values its parameters give. */
const BEHAVIOURS: Record<string, (module: LibraryModule, tracks: Map<string, Track>, environments: RecordedEnvironment[]) => void> = {
  'cut-in': (module, tracks) => {
    const [ego, car] = [trackOf(tracks, 'ego'), trackOf(tracks, 'adversary')];
    const speed = parameter(module, 'speed');
    assert.ok(Math.abs(speedAt(car, 2) - speed) < 0.05, `the cutting-in car drives at ${speedAt(car, 2)}, not ${speed} m/s`);
    const start = lateralStart(car);
    const gap = car[start].x - REAR - (ego[start].x + FRONT);
    const closing = Math.abs(speedAt(ego, start) - speedAt(car, start)) * STEP;
    assert.ok(Math.abs(gap - parameter(module, 'gap')) <= closing + 0.05, `the lane change starts at a gap of ${gap.toFixed(2)} m`);
    const end = sameTime(car, car[start].time + parameter(module, 'laneChangeTime') + 2 * STEP);
    assert.ok(end > 0, 'the run ends before the lane change does');
    assert.ok(Math.abs(car[end].y - ego[end].y) < 0.05, `the car ends at y ${car[end].y}, the ego's lane at ${ego[end].y}`);
    assert.ok(car[end].x - REAR > ego[end].x + FRONT, 'the car ends ahead of the ego');
  },
  'cut-out': (module, tracks) => {
    const [ego, lead, target] = [trackOf(tracks, 'ego'), trackOf(tracks, 'lead'), trackOf(tracks, 'target')];
    const start = lateralStart(lead);
    const gap = target[start].x - REAR - (lead[start].x + FRONT);
    assert.ok(
      Math.abs(gap - parameter(module, 'gap')) <= speedAt(lead, start) * STEP + 0.05,
      `the cut-out starts at a gap of ${gap.toFixed(2)} m`,
    );
    const end = sameTime(lead, lead[start].time + parameter(module, 'laneChangeTime') + 2 * STEP);
    const side = parameter(module, 'side');
    assert.ok(Math.abs(lead[end].y - (ego[end].y + side * 3.5)) < 0.05, `the lead ends at y ${lead[end].y}`);
    assert.ok(
      Math.abs(target[end].y - ego[end].y) < 0.05 && target[end].x > ego[end].x,
      'the revealed target stands in the ego lane ahead',
    );
  },
  'lead-brake': (module, tracks) => {
    const [ego, lead] = [trackOf(tracks, 'ego'), trackOf(tracks, 'lead')];
    brakesAsAsked(module, lead, egoHeadway(ego, lead), parameter(module, 'speedAfter'));
  },
  'slow-target': (module, tracks) => steadySpeed(module, trackOf(tracks, 'target')),
  'cyclist-ahead': (module, tracks) => steadySpeed(module, trackOf(tracks, 'cyclist')),
  'pedestrian-crossing': (module, tracks) => crossesAsTheEgoArrives(module, trackOf(tracks, 'ego'), trackOf(tracks, 'pedestrian')),
  'cyclist-crossing': (module, tracks) => crossesAsTheEgoArrives(module, trackOf(tracks, 'ego'), trackOf(tracks, 'cyclist')),
  'lane-change': (module, tracks) => {
    const car = trackOf(tracks, 'adversary');
    const start = lateralStart(car);
    assert.ok(Math.abs(car[start].time - parameter(module, 'startTime')) <= STEP * 1.5, `the lane change starts at ${car[start].time} s`);
    const end = sameTime(car, car[start].time + parameter(module, 'laneChangeTime') + 2 * STEP);
    const expected = car[start].y + parameter(module, 'side') * 3.5;
    assert.ok(Math.abs(car[end].y - expected) < 0.05, `it ends at y ${car[end].y}, not ${expected}`);
    const halfway = sameTime(car, car[start].time + parameter(module, 'laneChangeTime') / 2);
    assert.ok(Math.abs(car[halfway].y - expected) > 0.5, 'it is still changing lane halfway through the time asked');
  },
  'oncoming-vehicle': (module, tracks) => {
    const [ego, oncoming] = [trackOf(tracks, 'ego'), trackOf(tracks, 'oncoming')];
    const speed = parameter(module, 'speed');
    assert.ok(
      Math.abs(speedAt(oncoming, 2) + speed) < 0.05,
      `the oncoming vehicle drives at ${speedAt(oncoming, 2)} m/s along x, not -${speed}`,
    );
    const start = lateralStart(oncoming);
    // Front to front: the oncoming vehicle faces -x, its front 3.75 m behind its reference point in x.
    const gap = oncoming[start].x - FRONT - (ego[start].x + FRONT);
    const closing = (speedAt(ego, start) - speedAt(oncoming, start)) * STEP;
    assert.ok(Math.abs(gap - parameter(module, 'gap')) <= closing + 0.05, `it starts moving over at a gap of ${gap.toFixed(2)} m`);
    const end = sameTime(oncoming, oncoming[start].time + parameter(module, 'laneChangeTime') + 2 * STEP);
    assert.ok(end > 0, 'the run ends before the move over does');
    const expected = ego[end].y + parameter(module, 'offset');
    assert.ok(
      Math.abs(oncoming[end].y - expected) < 0.05,
      `it ends at y ${oncoming[end].y}, not ${expected} (the ego lane and the offset)`,
    );
    assert.ok(oncoming[end].x - FRONT > ego[end].x + FRONT && speedAt(oncoming, end) < 0, 'it ends ahead of the ego, head-on');
    takesTheTimeAsked(module, oncoming);
  },
  'double-lane-change': (module, tracks) => {
    const [ego, lead] = [trackOf(tracks, 'ego'), trackOf(tracks, 'lead')];
    const moves = lateralMoves(lead);
    assert.equal(moves.length, 2, `${moves.length} lane changes, not 2`);
    const [out, back] = moves;
    assert.ok(Math.abs(lead[out.start].time - parameter(module, 'startTime')) <= STEP * 1.5, `it starts out at ${lead[out.start].time} s`);
    takesTheTimeAsked(module, lead);
    const beside = ego[out.end].y + parameter(module, 'side') * 3.5;
    assert.ok(Math.abs(lead[out.end].y - beside) < 0.05, `it moves out to y ${lead[out.end].y}, not ${beside}`);
    const held = lead[back.start].time - lead[out.end].time;
    assert.ok(Math.abs(held - parameter(module, 'hold')) <= STEP * 2.5, `it stays beside for ${held.toFixed(2)} s`);
    const last = lead.length - 1;
    assert.ok(Math.abs(lead[last].y - ego[last].y) < 0.05 && lead[last].x > ego[last].x, 'it ends back in the ego lane, ahead');
  },
  overtaking: (module, tracks) => {
    const [ego, car] = [trackOf(tracks, 'ego'), trackOf(tracks, 'overtaker')];
    const speed = parameter(module, 'speed');
    assert.ok(Math.abs(speedAt(car, 2) - speed) < 0.05, `the overtaking car drives at ${speedAt(car, 2)}, not ${speed} m/s`);
    const moves = lateralMoves(car);
    assert.equal(moves.length, 2, `${moves.length} lane changes, not 2 (out and back)`);
    const [out, back] = moves;
    const headway = gapAhead(car, ego, out.start) / speedAt(car, out.start);
    assert.ok(Math.abs(headway - parameter(module, 'headway')) <= STEP * 1.5, `it pulls out at a headway of ${headway.toFixed(3)} s`);
    const beside = ego[out.end].y + parameter(module, 'side') * 3.5;
    assert.ok(Math.abs(car[out.end].y - beside) < 0.05, `it passes at y ${car[out.end].y}, not ${beside}`);
    const gap = gapAhead(ego, car, back.start);
    const closing = (speedAt(car, back.start) - speedAt(ego, back.start)) * STEP;
    assert.ok(
      Math.abs(gap - parameter(module, 'gap')) <= closing + 0.05,
      `it changes back at a gap of ${gap.toFixed(2)} m ahead of the ego`,
    );
    takesTheTimeAsked(module, car);
    assert.ok(
      Math.abs(car[back.end].y - ego[back.end].y) < 0.05 && gapAhead(ego, car, back.end) > 0,
      'it ends in the ego lane, ahead of it',
    );
  },
  'swerving-lead': (module, tracks) => {
    const lead = trackOf(tracks, 'lead');
    const moves = lateralMoves(lead);
    assert.equal(moves.length, 2, `${moves.length} sideways moves, not 2 (out and back)`);
    const [out, back] = moves;
    // esmini's lane offset moves one step later than a lane change does: the condition holds a step after the time, the move a step after that.
    assert.ok(Math.abs(lead[out.start].time - parameter(module, 'startTime')) <= STEP * 2.5, `it swerves at ${lead[out.start].time} s`);
    const offset = lead[out.end].y - lead[0].y;
    assert.ok(
      Math.abs(offset - parameter(module, 'offset')) < 0.01,
      `it swerves ${offset.toFixed(3)} m, not ${parameter(module, 'offset')}`,
    );
    const held = lead[back.start].time - lead[out.end].time;
    assert.ok(Math.abs(held - parameter(module, 'hold')) <= STEP * 2.5, `it stays at the offset for ${held.toFixed(2)} s`);
    let largest = 0;
    for (let index = 1; index < lead.length - 1; index++)
      largest = Math.max(largest, Math.abs(lead[index + 1].y - 2 * lead[index].y + lead[index - 1].y) / STEP ** 2);
    const asked = parameter(module, 'lateralAcceleration');
    assert.ok(Math.abs(largest - asked) <= asked * 0.05, `its largest lateral acceleration is ${largest.toFixed(2)} m/s², not ${asked}`);
    assert.ok(Math.abs(lead[back.end].y - lead[0].y) < 0.01, 'it swerves back to its lane centre');
  },
  'traffic-jam-end': (module, tracks) => {
    const ego = trackOf(tracks, 'ego');
    const jam1 = trackOf(tracks, 'jam1');
    const start = brakesAsAsked(module, jam1, egoHeadway(ego, jam1), parameter(module, 'jamSpeed'));
    for (const name of ['jam2', 'jam3']) {
      const vehicle = trackOf(tracks, name);
      const last = vehicle.length - 2;
      const brakesFrom = vehicle.findIndex(
        (_, index) => index < vehicle.length - 1 && speedAt(vehicle, index) < speedAt(vehicle, 0) - 0.01,
      );
      assert.equal(brakesFrom, start, `${name} brakes at step ${brakesFrom}, jam1 at ${start}`);
      assert.ok(Math.abs(speedAt(vehicle, last) - parameter(module, 'jamSpeed')) < 0.05, `${name} ends at ${speedAt(vehicle, last)} m/s`);
    }
  },
  'weather-light-change': (module, _tracks, environments) => {
    assert.equal(environments.length, 1, `esmini recorded ${environments.length} environment changes, not 1`);
    const [changed] = environments;
    // The condition holds a step after the time asked (its log says the action ran then); the recording stamps it a step later.
    assert.ok(Math.abs(changed.time - parameter(module, 'startTime')) <= STEP * 2.5, `the environment changes at ${changed.time} s`);
    const visibility = parameter(module, 'visibility');
    assert.equal(changed.visibilityRange, visibility, 'the fog');
    assert.ok(Math.abs(changed.fogVisibilityRangeFactor - 1 / (visibility + 1)) < 1e-9, 'the fog factor');
    assert.equal(changed.frictionScaleFactor, parameter(module, 'friction'), 'the road friction');
    assert.ok(Math.abs(changed.sunIntensityFactor - parameter(module, 'sunIntensity') / 100_000) < 1e-9, 'the sun intensity');
  },
  'highway-merge': (module, tracks) => {
    const [ego, car] = [trackOf(tracks, 'ego'), trackOf(tracks, 'merging')];
    const rampSpeed = speedAt(car, 0);
    const [acceleration, speed] = [parameter(module, 'acceleration'), parameter(module, 'speed')];
    const middle = Math.floor((speed - rampSpeed) / acceleration / STEP / 2);
    const measured = (speedAt(car, middle + 4) - speedAt(car, middle - 4)) / (8 * STEP);
    assert.ok(Math.abs(measured - acceleration) < 0.1, `it accelerates at ${measured.toFixed(2)} m/s², not ${acceleration}`);
    assert.ok(Math.abs(speedAt(car, car.length - 2) - speed) < 0.05, `it ends at ${speedAt(car, car.length - 2)} m/s, not ${speed}`);
    const start = lateralStart(car);
    const gap = gapAhead(ego, car, start);
    const closing = Math.abs(speedAt(ego, start) - speedAt(car, start)) * STEP;
    assert.ok(Math.abs(gap - parameter(module, 'gap')) <= closing + 0.05, `it starts merging at a gap of ${gap.toFixed(2)} m`);
    const end = sameTime(car, car[start].time + parameter(module, 'laneChangeTime') + 2 * STEP);
    assert.ok(end > 0, 'the run ends before the merge does');
    assert.ok(
      Math.abs(car[end].y - ego[end].y) < 0.05 && gapAhead(ego, car, end) > 0,
      `it ends at y ${car[end].y}, not ahead in the ego lane`,
    );
    assert.ok(car[end].x < accelerationLaneEnd(module), 'it merges before its acceleration lane starts narrowing');
    takesTheTimeAsked(module, car);
  },
  'crossing-path': (module, tracks) => {
    const [ego, crossing] = [trackOf(tracks, 'ego'), trackOf(tracks, 'crossing')];
    // The conflict point is fixed by the crossroads: the ego's lane (y -1.75) across the crossing vehicle's (x 1.75).
    const crosses = crossing.findIndex((point) => point.y >= -1.75);
    const egoThere = ego.findIndex((point) => point.x >= parameter(module, 'egoAt'));
    assert.ok(crosses > 0 && egoThere > 0, 'the crossing vehicle or the ego never arrives');
    assert.ok(
      Math.abs(crossing[crosses].time - ego[egoThere].time) <= STEP * 2,
      `the crossing vehicle reaches the conflict point at ${crossing[crosses].time} s, the ego its point at ${ego[egoThere].time} s`,
    );
    const arrival = (crossing[crosses].y - crossing[crosses - 1].y) / STEP;
    const asked = parameter(module, 'arrivalSpeed');
    assert.ok(Math.abs(arrival - asked) < 0.1, `it arrives at ${arrival.toFixed(2)} m/s, not ${asked}`);
    assert.ok(
      crossing.every((point) => Math.abs(point.x - 1.75) < 0.01),
      'it drives straight across, in its lane',
    );
    assert.ok(ego[ego.length - 1].x > 10, 'the ego drives on through the junction');
  },
  'turn-across-path': (module, tracks) => turnsAcrossAsSynchronized(tracks, parameter(module, 'egoAt'), parameter(module, 'turnSpeed')),
  'arrive-leave-site': (module, tracks) =>
    arrivesStaysLeaves(tracks, {
      brakeGap: parameter(module, 'brakeGap'),
      brakingDistance: parameter(module, 'brakingDistance'),
      stay: parameter(module, 'stay'),
      leaveSpeed: parameter(module, 'leaveSpeed'),
      passOffset: parameter(module, 'passOffset'),
      lateralAcceleration: parameter(module, 'lateralAcceleration'),
    }),
  'rear-end-collision': (module, tracks) => runsIntoTheOneAhead(module, trackOf(tracks, 'follower'), trackOf(tracks, 'ahead')),
  'ttc-brake': (module, tracks) => {
    const [follower, ahead] = [trackOf(tracks, 'follower'), trackOf(tracks, 'ahead')];
    const timeToCollision = (index: number) => gapAhead(follower, ahead, index) / (speedAt(follower, index) - speedAt(ahead, index));
    brakesAsAsked(module, follower, { name: 'time to collision', value: timeToCollision, asked: 'ttc' }, 0);
    assert.ok(
      follower.every((_, index) => gapAhead(follower, ahead, index) > 0),
      'it stops short of the vehicle ahead',
    );
  },
};

/**
 * The follower sets off at startTime at the speed asked (at once), never slows before the vehicle ahead, and stops dead
 * at the step its front reaches the other's rear: the boxes touch, overlapping by less than a step's travel.
 */
function runsIntoTheOneAhead(module: LibraryModule, follower: Track, ahead: Track): void {
  const speed = parameter(module, 'speed');
  const moving = follower.findIndex((_, index) => index < follower.length - 1 && speedAt(follower, index) > 1e-6);
  assert.ok(moving >= 0, 'the follower never moves');
  assert.ok(
    Math.abs(follower[moving].time - parameter(module, 'startTime')) <= STEP * 1.5,
    `it sets off at ${follower[moving].time} s, not ${parameter(module, 'startTime')}`,
  );
  const stops = follower.findIndex((_, index) => index > moving && index < follower.length - 1 && speedAt(follower, index) < 1e-6);
  assert.ok(stops > 0, 'it never stops');
  for (let index = moving; index < stops; index++)
    assert.ok(
      Math.abs(speedAt(follower, index) - speed) < 0.05,
      `at ${follower[index].time} s it drives at ${speedAt(follower, index)}, not ${speed} m/s`,
    );
  const gap = gapAhead(follower, ahead, stops);
  assert.ok(
    gap <= 0.1 + 1e-6 && gap > 0.1 - speed * STEP - 0.05,
    `it stops at a gap of ${gap.toFixed(2)} m to the vehicle ahead, not at its rear`,
  );
  const last = follower.length - 1;
  assert.ok(Math.abs(follower[last].x - follower[stops].x) < 1e-6, 'it moves again after the impact');
}

type SiteVisit = {
  brakeGap: number;
  brakingDistance: number;
  stay: number;
  leaveSpeed: number;
  passOffset: number;
  lateralAcceleration: number;
};

/**
 * The responder brakes once its gap to the standing site vehicle is below brakeGap, evenly over brakingDistance to a
 * stand, stands for `stay`, then drives off to leaveSpeed, pulled out by passOffset (with lateralAcceleration at its largest
 * sideways), past the site without touching it.
 */
function arrivesStaysLeaves(tracks: Map<string, Track>, asked: SiteVisit): void {
  const [site, responder] = [trackOf(tracks, 'site'), trackOf(tracks, 'responder')];
  const approach = speedAt(responder, 0);
  const start = responder.findIndex((_, index) => index < responder.length - 1 && speedAt(responder, index) < approach - 0.01);
  assert.ok(start > 0, 'the responder never brakes');
  // The condition holds at the step the braking starts from, sampled once a step: the gap is within a step's travel of the one asked.
  const gap = gapAhead(responder, site, start);
  assert.ok(
    gap <= asked.brakeGap + 1e-6 && gap > asked.brakeGap - approach * STEP - 0.05,
    `it starts braking at a gap of ${gap.toFixed(2)} m, not ${asked.brakeGap}`,
  );
  const stands = responder.findIndex((_, index) => index > start && index < responder.length - 1 && speedAt(responder, index) < 1e-6);
  assert.ok(stands > 0, 'it never stands still');
  const braked = responder[stands].x - responder[start].x;
  assert.ok(
    Math.abs(braked - asked.brakingDistance) <= (approach * STEP) / 2 + 0.05,
    `it brakes over ${braked.toFixed(2)} m, not ${asked.brakingDistance}`,
  );
  const even = approach ** 2 / (2 * asked.brakingDistance);
  const middle = start + Math.floor((stands - start) / 2);
  const measured = (speedAt(responder, middle - 4) - speedAt(responder, middle + 4)) / (8 * STEP);
  assert.ok(Math.abs(measured - even) < 0.1, `it decelerates at ${measured.toFixed(2)} m/s², not an even ${even.toFixed(2)}`);
  const leaves = responder.findIndex((_, index) => index > stands && index < responder.length - 1 && speedAt(responder, index) > 1e-6);
  assert.ok(leaves > 0, 'it never leaves');
  const stood = responder[leaves].time - responder[stands].time;
  assert.ok(Math.abs(stood - asked.stay) <= STEP * 2.5, `it stands at the site for ${stood.toFixed(2)} s, not ${asked.stay}`);
  const last = responder.length - 2;
  assert.ok(
    Math.abs(speedAt(responder, last) - asked.leaveSpeed) < 0.05,
    `it drives off at ${speedAt(responder, last).toFixed(2)} m/s, not ${asked.leaveSpeed}`,
  );
  const offset = responder[last].y - responder[stands].y;
  assert.ok(Math.abs(offset - asked.passOffset) < 0.01, `it pulls out ${offset.toFixed(3)} m, not ${asked.passOffset}`);
  let largest = 0;
  for (let index = leaves; index < responder.length - 1; index++)
    largest = Math.max(largest, Math.abs(responder[index + 1].y - 2 * responder[index].y + responder[index - 1].y) / STEP ** 2);
  assert.ok(
    Math.abs(largest - asked.lateralAcceleration) <= asked.lateralAcceleration * 0.05,
    `its largest lateral acceleration is ${largest.toFixed(2)} m/s², not ${asked.lateralAcceleration}`,
  );
  // Past the site: its rear ahead of the site's front by the end, and never beside it closer than the boxes' width (2 m).
  assert.ok(responder[last].x - REAR > site[last].x + FRONT, 'it ends past the site');
  for (let index = 0; index < responder.length; index++) {
    const alongside = responder[index].x + FRONT > site[index].x - REAR && responder[index].x - REAR < site[index].x + FRONT;
    assert.ok(
      !alongside || Math.abs(responder[index].y - site[index].y) >= 2,
      `at ${responder[index].time} s it touches the site (${(responder[index].y - site[index].y).toFixed(2)} m aside)`,
    );
  }
}

/** The crossroads' left turn (road 103, lane -1): an arc of radius 10 + 1.75 about (10, -10), across the ego's lane (y -1.75). */
const TURN_CENTRE = { x: 10, y: -10 };
const TURN_RADIUS = 11.75;

/**
 * The turning vehicle comes from the opposite arm, follows the left turn into the south arm, and crosses the ego's lane
 * centre as the ego's reference point reaches `egoAt`, at `turnSpeed`.
 */
function turnsAcrossAsSynchronized(tracks: Map<string, Track>, egoAt: number, turnSpeed: number): void {
  const [ego, turning] = [trackOf(tracks, 'ego'), trackOf(tracks, 'turning')];
  assert.ok(
    Math.abs(turning[0].y - 1.75) < 0.01 && turning[1].x < turning[0].x,
    "it starts in the ego's opposite lane, driving towards it",
  );
  const inJunction = turning.filter((point) => point.x < TURN_CENTRE.x && point.y > TURN_CENTRE.y);
  assert.ok(inJunction.length > 5, 'it never drives through the junction');
  for (const point of inJunction) {
    const radius = Math.hypot(point.x - TURN_CENTRE.x, point.y - TURN_CENTRE.y);
    assert.ok(
      Math.abs(radius - TURN_RADIUS) < 0.05,
      `at ${point.time} s it is ${radius.toFixed(2)} m from the turn's centre, off the turn`,
    );
  }
  const last = turning[turning.length - 1];
  assert.ok(
    Math.abs(last.x + 1.75) < 0.01 && last.y < TURN_CENTRE.y - 5,
    `it ends at (${last.x}, ${last.y}), not in the south arm's southbound lane`,
  );
  const crosses = turning.findIndex((point) => point.y <= -1.75);
  const egoThere = ego.findIndex((point) => point.x >= egoAt);
  assert.ok(crosses > 0 && egoThere > 0, "the turning vehicle never crosses the ego's lane, or the ego never arrives");
  assert.ok(
    Math.abs(turning[crosses].time - ego[egoThere].time) <= STEP * 2,
    `it crosses the ego's lane at ${turning[crosses].time} s, the ego reaches x ${egoAt} at ${ego[egoThere].time} s`,
  );
  const speed = Math.hypot(turning[crosses].x - turning[crosses - 1].x, turning[crosses].y - turning[crosses - 1].y) / STEP;
  assert.ok(Math.abs(speed - turnSpeed) < 0.1, `it crosses at ${speed.toFixed(2)} m/s, not ${turnSpeed}`);
  assert.ok(ego[ego.length - 1].x > 10, 'the ego drives on through the junction');
}

/** Each lane change of the track takes the lane-change time asked (from the step before it moves to the first it stands still). */
function takesTheTimeAsked(module: LibraryModule, track: Track): void {
  const laneChangeTime = parameter(module, 'laneChangeTime');
  for (const move of lateralMoves(track)) {
    const took = track[move.end].time - track[move.start].time;
    assert.ok(Math.abs(took - laneChangeTime) <= STEP * 2, `a lane change takes ${took.toFixed(2)} s, not ${laneChangeTime}`);
  }
}

/** Where the acceleration lane (-3) of a module's road starts narrowing: the s of the section where its width is a cubic. */
function accelerationLaneEnd(module: LibraryModule): number {
  const text = fs.readFileSync(module.example ?? '', 'utf8');
  const road = /<LogicFile\s+filepath="([^"]+)"/.exec(text)?.[1] ?? '';
  const network = parseOpenDrive(fs.readFileSync(path.resolve(path.dirname(module.example ?? ''), road), 'utf8'));
  const section = network.roads[0].laneSections.find((candidate) =>
    candidate.lanes.some((lane) => lane.id === -3 && lane.widths.some((width) => width.c !== 0)),
  );
  assert.ok(section, `${road} has no narrowing acceleration lane`);
  return section.s;
}

/** The lead brakes once the ego's headway to it is the one asked, at the deceleration asked, down to the speed asked; returns the step it starts at. */
function brakesAsAsked(module: LibraryModule, braking: Track, condition: BrakeCondition, after: number): number {
  const before = speedAt(braking, 0);
  const start = braking.findIndex((_, index) => index < braking.length - 1 && speedAt(braking, index) < before - 0.01);
  assert.ok(start > 0, 'it never brakes');
  // The condition held at the step before the speed first drops.
  const measured = condition.value(start - 1);
  const asked = parameter(module, condition.asked);
  assert.ok(
    Math.abs(measured - asked) <= STEP * 1.5,
    `the braking starts at a ${condition.name} of ${measured.toFixed(3)} s, not ${asked}`,
  );
  const deceleration = parameter(module, 'deceleration');
  const middle = start + Math.floor((before - after) / deceleration / STEP / 2);
  const rate = (speedAt(braking, middle - 4) - speedAt(braking, middle + 4)) / (8 * STEP);
  assert.ok(Math.abs(rate - deceleration) < 0.1, `it decelerates at ${rate.toFixed(2)} m/s², not ${deceleration}`);
  const last = braking.length - 2;
  assert.ok(Math.abs(speedAt(braking, last) - after) < 0.05, `it ends at ${speedAt(braking, last)} m/s, not ${after}`);
  return start;
}

/** What starts a braking, measured at a step, and the module's parameter that asks for it. */
type BrakeCondition = { name: string; value: (index: number) => number; asked: string };

/** The ego's time headway to the car ahead of it (gap / ego speed), against the module's `headway`. */
function egoHeadway(ego: Track, lead: Track): BrakeCondition {
  return { name: 'headway', value: (index) => gapAhead(ego, lead, index) / speedAt(ego, index), asked: 'headway' };
}

/** The actor keeps the speed asked from the start. */
function steadySpeed(module: LibraryModule, target: Track): void {
  const speed = parameter(module, 'speed');
  for (let index = 1; index < target.length - 1; index++)
    assert.ok(
      Math.abs(speedAt(target, index) - speed) < 0.01,
      `the target drives at ${speedAt(target, index)} m/s at ${target[index].time} s`,
    );
}

/** A pedestrian or cyclist starts across at the ego headway asked, at the speed asked, and is on the ego's path as the ego arrives. */
function crossesAsTheEgoArrives(module: LibraryModule, ego: Track, walker: Track): void {
  const start = lateralStart(walker);
  const egoSpeed = speedAt(ego, start);
  const headway = (walker[start].x - ego[start].x) / egoSpeed;
  assert.ok(
    Math.abs(headway - parameter(module, 'headway')) <= STEP * 1.5,
    `it starts walking at an ego headway of ${headway.toFixed(3)} s`,
  );
  const speed = parameter(module, 'speed');
  const walked = (walker[start + 21].y - walker[start + 1].y) / (20 * STEP);
  assert.ok(Math.abs(Math.abs(walked) - speed) < 0.02, `it walks at ${walked.toFixed(3)} m/s, not ${speed}`);
  // On the ego's path (its lane's centre line) at the time the ego's reference point reaches the crossing line.
  const onPath = walker.findIndex(
    (point, index) => index > start && Math.sign(point.y - ego[index].y) !== Math.sign(walker[start].y - ego[start].y),
  );
  const egoArrives = ego.findIndex((point) => point.x >= walker[start].x);
  assert.ok(onPath > 0 && egoArrives > 0, 'the pedestrian or the ego never reaches the crossing point');
  assert.ok(
    Math.abs(walker[onPath].time - ego[egoArrives].time) <= 0.15,
    `on the path at ${walker[onPath].time} s, the ego there at ${ego[egoArrives].time} s`,
  );
  const distance = parameter(module, 'distance');
  const final = walker[walker.length - 1];
  assert.ok(
    Math.abs(Math.abs(final.y - walker[start].y) - distance) < 0.05 ||
      walker[walker.length - 1].time < walker[start].time + distance / speed,
    'it walks the distance asked',
  );
}

/**
 * A module's example main with a second actor (`ACTOR2`, 40 m further along its lane) whose copy of the group Insert into
 * Main writes; where the module has them, the second copy starts 3 s later and holds a quarter as long.
 */
function twoCopies(
  module: LibraryModule,
  library: string,
): { text: string; second: { actor: string; groupName: string; startTime: number; hold: number } } {
  const actor = module.actor.name;
  const second = `${actor}2`;
  let text = fs.readFileSync(module.example ?? '', 'utf8').replace(/filepath="\.\.\/roads\//, `filepath="${path.join(library, 'roads')}/`);
  const entity = new RegExp(`( *)<ScenarioObject name="${actor}">[\\s\\S]*?</ScenarioObject>\n`).exec(text)?.[0] ?? '';
  const init = new RegExp(`( *)<Private entityRef="${actor}">[\\s\\S]*?</Private>\n`).exec(text)?.[0] ?? '';
  assert.ok(entity && init, `${module.name}: its example has no entity or Init for ${actor}`);
  text = text
    .replace(entity, entity + entity.replace(`name="${actor}"`, `name="${second}"`))
    .replace(
      init,
      init +
        init.replace(`entityRef="${actor}"`, `entityRef="${second}"`).replace(/ s="([\d.]+)"/, (_, s: string) => ` s="${Number(s) + 40}"`),
    )
    .replace(
      /(<Condition name="End"[\s\S]*?<SimulationTimeCondition value=")([\d.]+)/,
      (_, head: string, time: string) => `${head}${Number(time) + 6}`,
    );
  const players = Object.fromEntries(moduleRoles(module).map((role) => [role.name, role.name === actor ? second : role.name]));
  const has = (name: string) => module.parameters.some((candidate) => candidate.name === name);
  const startTime = has('startTime') ? parameter(module, 'startTime') + 3 : NaN;
  const hold = has('hold') ? parameter(module, 'hold') / 4 : NaN;
  const inserted = insertModuleGroup(text, module, { players });
  const group = inserted.text
    .replace(/(key="SimulationTimeCondition\.value" value=")[^"]*/, `$1${startTime}`)
    .replace(/(key="Condition\.delay" value=")[^"]*/, `$1${hold}`);
  return {
    text: text.slice(0, inserted.offset) + group + text.slice(inserted.offset),
    second: { actor: second, groupName: inserted.groupName, startTime, hold },
  };
}

describe('library modules: each verified in esmini and CARLA (issue 28)', function () {
  this.timeout(600_000);
  const libraryFolder = builtInLibraryFolder();
  let modules: LibraryModule[] = [];
  const outputs = temporaryFolder('m2s-library-');

  before(async () => {
    assert.ok(libraryFolder, 'the built-in library is not found');
    const listing = await listLibraries(nodeFileSystem, libraryFolders([], {}));
    assert.deepEqual(listing.problems, []);
    modules = listing.modules;
  });

  it('the modules and example mains are what scripts/library-build.mjs writes, the roads what scripts/library-roads.mjs writes', () => {
    for (const script of ['library-build.mjs', 'library-roads.mjs']) {
      const run = spawnSync(process.execPath, [path.join(repoRoot, 'scripts', script), '--check'], { encoding: 'utf8' });
      assert.equal(run.status, 0, `${script} --check: ${run.stdout}${run.stderr}`);
    }
  });

  it('every module has a doc block, documented keys, an example main; and a behaviour checked here', () => {
    assert.ok(modules.length >= 5, `${modules.length} modules`);
    for (const module of modules) {
      assert.ok(module.example && fs.existsSync(module.example), `${module.name}: no example main`);
      assert.ok(BEHAVIOURS[module.name], `${module.name}: no behaviour assertion in this test`);
      for (const parameter of module.parameters)
        assert.ok(parameter.defaultValue !== undefined, `${module.name} ${parameter.key}: no default`);
    }
  });

  it('every module and example main: schema-valid, no error and no warning under check', async () => {
    const errors: string[] = [];
    const out: string[] = [];
    const files = modules.flatMap((module) => [module.file, module.example ?? '']);
    const code = await main(['check', ...files], { out: (text) => out.push(text), err: (text) => errors.push(text) });
    assert.equal(code, 0, errors.join('\n'));
    assert.match(errors.join('\n') + out.join('\n'), /0 errors, 0 warnings/);
  });

  it('every example main flattens and runs in esmini, the behaviour happens as its parameters say, and its picture is drawn from that run', async function () {
    requireEsmini(this);
    for (const module of modules) {
      const recording = path.join(outputs, `${module.name}.dat`);
      const { run, svg } = await runExample(module, outputs, esminiBinary, recording);
      const environments = recordedEnvironments(fs.readFileSync(recording));
      fs.rmSync(recording);
      BEHAVIOURS[module.name](module, tracksOf(run), environments);
      const picture = path.join(libraryFolder ?? '', 'pictures', `${module.name}.svg`);
      assert.ok(module.picture, `${module.name}: no picture (npx tsx scripts/library-pictures.ts draws them)`);
      assert.equal(
        svg,
        fs.readFileSync(picture, 'utf8'),
        `${module.name}: its picture is not what scripts/library-pictures.ts draws from this run`,
      );
    }
  });

  /** A module's example main changed to `variant` (its road path made absolute), flattened and run in esmini: its tracks. */
  async function runVariant(module: LibraryModule, variant: string): Promise<Map<string, Track>> {
    // Beside the run's files, not among them: runExample writes the flattened main as NAME.xosc in the folder it is given.
    const example = path.join(outputs, 'variant', `${module.name}.xosc`);
    fs.mkdirSync(path.dirname(example));
    fs.writeFileSync(example, variant.replace(/filepath="\.\.\/roads\//, `filepath="${path.join(libraryFolder ?? '', 'roads')}/`));
    try {
      const { run } = await runExample({ ...module, example }, outputs, esminiBinary);
      return tracksOf(run);
    } finally {
      fs.rmSync(path.dirname(example), { recursive: true });
    }
  }

  it("turn-across-path keeps its synchronization when the main changes the ego's speed, the time gap and the turning speed", async function () {
    requireEsmini(this);
    const module = modules.find((candidate) => candidate.name === 'turn-across-path');
    assert.ok(module?.example, 'no turn-across-path module with an example');
    const text = fs.readFileSync(module.example, 'utf8');
    for (const [egoSpeed, egoAt, turnSpeed] of [
      // The ego at 14 m/s instead of 10, and 10 m short of the conflict point (x 1.63) as the turning vehicle arrives: a time gap of 0.83 s.
      [14, -10, parameter(module, 'turnSpeed')],
      // The ego at 12 m/s and 7.63 m short (0.64 s), the turning vehicle crossing at 4 m/s (with its target resolved on the
      // ego's road 101, esmini ended the synchronization as the turn began and it crossed 1.2 s late).
      [12, -6, 4],
    ]) {
      const variant = text
        .replace(/(<Private entityRef="ego">[\s\S]*?<AbsoluteTargetSpeed value=")[^"]*/, `$1${egoSpeed}`)
        .replace(/(key="WorldPosition\.x" value=")[^"]*/, `$1${egoAt}`)
        .replace(/(key="AbsoluteSpeed\.value" value=")[^"]*/, `$1${turnSpeed}`);
      assert.notEqual(variant, text);
      const tracks = await runVariant(module, variant);
      assert.ok(Math.abs(speedAt(trackOf(tracks, 'ego'), 1) - egoSpeed) < 0.01, "the variant did not change the ego's speed");
      turnsAcrossAsSynchronized(tracks, egoAt, turnSpeed);
    }
  });

  it('arrive-leave-site does what other keys ask, and what its defaults ask is not what that run shows (esmini)', async function () {
    requireEsmini(this);
    const module = modules.find((candidate) => candidate.name === 'arrive-leave-site');
    assert.ok(module?.example, 'no arrive-leave-site module with an example');
    const keys: Record<string, [keyof SiteVisit, number]> = {
      'RelativeDistanceCondition.value': ['brakeGap', 50],
      'SpeedActionDynamics.value': ['brakingDistance', 40],
      'Condition.delay': ['stay', 1.5],
      'AbsoluteTargetSpeed.value': ['leaveSpeed', 6],
      'AbsoluteTargetLaneOffset.value': ['passOffset', -3.5],
      'LaneOffsetActionDynamics.maxLateralAcc': ['lateralAcceleration', 1],
    };
    const text = fs.readFileSync(module.example, 'utf8');
    let variant = text;
    for (const [key, [, value]] of Object.entries(keys)) {
      const before = variant;
      variant = variant.replace(new RegExp(`(key="${key.replace(/\./g, '\\.')}" value=")[^"]*`), `$1${value}`);
      assert.notEqual(variant, before, `the example sets no ${key}`);
    }
    const tracks = await runVariant(module, variant);
    const asked = Object.fromEntries(Object.values(keys)) as SiteVisit;
    arrivesStaysLeaves(tracks, asked);
    // Each value is checked: the run fails the assertions with any one of them at its default instead.
    for (const [name] of Object.values(keys)) {
      const defaults = { ...asked, [name]: parameter(module, name) };
      assert.throws(() => arrivesStaysLeaves(tracks, defaults), assert.AssertionError, `${name} at its default passes too`);
    }
  });

  it('modules whose later event waits for their earlier one by name: two copies in one main, each waits for its own (esmini)', async function () {
    requireEsmini(this);
    // Which modules those are is read from their files: a StoryboardElementStateCondition naming an element of the module's own group.
    const waiting = modules.filter((module) => {
      const text = fs.readFileSync(module.file, 'utf8');
      return [...text.matchAll(/storyboardElementRef="([^"]+)"/g)].some((match) => text.includes(`name="${match[1]}"`));
    });
    assert.deepEqual(
      waiting.map((module) => module.name),
      ['arrive-leave-site', 'double-lane-change', 'overtaking', 'swerving-lead'],
    );
    for (const module of waiting) {
      const { text, second } = twoCopies(module, libraryFolder ?? '');
      const flat = path.join(outputs, `${module.name}-twice.xosc`);
      fs.writeFileSync(path.join(outputs, `${module.name}-twice.main.xosc`), text);
      const errors: string[] = [];
      const code = await main(['flatten', path.join(outputs, `${module.name}-twice.main.xosc`), '-o', flat, '-q'], {
        out: () => {},
        err: (line) => errors.push(line),
      });
      assert.equal(code, 0, errors.join('\n'));
      // Each copy's condition names its own copy's event, which no other element is named.
      const flatText = fs.readFileSync(flat, 'utf8');
      for (const outer of [module.maneuverGroup, second.groupName]) {
        const reference = new RegExp(`storyboardElementRef="(${outer.replace('.', '\\.')}\\.[^"]+)"`).exec(flatText)?.[1];
        assert.ok(reference, `${module.name}: the copy ${outer} names no element of its own in its condition:\n${flatText}`);
        assert.equal(flatText.split(`name="${reference}"`).length - 1, 1, `${module.name}: one element is named ${reference}`);
      }
      // Their own waits in esmini: overtaking's depends on the gap, arrive-leave-site's on the site (the test above runs it).
      if (module.name === 'overtaking' || module.name === 'arrive-leave-site') continue;
      const example = path.join(outputs, 'twice', `${module.name}.xosc`);
      fs.mkdirSync(path.dirname(example), { recursive: true });
      fs.writeFileSync(example, text);
      const { run } = await runExample({ ...module, example }, outputs, esminiBinary);
      fs.rmSync(path.dirname(example), { recursive: true });
      const tracks = tracksOf(run);
      for (const [actor, startTime, hold] of [
        [module.actor.name, parameter(module, 'startTime'), parameter(module, 'hold')],
        [second.actor, second.startTime, second.hold],
      ] as const) {
        const moves = lateralMoves(trackOf(tracks, actor));
        const track = trackOf(tracks, actor);
        assert.ok(moves.length >= 2, `${module.name} ${actor}: ${moves.length} sideways moves, not out and back`);
        const [out, back] = moves;
        assert.ok(
          Math.abs(track[out.start].time - startTime) <= STEP * 2.5,
          `${module.name} ${actor} moves out at ${track[out.start].time} s`,
        );
        const waited = track[back.start].time - track[out.end].time;
        assert.ok(
          Math.abs(waited - hold) <= STEP * 2.5,
          `${module.name} ${actor} moves back ${waited.toFixed(2)} s after its own move out ended, not its hold ${hold} s`,
        );
      }
    }
  });

  it("every example main's CARLA export builds in ScenarioRunner's loader, and check --simulator carla finds no error in it", async function () {
    requireCarlaHarness(this);
    const exported: string[] = [];
    for (const module of modules) {
      const output = path.join(outputs, `${module.name}.carla.xosc`);
      const errors: string[] = [];
      const code = await main(['export', module.example ?? '', '--target', 'carla', '-o', output, '-q'], {
        out: () => {},
        err: (text) => errors.push(text),
      });
      assert.equal(code, 0, `${module.name}: ${errors.join('\n')}`);
      exported.push(output);
    }
    const verdicts = await harnessVerdicts(exported);
    for (const file of exported) {
      const verdict = verdicts.get(path.resolve(file));
      assert.equal(verdict?.status, 'OK', `${path.basename(file)}: ${verdict?.stage} ${verdict?.reason}`);
      // check --simulator carla agrees with the harness: nothing ScenarioRunner refuses (its warnings say what it runs otherwise).
      const said: string[] = [];
      const code = await main(['check', file, '--simulator', 'carla'], { out: (text) => said.push(text), err: (text) => said.push(text) });
      assert.equal(code, 0, said.join('\n'));
      assert.match(said.join('\n'), /checked 1 file: 0 errors/);
    }
  });
});
