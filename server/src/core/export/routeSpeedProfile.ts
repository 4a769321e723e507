/**
 * The speed of a vehicle along its route (Init, or story from a start the profile fixes) when its story changes that speed at known times, as esmini drives it: the
 * route written as a trajectory keeps it in esmini (a trajectory without timing is followed at the entity's speed), and in
 * ScenarioRunner its vertex times do, since its vehicle controller drives to each vertex by its time whatever speed a
 * SpeedAction sets (CARLA_FACTS.vehicleSpeedChangeOnTrajectory). Known for SpeedActions to an absolute speed above 0, step or
 * linear (by time, rate or distance, as esmini's LongSpeedAction reads them), each in an Event started by one
 * SimulationTimeCondition in an Act that starts at the run's start: ScenarioRunner counts such a condition from its first
 * tick, which is then the run's start too (CARLA_FACTS.conditionsCountFromTheirStart).
 */
import { CARLA_FACTS } from '../profiles/carla';
import { baseName } from '../sources';
import { actorsOf, constantSpeedOf, scenarioObjectOf, storySpeedChangesOf } from './scenarioTree';
import { ancestor, attr, child, childrenNamed, fourDecimals, named, Node, numberAttr } from './tree';

/** The rules a SimulationTimeCondition holds from its value on: once the time has come. */
export const FROM_TIME_ON: ReadonlySet<string> = new Set(['greaterThan', 'greaterOrEqual', 'equalTo']);

/** Where a node was written (`file:line`), or '' when it was not. */
export function lineOf(node: Node): string {
  return node.place ? `${baseName(node.place.source)}:${node.place.range.start.line + 1}` : '';
}

/** When a trigger's groups that are one SimulationTimeCondition each hold at the latest, and whether it has other groups. */
function timeOfTrigger(trigger: Node | undefined): { time: number | undefined; other: boolean } {
  let time: number | undefined;
  let other = false;
  for (const group of trigger ? childrenNamed(trigger, 'ConditionGroup') : []) {
    const conditions = childrenNamed(group, 'Condition');
    const simulation = conditions.length === 1 ? named(conditions[0], 'SimulationTimeCondition')[0] : undefined;
    const at = simulation ? numberAttr(simulation, 'value', NaN) + numberAttr(conditions[0], 'delay', 0) : NaN;
    if (!simulation || !FROM_TIME_ON.has(attr(simulation, 'rule') ?? '') || !(at >= 0)) other = true;
    else time = Math.min(time ?? Infinity, at);
  }
  return { time, other };
}

/** Whether an Act starts at the run's start: its StartTrigger one SimulationTimeCondition at 0 without delay. */
export function startsAtZero(act: Node): boolean {
  const trigger = child(act, 'StartTrigger');
  const conditions = trigger ? childrenNamed(trigger, 'ConditionGroup').flatMap((group) => childrenNamed(group, 'Condition')) : [];
  const { time, other } = timeOfTrigger(trigger);
  return conditions.length === 1 && !other && time === 0;
}

/** When the run stops at the latest, by a Storyboard StopTrigger group that is one SimulationTimeCondition. */
export function runStopTime(tree: Node): number | undefined {
  const storyboard = child(tree, 'Storyboard');
  return timeOfTrigger(storyboard ? child(storyboard, 'StopTrigger') : undefined).time;
}

/** A stretch of the profile: from `from` seconds on, `speed` changing by `acceleration` each second, up to `until`. */
interface Piece {
  from: number;
  speed: number;
  acceleration: number;
  until: number;
}

/** A SpeedAction of the story and when it starts, in seconds from the run's start. */
export interface SpeedChange {
  action: Node;
  at: number;
  to: number;
  /** Seconds it takes to reach `to`: 0 for a step. */
  takes: number;
}

export interface SpeedProfile {
  /** The speed the Init sets. */
  start: number;
  changes: SpeedChange[];
  pieces: Piece[];
}

/** When a story SpeedAction starts, or why that is not known before the run. */
function startOf(action: Node, where: string): number | string {
  const event = ancestor(action, 'Event');
  const act = ancestor(action, 'Act');
  const trigger = event ? child(event, 'StartTrigger') : undefined;
  const conditions = trigger ? childrenNamed(trigger, 'ConditionGroup').flatMap((group) => childrenNamed(group, 'Condition')) : [];
  const { time, other } = timeOfTrigger(trigger);
  if (!event || !act || conditions.length !== 1 || other || time === undefined)
    return `the SpeedAction at ${where} starts on ${conditions.length === 1 ? `${named(conditions[0], new Set(['EntityCondition', 'ByValueCondition']))[0]?.children[0]?.name ?? 'a condition'}` : `${conditions.length} conditions`}, not one SimulationTimeCondition, so when it starts is known only as the run goes`;
  if ((attr(event, 'maximumExecutionCount') ?? '1') !== '1') return `the Event of the SpeedAction at ${where} may run more than once`;
  if (!startsAtZero(act))
    return `the Act of the SpeedAction at ${where} does not start at the run's start, and ScenarioRunner ${CARLA_FACTS.conditionsCountFromTheirStart.does} (${CARLA_FACTS.conditionsCountFromTheirStart.source})`;
  const stop = timeOfTrigger(child(act, 'StopTrigger'));
  if (stop.other || (stop.time !== undefined && stop.time <= time))
    return `the Act of the SpeedAction at ${where} may stop before the SpeedAction starts`;
  return time;
}

/** The speed an actor has at `time` on the profile. */
export function speedAt(profile: SpeedProfile, time: number): number {
  const piece = profile.pieces.find((each) => time < each.until) ?? profile.pieces[profile.pieces.length - 1];
  return piece.speed + piece.acceleration * (Math.max(time, piece.from) - piece.from);
}

