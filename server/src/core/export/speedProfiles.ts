/**
 * A 1.2 SpeedProfileAction has no 1.0 form. Followed in position mode, as esmini 3.6 follows it
 * (`LongSpeedProfileAction::Start`: straight ramps between the entries, each ramp's slope held within the
 * DynamicConstraints by lengthening the ramp, an entry without a time reached at that limit), it is a chain of
 * linear SpeedActions over time: the first in the profile's Event, each next one in an Event of its own whose
 * StartTrigger is the profile Event's with every condition delayed by the time the ramps before it take. A condition
 * delay is a latch in both simulators (the trigger fires that long after the condition first holds), so each ramp
 * starts when esmini would reach that entry. ScenarioRunner runs each SpeedAction as any other, towards the target
 * speed for the ramp's duration (SR_PARSER convert_maneuver_to_atomic, SR_ATOMICS ChangeActorTargetSpeed).
 */
import { SR_ATOMICS, SR_PARSER } from './carlaFacts';
import { dropUnit, type LossSink } from './carlaLosses';
import { actorsOf, scenarioObjectOf, startSpeedOf } from './scenarioTree';
import {
  ancestor,
  appendChild,
  attr,
  child,
  childrenNamed,
  cloneNode,
  fourDecimals,
  makeNode,
  named,
  Node,
  replaceNode,
  setAttr,
} from './tree';

const ESMINI = 'esmini 3.6 LongSpeedProfileAction::Start';
const CARLA = `speed profiles are not in 1.0; ScenarioRunner runs each SpeedAction written for it towards its target speed for the ramp's duration (${SR_PARSER} convert_maneuver_to_atomic, ${SR_ATOMICS} ChangeActorTargetSpeed)`;
const NOT_MAPPED = 'speed profiles are not in 1.0, and this one has no 1.0 form';

/** One SpeedAction of the chain: reach `speed` (m/s) in `seconds`, from the entry at `entry`. */
interface Ramp {
  speed: number;
  seconds: number;
  entry: Node;
}

/** The actor's limit of acceleration or deceleration: the profile's DynamicConstraints, capped by the vehicle's Performance as esmini caps it (parseDynamicConstraints); none without constraints. */
function limitOf(profile: Node, tree: Node, actor: string, which: 'maxAcceleration' | 'maxDeceleration'): number {
  const constraints = child(profile, 'DynamicConstraints');
  const given = constraints ? Number(attr(constraints, which)) : NaN;
  if (!(given > 0)) return Infinity;
  const object = scenarioObjectOf(tree, actor);
  const performance = object ? named(object, 'Performance')[0] : undefined;
  const capped = performance ? Number(attr(performance, which)) : NaN;
  return capped > 0 ? Math.min(given, capped) : given;
}

