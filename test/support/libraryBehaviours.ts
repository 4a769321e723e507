import { strict as assert } from 'node:assert';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { EsminiRun } from '../../common/src/esminiCsv';
import { LibraryModule } from '../../server/src/core/library';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { RecordedEnvironment } from './esminiDat';

/**
 * What each module of the built-in library does, asserted on esmini's trajectories from the values its keys are given
 * (the module's defaults, or a main's values on a copy of the module): its example main's run
 * (test/cli/libraryModules.test.ts) and a main composed with Insert into Main (test/server/libraryNewEntities.test.ts).
 */

export type Track = { time: number; x: number; y: number }[];

/** Vehicles of the library: the bounding box's front is 3.75 m ahead of the reference point, its rear 0.75 m behind. */
export const FRONT = 3.75;
export const REAR = 0.75;
export const STEP = 0.05;

export function parameter(module: LibraryModule, name: string): number {
  const found = module.parameters.find((candidate) => candidate.name === name);
  assert.ok(found?.defaultValue !== undefined, `${module.name} documents no parameter '${name}' with a default`);
  return Number(found.defaultValue);
}

export function trackOf(tracks: Map<string, Track>, name: string): Track {
  const track = tracks.get(name);
  assert.ok(track && track.length > 2, `esmini logged no track for ${name}`);
  return track;
}

/** Speed along x between two consecutive steps. */
export function speedAt(track: Track, index: number): number {
  return (track[index + 1].x - track[index].x) / (track[index + 1].time - track[index].time);
}

/** The first step at which the track leaves its first y (a lane change or a crossing starts). */
function lateralStart(track: Track): number {
  const index = track.findIndex((point) => Math.abs(point.y - track[0].y) > 1e-5);
  assert.ok(index > 0, 'the entity never moved sideways');
  return index - 1;
}

export function tracksOf(run: EsminiRun): Map<string, Track> {
  return new Map(
    run.entities.map((entity) => [entity.name, Array.from(run.times, (time, index) => ({ time, x: entity.x[index], y: entity.y[index] }))]),
  );
}

const sameTime = (track: Track, time: number) => track.findIndex((point) => point.time >= time - 1e-6);

/** Each sideways move of a track: the step before y starts changing and the first step at which it stops. */
export function lateralMoves(track: Track): { start: number; end: number }[] {
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
export const BEHAVIOURS: Record<string, (module: LibraryModule, tracks: Map<string, Track>, environments: RecordedEnvironment[]) => void> =
  {
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
      assert.ok(
        Math.abs(lead[out.start].time - parameter(module, 'startTime')) <= STEP * 1.5,
        `it starts out at ${lead[out.start].time} s`,
      );
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

export type SiteVisit = {
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
export function arrivesStaysLeaves(tracks: Map<string, Track>, asked: SiteVisit): void {
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
export function turnsAcrossAsSynchronized(tracks: Map<string, Track>, egoAt: number, turnSpeed: number): void {
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