/** How far the actor has driven on the profile by `time` seconds from the run's start. */
export function distanceAt(profile: SpeedProfile, time: number): number {
  let covered = 0;
  for (const piece of profile.pieces) {
    if (time <= piece.from) break;
    const span = Math.min(time, piece.until) - piece.from;
    covered += piece.speed * span + (piece.acceleration * span * span) / 2;
  }
  return covered;
}

/** When the actor has covered `distance` metres on the profile. */
export function timeAt(profile: SpeedProfile, distance: number): number {
  let covered = 0;
  for (const piece of profile.pieces) {
    const span = piece.until - piece.from;
    const length = piece.until === Infinity ? Infinity : piece.speed * span + (piece.acceleration * span * span) / 2;
    if (covered + length >= distance) {
      const rest = distance - covered;
      const { speed, acceleration } = piece;
      const within = acceleration === 0 ? rest / speed : (Math.sqrt(speed * speed + 2 * acceleration * rest) - speed) / acceleration;
      return piece.from + within;
    }
    covered += length;
  }
  return Infinity;
}

/**
 * The vehicle's speed profile from the run's start, when its Init sets its speed at once and its story changes it only by
 * SpeedActions whose start esmini and ScenarioRunner both know beforehand (above); else why not. `route` is the route action.
 */
export function routeSpeedProfile(tree: Node, actor: string, route: Node): SpeedProfile | string {
  const object = scenarioObjectOf(tree, actor);
  if (object && child(object, 'ObjectController'))
    return `'${actor}' has an ObjectController of its own, which drives it at a speed the export does not know`;
  const actions = storySpeedChangesOf(tree, actor, route);
  const changes: { action: Node; at: number; to: number; dynamics: Node }[] = [];
  for (const action of actions) {
    const where = lineOf(action) || 'a story line';
    const actors = actorsOf(action);
    if (action.name !== 'SpeedAction' || actors.length !== 1 || actors[0] !== actor)
      return `${/^[AEIOU]/.test(action.name) ? 'an' : 'a'} ${action.name} at ${where} may change it, and the export times a route only by SpeedActions on '${actor}' alone`;
    const target = named(action, 'AbsoluteTargetSpeed')[0];
    const to = target ? numberAttr(target, 'value', NaN) : NaN;
    const dynamics = named(action, 'SpeedActionDynamics')[0];
    if (!(to > 0) || !dynamics)
      return `the SpeedAction at ${where} sets no absolute speed above 0, and a vehicle that stops or whose target follows another entity reaches no vertex at a time known beforehand`;
    const at = startOf(action, where);
    if (typeof at === 'string') return at;
    changes.push({ action, at, to, dynamics });
  }
  const start = constantSpeedOf(tree, actor, new Set([route, ...actions]));
  if (start === undefined || !(start > 0))
    return `its Init sets no speed above 0 at once (a step SpeedAction to an absolute speed, or one relative to an entity whose speed is certain)${actions.length > 0 ? ' that only those SpeedActions change' : ''}, or a ControllerAction gives it a controller`;
  changes.sort((one, other) => one.at - other.at);
  const pieces: Piece[] = [{ from: 0, speed: start, acceleration: 0, until: Infinity }];
  const profile: SpeedProfile = { start, changes: [], pieces };
  for (const [index, { action, at, to, dynamics }] of changes.entries()) {
    const where = lineOf(action) || 'a story line';
    if (index > 0 && changes[index - 1].at === at)
      return `the SpeedActions at ${lineOf(changes[index - 1].action) || 'a story line'} and ${where} start at the same time, and which one esmini keeps depends on the order it starts them`;
    // esmini starts a speed change from the speed the actor has then, ending any change still running (one longitudinal action at a time).
    const from = speedAt(profile, at);
    while (pieces.length > 0 && pieces[pieces.length - 1].from >= at) pieces.pop();
    pieces[pieces.length - 1].until = at;
    const shape = attr(dynamics, 'dynamicsShape');
    const dimension = attr(dynamics, 'dynamicsDimension');
    const value = Math.abs(numberAttr(dynamics, 'value', NaN));
    let takes: number;
    if (shape === 'step' || from === to) takes = 0;
    else if (shape !== 'linear')
      return `the SpeedAction at ${where} changes the speed by a ${shape ?? 'missing'} shape, and the export times a route by step and linear changes only`;
    else if (dimension === 'time') takes = value;
    else if (dimension === 'rate') takes = Math.abs(to - from) / value;
    else if (dimension === 'distance') takes = (2 * value) / (from + to);
    else return `the SpeedAction at ${where} has no dynamicsDimension the export reads`;
    if (!Number.isFinite(takes)) return `the SpeedAction at ${where} has a dynamics value that is not a number above 0`;
    if (takes > 0) pieces.push({ from: at, speed: from, acceleration: (to - from) / takes, until: at + takes });
    pieces.push({ from: at + takes, speed: to, acceleration: 0, until: Infinity });
    profile.changes.push({ action, at, to, takes });
  }
  return profile;
}

/** What the report says of the profile: each change, when it starts and how long it takes. */
export function describeProfile(profile: SpeedProfile): string {
  return [
    `${fourDecimals(profile.start)} m/s`,
    ...profile.changes.map(
      ({ action, at, to, takes }) =>
        `${fourDecimals(to)} m/s from ${fourDecimals(at)} s${takes > 0 ? ` (linear over ${fourDecimals(takes)} s)` : ''} by the SpeedAction at ${lineOf(action) || 'a story line'}`,
    ),
  ].join(', then ');
}