/** The ramps of a profile in position mode, as esmini computes them, or why it has no 1.0 form. */
function rampsOf(
  profile: Node,
  tree: Node,
  actor: string,
): { ramps: Ramp[]; lengthened: number; jumpTo?: number; uncheckedFirst: boolean } | string {
  const entries = childrenNamed(profile, 'SpeedProfileEntry').map((entry) => {
    const time = attr(entry, 'time');
    return { entry, speed: Number(attr(entry, 'speed')), time: time === undefined ? undefined : Number(time) };
  });
  if (entries.length === 0) return 'it has no SpeedProfileEntry';
  if (entries.some((each) => !Number.isFinite(each.speed) || (each.time !== undefined && !(each.time >= 0))))
    return 'an entry has a speed or time that is no number';
  const acceleration = limitOf(profile, tree, actor, 'maxAcceleration');
  const deceleration = limitOf(profile, tree, actor, 'maxDeceleration');
  let previous: number | undefined;
  let jumpTo: number | undefined;
  let from = 0;
  if (entries[0].time === 0) {
    // esmini sets the first entry's speed at once in position mode, and starts from the speed the actor has in follow mode; 1.0 has no action that sets a speed and ramps on from it.
    if (attr(profile, 'followingMode') !== 'follow') {
      jumpTo = entries[0].speed;
      previous = jumpTo;
    }
    from = 1;
  }
  const ramps: Ramp[] = [];
  let lengthened = 0;
  let uncheckedFirst = false;
  for (let index = from; index < entries.length; index++) {
    const { entry, speed, time } = entries[index];
    if (time === 0) return 'an entry after the first has time 0 (esmini replaces the entry before it)';
    if (previous === undefined) {
      if (time === undefined) return 'its first entry has no time, and the speed it starts from is not known before the run';
      uncheckedFirst = Number.isFinite(acceleration) || Number.isFinite(deceleration);
      ramps.push({ speed, seconds: time, entry });
      previous = speed;
      continue;
    }
    const change = speed - previous;
    const limit = change < 0 ? deceleration : acceleration;
    if (time === undefined) {
      if (change === 0) continue;
      if (!Number.isFinite(limit)) return 'an entry has no time and the profile no DynamicConstraints to reach it at';
      ramps.push({ speed, seconds: Math.abs(change) / limit, entry });
    } else if (Math.abs(change) / time > limit) {
      lengthened++;
      ramps.push({ speed, seconds: Math.abs(change) / limit, entry });
    } else ramps.push({ speed, seconds: time, entry });
    previous = speed;
  }
  if (ramps.length === 0) return 'no entry changes the speed';
  return { ramps, lengthened, jumpTo, uncheckedFirst };
}

/** `<SpeedAction>` reaching `ramp.speed` linearly in `ramp.seconds`, placed at its entry's line. */
function speedAction(ramp: Ramp): Node {
  const place = ramp.entry.place;
  return makeNode(
    'SpeedAction',
    [],
    [
      makeNode(
        'SpeedActionDynamics',
        [
          ['dynamicsShape', 'linear'],
          ['value', fourDecimals(ramp.seconds)],
          ['dynamicsDimension', 'time'],
        ],
        [],
        place,
      ),
      makeNode('SpeedActionTarget', [], [makeNode('AbsoluteTargetSpeed', [['value', fourDecimals(ramp.speed)]], [], place)], place),
    ],
    place,
  );
}

/** Names of the storyboard's elements, so that the Events and Actions written are new names. */
function storyboardNames(tree: Node): Set<string> {
  const names = new Set<string>();
  for (const kind of ['Story', 'Act', 'ManeuverGroup', 'Maneuver', 'Event', 'Action'])
    for (const node of named(tree, kind)) names.add(attr(node, 'name') ?? '');
  return names;
}

function freshName(base: string, names: Set<string>): string {
  let name = base;
  for (let suffix = 2; names.has(name); suffix++) name = `${base}_${suffix}`;
  names.add(name);
  return name;
}

/** Why the profile's Event cannot be repeated with delayed triggers, or undefined when it can. */
function unrepeatable(event: Node, action: Node, tree: Node): string | undefined {
  const trigger = child(event, 'StartTrigger');
  const conditions = trigger ? named(trigger, 'Condition') : [];
  if (conditions.length === 0) return 'its Event has no StartTrigger to delay';
  if (conditions.some((condition) => !Number.isFinite(Number(attr(condition, 'delay') ?? '0'))))
    return "a condition of its Event's StartTrigger has a delay that is no number";
  const eventName = attr(event, 'name');
  const actionName = attr(action, 'name');
  const waiting = named(tree, 'StoryboardElementStateCondition').find((condition) => {
    const ref = attr(condition, 'storyboardElementRef');
    return ref !== undefined && (ref === eventName || ref === actionName);
  });
  if (waiting)
    return `a StoryboardElementStateCondition waits for its ${attr(waiting, 'storyboardElementType') ?? 'Event'} '${attr(waiting, 'storyboardElementRef')}', which would end before the profile does`;
  return undefined;
}

/** Every SpeedProfileAction of a story written as its chain of SpeedActions, or dropped naming why it has none. */
export function speedProfiles(tree: Node, context: { sink: LossSink }): void {
  // Read once, when a first profile is written; each name written joins it.
  let names: Set<string> | undefined;
  for (const profile of named(tree, 'SpeedProfileAction')) {
    if (!profile.parent) continue;
    const action = ancestor(profile, 'Action');
    const event = action ? ancestor(action, 'Event') : undefined;
    // In the Init: the refused-actions rule drops it, as ScenarioRunner passes over it there.
    if (!action || !event || !event.parent) continue;
    const actors = actorsOf(profile);
    const why =
      attr(profile, 'entityRef') !== undefined
        ? 'its speeds are relative to another entity, whose speed at each entry is known only in the run'
        : actors.length !== 1
          ? `it acts on ${actors.length} actors, and a vehicle's limits are its own`
          : unrepeatable(event, action, tree);
    const found = why === undefined ? rampsOf(profile, tree, actors[0]) : why;
    if (typeof found === 'string') {
      dropUnit(profile, context, 'SpeedProfileAction', `${NOT_MAPPED}: ${found}`);
      continue;
    }
    const { ramps, lengthened, jumpTo, uncheckedFirst } = found;
    const taken = (names ??= storyboardNames(tree));
    const trigger = child(event, 'StartTrigger') as Node;
    const written: string[] = [];
    let offset = 0;
    let after = event;
    ramps.forEach((ramp, index) => {
      if (index === 0) {
        replaceNode(profile, speedAction(ramp));
      } else {
        const copy = makeNode('Event', [], [], event.place);
        setAttr(copy, 'name', freshName(`${attr(event, 'name') ?? 'Event'}_ramp${index + 1}`, taken));
        setAttr(copy, 'priority', 'parallel');
        const count = attr(event, 'maximumExecutionCount');
        if (count !== undefined) setAttr(copy, 'maximumExecutionCount', count);
        const longitudinal = makeNode('LongitudinalAction', [], [speedAction(ramp)], ramp.entry.place);
        const rampAction = makeNode('Action', [], [makeNode('PrivateAction', [], [longitudinal], ramp.entry.place)], action.place);
        setAttr(rampAction, 'name', freshName(`${attr(action, 'name') ?? 'Action'}_ramp${index + 1}`, taken));
        appendChild(copy, rampAction);
        const delayed = cloneNode(trigger);
        for (const condition of named(delayed, 'Condition'))
          setAttr(condition, 'delay', fourDecimals(Number(attr(condition, 'delay') ?? '0') + offset));
        appendChild(copy, delayed);
        const next = after.parent?.children[after.parent.children.indexOf(after) + 1];
        appendChild(event.parent as Node, copy, next);
        after = copy;
        written.push(`'${attr(copy, 'name')}' after ${fourDecimals(offset)} s`);
      }
      offset += ramp.seconds;
    });
    const steps = ramps.map((ramp) => `${fourDecimals(ramp.speed)} m/s in ${fourDecimals(ramp.seconds)} s`).join(', ');
    const notes = [
      attr(profile, 'followingMode') === 'follow'
        ? "followingMode follow's smooth, jerk-limited changes are written as straight ramps"
        : '',
      uncheckedFirst
        ? 'the first ramp starts from the speed the actor has, which is known only in the run: esmini lengthens it if it is steeper than the DynamicConstraints allow, the export does not'
        : '',
      lengthened > 0
        ? `${lengthened} ramp${lengthened > 1 ? 's' : ''} lengthened to the DynamicConstraints' acceleration, as esmini does`
        : '',
      jumpTo !== undefined && startSpeedOf(tree, actors[0]) !== jumpTo
        ? `the first entry's speed ${fourDecimals(jumpTo)} m/s, which esmini sets at once, is not written: the first ramp starts from the speed the actor has`
        : '',
    ].filter((note) => note !== '');
    context.sink.approximated(
      profile,
      'SpeedProfileAction',
      `written as ${ramps.length} linear SpeedAction${ramps.length > 1 ? 's' : ''} (${steps})${written.length > 0 ? `, each after the first in an Event started by the profile Event's trigger, delayed: ${written.join(', ')}` : ''}, as ${ESMINI} follows the profile${notes.length > 0 ? `; ${notes.join('; ')}` : ''}`,
      CARLA,
    );
  }
}
