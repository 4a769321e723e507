#!/usr/bin/env node
// `node scripts/library-build.mjs`: writes the scenario library's modules (library/NAME.xosc) and their
// example mains (library/examples/NAME.xosc) from the descriptions below. Each module is a whole scenario that runs
// by itself (its group in a story, on the library's own road); its example main is the same scenario with the group
// replaced by a ScenarioReference to `library:NAME`, every key at its default. test/library/ runs each example in
// esmini and checks the behaviour, and that these files are what this script writes.
import * as fs from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';

const ROAD = 'straight_1000m.xodr';

/** @param {string} text @param {number} depth */
const indent = (text, depth) =>
  text
    .split('\n')
    .map((line) => (line ? ' '.repeat(depth) + line : line))
    .join('\n');

/**
 * @typedef {{ model: string, category: string, maxSpeed: string, maxAcceleration: string, maxDeceleration: string,
 *   centerX: string, centerZ: string, width: string, length: string, height: string,
 *   wheel: string, track: string, frontX: string, axleZ: string }} VehicleShape
 */

/** A Vehicle entity as every library file writes it: one layout, the values of its kind. @param {string} name @param {VehicleShape} v */
const vehicleObject = (name, v) => `<ScenarioObject name="${name}">
  <Vehicle name="${v.model}" vehicleCategory="${v.category}">
    <ParameterDeclarations/>
    <Performance maxSpeed="${v.maxSpeed}" maxAcceleration="${v.maxAcceleration}" maxDeceleration="${v.maxDeceleration}"/>
    <BoundingBox>
      <Center x="${v.centerX}" y="0" z="${v.centerZ}"/>
      <Dimensions width="${v.width}" length="${v.length}" height="${v.height}"/>
    </BoundingBox>
    <Axles>
      <FrontAxle maxSteering="0.5" wheelDiameter="${v.wheel}" trackWidth="${v.track}" positionX="${v.frontX}" positionZ="${v.axleZ}"/>
      <RearAxle maxSteering="0" wheelDiameter="${v.wheel}" trackWidth="${v.track}" positionX="0" positionZ="${v.axleZ}"/>
    </Axles>
    <Properties/>
  </Vehicle>
</ScenarioObject>`;
const VEHICLE = (/** @type {string} */ name, /** @type {string} */ model) =>
  vehicleObject(name, {
    model,
    category: 'car',
    maxSpeed: '69.444',
    maxAcceleration: '10',
    maxDeceleration: '10',
    centerX: '1.5',
    centerZ: '0.9',
    width: '2.0',
    length: '4.5',
    height: '1.5',
    wheel: '0.6',
    track: '1.8',
    frontX: '3.1',
    axleZ: '0.3',
  });
export const BICYCLE = (/** @type {string} */ name) =>
  vehicleObject(name, {
    model: 'vehicle.diamondback.century',
    category: 'bicycle',
    maxSpeed: '15',
    maxAcceleration: '3',
    maxDeceleration: '6',
    centerX: '0.5',
    centerZ: '0.9',
    width: '0.6',
    length: '1.8',
    height: '1.8',
    wheel: '0.7',
    track: '0.1',
    frontX: '1.1',
    axleZ: '0.35',
  });
const PEDESTRIAN = (/** @type {string} */ name) => `<ScenarioObject name="${name}">
  <Pedestrian name="walker.pedestrian.0001" pedestrianCategory="pedestrian" mass="75" model3d="walker.pedestrian.0001">
    <ParameterDeclarations/>
    <BoundingBox>
      <Center x="0" y="0" z="0.9"/>
      <Dimensions width="0.5" length="0.5" height="1.8"/>
    </BoundingBox>
    <Properties/>
  </Pedestrian>
</ScenarioObject>`;
export const OBSTRUCTION = (/** @type {string} */ name) =>
  vehicleObject(name, {
    model: 'vehicle.carlamotors.carlacola',
    category: 'van',
    maxSpeed: '30',
    maxAcceleration: '3',
    maxDeceleration: '8',
    centerX: '2.5',
    centerZ: '1.3',
    width: '2.2',
    length: '6',
    height: '2.6',
    wheel: '0.8',
    track: '1.9',
    frontX: '4',
    axleZ: '0.4',
  });

/**
 * An entity's Init: where it stands on the library's road and its speed.
 * @param {string} entity @param {number} lane @param {number} s @param {number} speed @param {{ offset?: number, heading?: number, road?: number }} [more]
 */
function placed(entity, lane, s, speed, more = {}) {
  const orientation = more.heading !== undefined ? `\n        <Orientation type="relative" h="${more.heading}" p="0" r="0"/>\n      ` : '';
  const position = `<LanePosition roadId="${more.road ?? 0}" laneId="${lane}" s="${s}" offset="${more.offset ?? 0}"${orientation ? `>${orientation}</LanePosition>` : '/>'}`;
  return `<Private entityRef="${entity}">
  <PrivateAction>
    <TeleportAction>
      <Position>
        ${position}
      </Position>
    </TeleportAction>
  </PrivateAction>
  <PrivateAction>
    <LongitudinalAction>
      <SpeedAction>
        <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
        <SpeedActionTarget>
          <AbsoluteTargetSpeed value="${speed}"/>
        </SpeedActionTarget>
      </SpeedAction>
    </LongitudinalAction>
  </PrivateAction>
</Private>`;
}

/** @param {string} name @param {string} condition @param {string} [edge] */
const trigger = (name, condition, edge = 'none') => `<StartTrigger>
  <ConditionGroup>
    <Condition name="${name}" delay="0" conditionEdge="${edge}">
${indent(condition, 6)}
    </Condition>
  </ConditionGroup>
</StartTrigger>`;
const atTime = (/** @type {number} */ time, /** @type {string} */ listed = '') => `<ByValueCondition>
  <SimulationTimeCondition${listed} value="${time}" rule="greaterThan"/>
</ByValueCondition>`;
/** @param {string} triggering @param {string} condition */
const byEntity = (triggering, condition) => `<ByEntityCondition>
  <TriggeringEntities triggeringEntitiesRule="any">
    <EntityRef parameterAttributes="entityRef" entityRef="${triggering}"/>
  </TriggeringEntities>
  <EntityCondition>
    ${condition}
  </EntityCondition>
</ByEntityCondition>`;

/** Starts `delay` seconds (a key: Condition.delay) after the event `after` of the same maneuver ends. @param {string} name @param {string} after @param {number} delay */
const afterEvent = (name, after, delay) => `<StartTrigger>
  <ConditionGroup>
    <Condition parameterAttributes="delay" name="${name}" delay="${delay}" conditionEdge="none">
      <ByValueCondition>
        <StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="${after}" state="endTransition"/>
      </ByValueCondition>
    </Condition>
  </ConditionGroup>
</StartTrigger>`;
/** @param {string} name @param {string} actions @param {string} start @param {string} [priority] */
const event = (name, actions, start, priority = 'overwrite') => `<Event name="${name}" priority="${priority}">
${indent(actions, 2)}
${indent(start, 2)}
</Event>`;
/** @param {string} name @param {string} action */
const privateAction = (name, action) => `<Action name="${name}">
  <PrivateAction>
${indent(action, 4)}
  </PrivateAction>
</Action>`;
/** @param {string} dynamics @param {string} target */
const speedAction = (dynamics, target) => `<LongitudinalAction>
  <SpeedAction>
    ${dynamics}
    <SpeedActionTarget>
      ${target}
    </SpeedActionTarget>
  </SpeedAction>
</LongitudinalAction>`;
/** @param {string} dynamics @param {string} target @param {string} [attributes] of the LaneChangeAction */
const laneChange = (dynamics, target, attributes = '') => `<LateralAction>
  <LaneChangeAction${attributes}>
    ${dynamics}
    <LaneChangeTarget>
      ${target}
    </LaneChangeTarget>
  </LaneChangeAction>
</LateralAction>`;
/** A swerve within the lane to a target offset, as smooth as its largest lateral acceleration allows. @param {string} target */
const laneOffset = (target) => `<LateralAction>
  <LaneOffsetAction continuous="false">
    <LaneOffsetActionDynamics parameterAttributes="maxLateralAcc" maxLateralAcc="2" dynamicsShape="sinusoidal"/>
    <LaneOffsetTarget>
      ${target}
    </LaneOffsetTarget>
  </LaneOffsetAction>
</LateralAction>`;
/** The overtaking vehicle changes back once its pull-out is over and it is the gap asked ahead of the ego. */
const overtakenTrigger = () => `<StartTrigger>
  <ConditionGroup>
    <Condition name="OvertakingPulledOut" delay="0" conditionEdge="none">
      <ByValueCondition>
        <StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="OvertakingPullOut" state="completeState"/>
      </ByValueCondition>
    </Condition>
    <Condition name="OvertakingAhead" delay="0" conditionEdge="none">
${indent(
  byEntity(
    'overtaker',
    '<RelativeDistanceCondition parameterAttributes="entityRef,value" entityRef="ego" relativeDistanceType="longitudinal" value="10" freespace="true" rule="greaterThan"/>',
  ),
  6,
)}
    </Condition>
  </ConditionGroup>
</StartTrigger>`;
/** The lane-change time of every module that changes lane. @param {string} [about] @returns {Parameter} */
const laneChangeTimeParameter = (about = 'how long the lane change takes') => ({
  key: 'LaneChangeActionDynamics.value',
  name: 'laneChangeTime',
  unit: 's',
  range: '0.5..10',
  about,
});
/** A lane change's dynamics, its time a key. @param {number} time */
const sinusoidalLaneChange = (time) =>
  `<LaneChangeActionDynamics parameterAttributes="value" dynamicsShape="sinusoidal" value="${time}" dynamicsDimension="time"/>`;
/** A braking at the deceleration the key `SpeedActionDynamics.value` gives (6 m/s² by default) down to `target`, started by `start`. */
const brakeEvent = (/** @type {string} */ name, /** @type {string} */ target, /** @type {string} */ start) =>
  event(
    name,
    privateAction(
      name,
      speedAction('<SpeedActionDynamics parameterAttributes="value" dynamicsShape="linear" value="6" dynamicsDimension="rate"/>', target),
    ),
    start,
    'parallel',
  );
/**
 * The actor takes a speed (a key) at once, from the start or when `start` holds.
 * @param {string} name @param {number} speed @param {string} triggerName @param {string} [start]
 */
const speedFromStart = (name, speed, triggerName, start = atTime(0)) =>
  event(
    name,
    privateAction(
      name,
      speedAction(
        '<SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>',
        `<AbsoluteTargetSpeed parameterAttributes="value" value="${speed}"/>`,
      ),
    ),
    trigger(triggerName, start),
    'parallel',
  );
/**
 * From the start, the actor adapts its speed to reach `target` (on the crossroads) as the ego reaches x `egoAt` on its
 * lane's centre (y -1.75), arriving at `speed`; egoAt (WorldPosition.x) and speed (AbsoluteSpeed.value) are keys.
 * `target` is a lane position on the actor's connecting road: esmini 3.6 puts a WorldPosition on the first road of the
 * file that covers it (RoadManager.cpp XYZ2TrackPos, heading disregarded), and in the junction that is road 101, the ego's.
 * @param {string} name @param {string} startName @param {number} egoAt @param {{ road: number, lane: number, s: number }} target @param {number} speed
 */
const synchronizedArrival = (name, startName, egoAt, target, speed) =>
  event(
    name,
    privateAction(
      name,
      `<SynchronizeAction parameterAttributes="masterEntityRef" masterEntityRef="ego">
  <TargetPositionMaster>
    <WorldPosition parameterAttributes="x" x="${egoAt}" y="-1.75" z="0" h="0" p="0" r="0"/>
  </TargetPositionMaster>
  <TargetPosition>
    <LanePosition roadId="${target.road}" laneId="${target.lane}" s="${target.s}" offset="0"/>
  </TargetPosition>
  <FinalSpeed>
    <AbsoluteSpeed parameterAttributes="value" value="${speed}"/>
  </FinalSpeed>
</SynchronizeAction>`,
    ),
    trigger(startName, atTime(0)),
    'parallel',
  );
/**
 * The keys of a synchronizedArrival: where the ego is at the arrival (the conflict point at x `conflictX` by default),
 * the speed of arrival, and the ego.
 * @param {string} mover @param {number} conflictX @param {string} gapNote @param {{ name: string, range: string, about: string }} speed
 * @returns {Parameter[]}
 */
const synchronizedParameters = (mover, conflictX, gapNote, speed) => [
  {
    key: 'WorldPosition.x',
    name: 'egoAt',
    unit: 'm',
    range: `-60..${conflictX}`,
    about: `where (x on the crossroads) the ego is when the ${mover} vehicle reaches the conflict point: ${conflictX} the conflict point itself (a collision course), less: the ego that far short of it${gapNote}`,
  },
  { key: 'AbsoluteSpeed.value', unit: 'm/s', ...speed },
  { key: 'SynchronizeAction.masterEntityRef', name: 'ego', about: 'the vehicle whose arrival it synchronizes with' },
];
/** A straight walk or ride from where the actor stands, `length` metres ahead of it. @param {string} actor @param {number} length */
const crossing = (actor, length) => `<RoutingAction>
  <FollowTrajectoryAction>
    <TrajectoryRef>
      <Trajectory name="Crossing" closed="false">
        <ParameterDeclarations/>
        <Shape>
          <Polyline>
            <Vertex>
              <Position>
                <RelativeObjectPosition parameterAttributes="entityRef" entityRef="${actor}" dx="0" dy="0"/>
              </Position>
            </Vertex>
            <Vertex>
              <Position>
                <RelativeObjectPosition parameterAttributes="entityRef,dx" entityRef="${actor}" dx="${length}" dy="0"/>
              </Position>
            </Vertex>
          </Polyline>
        </Shape>
      </Trajectory>
    </TrajectoryRef>
    <TimeReference>
      <None/>
    </TimeReference>
    <TrajectoryFollowingMode followingMode="position"/>
  </FollowTrajectoryAction>
</RoutingAction>`;

/**
 * @typedef {{ key: string, name: string, unit?: string, range?: string, about: string }} Parameter
 * @typedef {{
 *   name: string, title: string, group: string, summary: string, actor: string, groupName: string,
 *   entities: string[], init: string[], parameters: Parameter[], maneuver: string, stopAt: number, otherActors?: string[],
 *   road?: string, queue?: 'enters' | 'slower',
 *   actorName: string, keys: Record<string, string>,
 * }} Module
 */

/** @type {Module[]} */
export const MODULES = [
  {
    name: 'cut-in',
    // Its car enters the ego's lane ahead of it: a slower car inserted later goes behind it (docs/library.md).
    queue: 'enters',
    title: 'Cut-in',
    group: 'Vehicles ahead',
    summary:
      "A vehicle in a lane beside the ego's (either side) drives at a set speed and, once the gap between it and the ego is below the one asked, changes into the ego's lane.",
    actor: "the cutting-in car, in a lane beside the ego's",
    actorName: 'adversary',
    groupName: 'CutIn',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('adversary', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 20), placed('adversary', -2, 85, 17)],
    stopAt: 10,
    parameters: [
      { key: 'AbsoluteTargetSpeed.value', name: 'speed', unit: 'm/s', range: '0..70', about: "the cutting-in car's speed from the start" },
      {
        key: 'RelativeDistanceCondition.value',
        name: 'gap',
        unit: 'm',
        range: '2..100',
        about: 'the gap (bumper to bumper, along the road) between the ego and the car when the lane change starts',
      },
      laneChangeTimeParameter(),
      { key: 'RelativeDistanceCondition.entityRef', name: 'ego', about: 'the vehicle it cuts in ahead of' },
      { key: 'RelativeTargetLane.entityRef', name: 'egoLane', about: 'the vehicle whose lane it changes into (the ego)' },
      { key: 'EntityRef.entityRef', name: 'self', about: 'the cutting-in car itself (as in Actors): its gap triggers the lane change' },
    ],
    keys: {},
    maneuver: [
      speedFromStart('CutInSpeed', 17, 'CutInSpeedStart'),
      event(
        'CutInLaneChange',
        privateAction(
          'CutInLaneChange',
          laneChange(sinusoidalLaneChange(3), '<RelativeTargetLane parameterAttributes="entityRef" entityRef="ego" value="0"/>'),
        ),
        trigger(
          'CutInGap',
          byEntity(
            'adversary',
            '<RelativeDistanceCondition parameterAttributes="entityRef,value" entityRef="ego" relativeDistanceType="longitudinal" value="20" freespace="true" rule="lessThan"/>',
          ),
        ),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'lead-brake',
    // Slower than the ego ahead in its lane: behind a car that enters the lane, which would run into it braking.
    queue: 'slower',
    title: 'Lead vehicle braking',
    group: 'Vehicles ahead',
    summary:
      "The vehicle ahead in the ego's lane brakes at a set deceleration down to a set speed, once the ego's time headway to it is below the one asked (at once when it already is).",
    actor: "the lead vehicle, ahead in the ego's lane",
    actorName: 'lead',
    groupName: 'LeadBrake',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('lead', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 16), placed('lead', -1, 84.5, 14)],
    stopAt: 8,
    parameters: [
      { key: 'SpeedActionDynamics.value', name: 'deceleration', unit: 'm/s²', range: '0.5..10', about: 'how hard the lead vehicle brakes' },
      {
        key: 'AbsoluteTargetSpeed.value',
        name: 'speedAfter',
        unit: 'm/s',
        range: '0..70',
        about: 'the speed it brakes down to (0: to a stop)',
      },
      {
        key: 'TimeHeadwayCondition.value',
        name: 'headway',
        unit: 's',
        range: '0.2..10',
        about: "the ego's time headway (gap / ego speed) to the lead vehicle when the braking starts",
      },
      { key: 'TimeHeadwayCondition.entityRef', name: 'self', about: 'the lead vehicle itself (as in Actors)' },
      { key: 'EntityRef.entityRef', name: 'ego', about: 'the vehicle following it, whose headway counts' },
    ],
    keys: {},
    maneuver: brakeEvent(
      'LeadBrake',
      '<AbsoluteTargetSpeed parameterAttributes="value" value="0"/>',
      trigger(
        'LeadBrakeHeadway',
        byEntity(
          'ego',
          '<TimeHeadwayCondition parameterAttributes="entityRef,value" entityRef="lead" value="1.5" freespace="true" coordinateSystem="road" relativeDistanceType="longitudinal" rule="lessThan"/>',
        ),
      ),
    ),
  },
  {
    name: 'ttc-brake',
    title: 'Braking at a time to collision',
    group: 'Vehicles ahead',
    summary:
      'A vehicle closing in on a standing or slower vehicle ahead in its lane brakes at a set deceleration to a stop once its time to collision with it (the gap between them over the speed it closes in at) is below the one asked: the late braking of a driver or an emergency-braking system, at the time to collision rear-end test protocols vary.',
    actor: 'the vehicle that closes in and brakes, behind the other in its lane',
    actorName: 'follower',
    groupName: 'TtcBrake',
    entities: [VEHICLE('ahead', 'vehicle.tesla.model3'), VEHICLE('follower', 'vehicle.audi.tt')],
    init: [placed('ahead', -1, 300, 0), placed('follower', -1, 100, 20)],
    stopAt: 11,
    parameters: [
      {
        key: 'TimeToCollisionCondition.value',
        name: 'ttc',
        unit: 's',
        range: '0.5..10',
        about: 'its time to collision with the vehicle ahead (gap / closing speed) when the braking starts',
      },
      {
        key: 'SpeedActionDynamics.value',
        name: 'deceleration',
        unit: 'm/s²',
        range: '0.5..10',
        about: 'how hard it brakes, down to a stop',
      },
      {
        key: 'TimeToCollisionConditionTarget.EntityRef.entityRef',
        name: 'ahead',
        about: 'the vehicle ahead in its lane that it closes in on',
      },
      {
        key: 'TriggeringEntities.EntityRef.entityRef',
        name: 'self',
        about: 'the vehicle itself (as in Actors): its time to collision counts',
      },
    ],
    keys: { 'TimeToCollisionConditionTarget.EntityRef.entityRef': 'ahead', 'TriggeringEntities.EntityRef.entityRef': 'follower' },
    maneuver: brakeEvent(
      'TtcBrake',
      '<AbsoluteTargetSpeed value="0"/>',
      trigger(
        'TtcBrakeTimeToCollision',
        byEntity(
          'follower',
          `<TimeToCollisionCondition parameterAttributes="value" value="4" freespace="true" coordinateSystem="road" relativeDistanceType="longitudinal" rule="lessThan">
      <TimeToCollisionConditionTarget>
        <EntityRef parameterAttributes="entityRef" entityRef="ahead"/>
      </TimeToCollisionConditionTarget>
    </TimeToCollisionCondition>`,
        ),
      ),
    ),
  },
  {
    name: 'slow-target',
    // Slower than the ego ahead in its lane: behind a car that enters the lane, which would run into it.
    queue: 'slower',
    title: 'Stationary or slow target ahead',
    group: 'Vehicles ahead',
    summary: "A vehicle ahead in the ego's lane stands still or drives slowly at a set speed from the start, for the ego to come up to.",
    actor: "the target vehicle, ahead in the ego's lane",
    actorName: 'target',
    groupName: 'SlowTarget',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('target', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 14), placed('target', -1, 150, 10)],
    stopAt: 6,
    parameters: [{ key: 'AbsoluteTargetSpeed.value', name: 'speed', unit: 'm/s', range: '0..40', about: 'its speed (0: stationary)' }],
    keys: {},
    maneuver: speedFromStart('SlowTargetSpeed', 0, 'SlowTargetStart'),
  },
  {
    name: 'pedestrian-crossing',
    title: 'Pedestrian crossing',
    group: 'Vulnerable road users',
    summary:
      "A pedestrian at the roadside (near or far side, or behind a parked vehicle: where the main places it, facing across the road) walks straight across at a set speed once the ego's time headway to its crossing line is below the one asked.",
    actor: 'the pedestrian, at the roadside facing across the road',
    actorName: 'pedestrian',
    groupName: 'PedestrianCrossing',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), PEDESTRIAN('pedestrian')],
    init: [placed('ego', -1, 20, 10), placed('pedestrian', -4, 100, 0, { offset: 0.75, heading: 1.5708 })],
    stopAt: 10,
    parameters: [
      { key: 'AbsoluteTargetSpeed.value', name: 'speed', unit: 'm/s', range: '0.5..3', about: 'its walking speed' },
      {
        key: 'TimeHeadwayCondition.value',
        name: 'headway',
        unit: 's',
        range: '0.5..15',
        about:
          "the ego's time to the crossing line when it starts walking: distance to the ego's path / speed puts it on the path as the ego arrives",
      },
      { key: 'RelativeObjectPosition.dx', name: 'distance', unit: 'm', range: '1..30', about: 'how far it walks' },
      {
        key: 'RelativeObjectPosition.entityRef',
        name: 'self',
        about: 'the pedestrian itself (as in Actors): its walk starts where it stands',
      },
      { key: 'TimeHeadwayCondition.entityRef', name: 'selfHeadway', about: 'the pedestrian itself, the ego headway is measured to' },
      { key: 'EntityRef.entityRef', name: 'ego', about: 'the vehicle it crosses in front of' },
    ],
    keys: {},
    maneuver: event(
      'PedestrianWalk',
      [
        privateAction('PedestrianPath', crossing('pedestrian', 14)),
        privateAction(
          'PedestrianSpeed',
          speedAction(
            '<SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>',
            '<AbsoluteTargetSpeed parameterAttributes="value" value="1.5"/>',
          ),
        ),
      ].join('\n'),
      trigger(
        'PedestrianHeadway',
        byEntity(
          'ego',
          '<TimeHeadwayCondition parameterAttributes="entityRef,value" entityRef="pedestrian" value="6" freespace="false" coordinateSystem="road" relativeDistanceType="longitudinal" rule="lessThan"/>',
        ),
      ),
      'parallel',
    ),
  },
  {
    name: 'cut-out',
    title: 'Cut-out revealing a target',
    group: 'Vehicles ahead',
    summary:
      "The vehicle ahead in the ego's lane changes lane once it is within the gap asked of a stopped or slow vehicle further ahead, revealing it to the ego.",
    actor: "the cutting-out vehicle, ahead in the ego's lane",
    actorName: 'lead',
    groupName: 'CutOut',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('lead', 'vehicle.audi.tt'), VEHICLE('target', 'vehicle.tesla.model3')],
    init: [placed('ego', -1, 50, 15), placed('lead', -1, 80, 15), placed('target', -1, 180, 0)],
    stopAt: 9,
    parameters: [
      {
        key: 'RelativeDistanceCondition.value',
        name: 'gap',
        unit: 'm',
        range: '2..100',
        about: 'its gap to the vehicle ahead of it when the lane change starts',
      },
      laneChangeTimeParameter(),
      {
        key: 'RelativeTargetLane.value',
        name: 'side',
        unit: 'lanes',
        range: '-1..1',
        about: 'the lane it moves to: 1 the next lane to the left, -1 to the right',
      },
      { key: 'RelativeDistanceCondition.entityRef', name: 'target', about: 'the vehicle ahead that it reveals' },
      {
        key: 'RelativeTargetLane.entityRef',
        name: 'self',
        about: 'the cutting-out vehicle itself (as in Actors): its lane is the reference',
      },
      { key: 'EntityRef.entityRef', name: 'selfTrigger', about: 'the cutting-out vehicle itself, whose gap counts' },
    ],
    keys: {},
    maneuver: event(
      'CutOutLaneChange',
      privateAction(
        'CutOutLaneChange',
        laneChange(sinusoidalLaneChange(2), '<RelativeTargetLane parameterAttributes="entityRef,value" entityRef="lead" value="-1"/>'),
      ),
      trigger(
        'CutOutGap',
        byEntity(
          'lead',
          '<RelativeDistanceCondition parameterAttributes="entityRef,value" entityRef="target" relativeDistanceType="longitudinal" value="30" freespace="true" rule="lessThan"/>',
        ),
      ),
      'parallel',
    ),
  },
  {
    name: 'cyclist-ahead',
    // Slower than the ego ahead in its lane: behind a car that enters the lane, which would run into it.
    queue: 'slower',
    title: 'Cyclist ahead',
    group: 'Vulnerable road users',
    summary: "A cyclist rides ahead in the ego's lane, near its right edge, at a set speed from the start, for the ego to come up to.",
    actor: "the cyclist, ahead in the ego's lane",
    actorName: 'cyclist',
    groupName: 'CyclistAhead',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), BICYCLE('cyclist')],
    init: [placed('ego', -1, 20, 14), placed('cyclist', -1, 80, 5, { offset: -0.9 })],
    stopAt: 6,
    parameters: [{ key: 'AbsoluteTargetSpeed.value', name: 'speed', unit: 'm/s', range: '0..12', about: 'its riding speed' }],
    keys: {},
    maneuver: speedFromStart('CyclistSpeed', 4, 'CyclistStart'),
  },
  {
    name: 'cyclist-crossing',
    title: 'Cyclist crossing',
    group: 'Vulnerable road users',
    summary:
      "A cyclist at the roadside (where the main places it, facing across the road) rides straight across at a set speed once the ego's time headway to its crossing line is below the one asked.",
    actor: 'the cyclist, at the roadside facing across the road',
    actorName: 'cyclist',
    groupName: 'CyclistCrossing',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), BICYCLE('cyclist')],
    init: [placed('ego', -1, 20, 12), placed('cyclist', -4, 100, 0, { offset: 0.5, heading: 1.5708 })],
    stopAt: 9,
    parameters: [
      { key: 'AbsoluteTargetSpeed.value', name: 'speed', unit: 'm/s', range: '1..10', about: 'its riding speed' },
      {
        key: 'TimeHeadwayCondition.value',
        name: 'headway',
        unit: 's',
        range: '0.5..15',
        about:
          "the ego's time to the crossing line when it starts riding: distance to the ego's path / speed puts it on the path as the ego arrives",
      },
      { key: 'RelativeObjectPosition.dx', name: 'distance', unit: 'm', range: '1..30', about: 'how far it rides' },
      {
        key: 'RelativeObjectPosition.entityRef',
        name: 'self',
        about: 'the cyclist itself (as in Actors): its ride starts where it stands',
      },
      { key: 'TimeHeadwayCondition.entityRef', name: 'selfHeadway', about: 'the cyclist itself, the ego headway is measured to' },
      { key: 'EntityRef.entityRef', name: 'ego', about: 'the vehicle it crosses in front of' },
    ],
    keys: {},
    maneuver: event(
      'CyclistRide',
      [
        privateAction('CyclistPath', crossing('cyclist', 16)),
        privateAction(
          'CyclistSpeed',
          speedAction(
            '<SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>',
            '<AbsoluteTargetSpeed parameterAttributes="value" value="4"/>',
          ),
        ),
      ].join('\n'),
      trigger(
        'CyclistHeadway',
        byEntity(
          'ego',
          '<TimeHeadwayCondition parameterAttributes="entityRef,value" entityRef="cyclist" value="2.25" freespace="false" coordinateSystem="road" relativeDistanceType="longitudinal" rule="lessThan"/>',
        ),
      ),
      'parallel',
    ),
  },
  {
    name: 'lane-change',
    title: 'Lane change',
    group: 'Vehicles beside',
    summary: 'A vehicle changes one lane to the left or right at a set time, taking a set time for it.',
    actor: 'the vehicle changing lane',
    actorName: 'adversary',
    groupName: 'LaneChange',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('adversary', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 15), placed('adversary', -2, 70, 15)],
    stopAt: 7,
    parameters: [
      { key: 'SimulationTimeCondition.value', name: 'startTime', unit: 's', range: '0..600', about: 'when the lane change starts' },
      laneChangeTimeParameter(),
      {
        key: 'RelativeTargetLane.value',
        name: 'side',
        unit: 'lanes',
        range: '-1..1',
        about: 'the lane it moves to: 1 the next lane to the left, -1 to the right',
      },
      { key: 'RelativeTargetLane.entityRef', name: 'self', about: 'the vehicle itself (as in Actors): its lane is the reference' },
    ],
    keys: {},
    maneuver: event(
      'LaneChange',
      privateAction(
        'LaneChange',
        laneChange(sinusoidalLaneChange(3), '<RelativeTargetLane parameterAttributes="entityRef,value" entityRef="adversary" value="1"/>'),
      ),
      trigger('LaneChangeStart', atTime(2, ' parameterAttributes="value"')),
      'parallel',
    ),
  },
  {
    name: 'oncoming-vehicle',
    title: 'Oncoming vehicle in the ego lane',
    group: 'Vehicles oncoming or crossing',
    summary:
      "A vehicle in the lane of the other direction drives towards the ego at a set speed and, once the gap between them is below the one asked, moves over into the ego's lane, head-on, at a set lateral offset from its centre.",
    actor: 'the oncoming vehicle, in the lane of the other direction',
    actorName: 'oncoming',
    groupName: 'OncomingVehicle',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('oncoming', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 15), placed('oncoming', 1, 300, 15)],
    stopAt: 7.5,
    parameters: [
      {
        key: 'AbsoluteTargetSpeed.value',
        name: 'speed',
        unit: 'm/s',
        range: '0..70',
        about: "the oncoming vehicle's speed from the start",
      },
      {
        key: 'RelativeDistanceCondition.value',
        name: 'gap',
        unit: 'm',
        range: '5..300',
        about: 'the gap (bumper to bumper, along the road) between it and the ego when it starts moving over',
      },
      laneChangeTimeParameter("how long moving over into the ego's lane takes"),
      {
        key: 'LaneChangeAction.targetLaneOffset',
        name: 'offset',
        unit: 'm',
        range: '-1.75..1.75',
        about:
          "where it ends across the ego's lane: its offset from the lane's centre line, positive to the ego's left (0: head-on, full overlap)",
      },
      { key: 'RelativeDistanceCondition.entityRef', name: 'ego', about: 'the vehicle it drives towards' },
      { key: 'RelativeTargetLane.entityRef', name: 'egoLane', about: 'the vehicle whose lane it moves into (the ego)' },
      { key: 'EntityRef.entityRef', name: 'self', about: 'the oncoming vehicle itself (as in Actors): its gap triggers the move' },
    ],
    keys: {},
    maneuver: [
      speedFromStart('OncomingSpeed', 15, 'OncomingSpeedStart'),
      event(
        'OncomingIntoEgoLane',
        privateAction(
          'OncomingIntoEgoLane',
          laneChange(
            sinusoidalLaneChange(2),
            '<RelativeTargetLane parameterAttributes="entityRef" entityRef="ego" value="0"/>',
            ' parameterAttributes="targetLaneOffset" targetLaneOffset="0"',
          ),
        ),
        trigger(
          'OncomingGap',
          byEntity(
            'oncoming',
            '<RelativeDistanceCondition parameterAttributes="entityRef,value" entityRef="ego" relativeDistanceType="longitudinal" value="100" freespace="true" rule="lessThan"/>',
          ),
        ),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'double-lane-change',
    title: 'Double lane change',
    group: 'Vehicles ahead',
    summary:
      "The vehicle ahead in the ego's lane changes into the lane beside it (left or right) at a set time, stays there for a set time, and changes back into the ego's lane.",
    actor: "the vehicle changing lane, ahead in the ego's lane",
    actorName: 'lead',
    groupName: 'DoubleLaneChange',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('lead', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 15), placed('lead', -1, 80, 15)],
    stopAt: 10,
    parameters: [
      { key: 'SimulationTimeCondition.value', name: 'startTime', unit: 's', range: '0..600', about: 'when the first lane change starts' },
      laneChangeTimeParameter('how long each of the two lane changes takes'),
      {
        key: 'RelativeTargetLane.value',
        name: 'side',
        unit: 'lanes',
        range: '-1..1',
        about: "the lane it moves out to: 1 the lane left of the ego's, -1 the one right of it",
      },
      { key: 'Condition.delay', name: 'hold', unit: 's', range: '0..60', about: 'how long it stays in that lane before changing back' },
      { key: 'RelativeTargetLane.entityRef', name: 'ego', about: 'the vehicle whose lane it leaves and comes back to (the ego)' },
    ],
    keys: {},
    maneuver: [
      event(
        'DoubleLaneChangeOut',
        privateAction(
          'DoubleLaneChangeOut',
          laneChange(sinusoidalLaneChange(2.5), '<RelativeTargetLane parameterAttributes="entityRef,value" entityRef="ego" value="1"/>'),
        ),
        trigger('DoubleLaneChangeStart', atTime(1, ' parameterAttributes="value"')),
        'parallel',
      ),
      event(
        'DoubleLaneChangeBack',
        privateAction(
          'DoubleLaneChangeBack',
          laneChange(sinusoidalLaneChange(2.5), '<RelativeTargetLane parameterAttributes="entityRef" entityRef="ego" value="0"/>'),
        ),
        afterEvent('DoubleLaneChangeHold', 'DoubleLaneChangeOut', 2),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'overtaking',
    title: 'Overtaking',
    group: 'Vehicles beside',
    summary:
      "A faster vehicle behind the ego in its lane pulls out into the lane beside it once its time headway to the ego is below the one asked, passes the ego, and changes back into the ego's lane once it is the gap asked ahead of it.",
    actor: "the overtaking vehicle, behind the ego in the ego's lane",
    actorName: 'overtaker',
    groupName: 'Overtaking',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('overtaker', 'vehicle.audi.tt')],
    init: [placed('ego', -2, 80, 15), placed('overtaker', -2, 30, 22)],
    stopAt: 14,
    parameters: [
      {
        key: 'AbsoluteTargetSpeed.value',
        name: 'speed',
        unit: 'm/s',
        range: '0..70',
        about: "the overtaking vehicle's speed from the start",
      },
      {
        key: 'TimeHeadwayCondition.value',
        name: 'headway',
        unit: 's',
        range: '0.2..10',
        about: 'its time headway (gap / its speed) to the ego when it pulls out',
      },
      {
        key: 'RelativeDistanceCondition.value',
        name: 'gap',
        unit: 'm',
        range: '2..100',
        about: "the gap (bumper to bumper, along the road) ahead of the ego when it changes back into the ego's lane",
      },
      laneChangeTimeParameter('how long each of the two lane changes takes'),
      {
        key: 'RelativeTargetLane.value',
        name: 'side',
        unit: 'lanes',
        range: '-1..1',
        about: "the lane it passes in: 1 the lane left of the ego's, -1 the one right of it",
      },
      { key: 'TimeHeadwayCondition.entityRef', name: 'ego', about: 'the vehicle it overtakes' },
      { key: 'RelativeDistanceCondition.entityRef', name: 'egoGap', about: 'the vehicle it overtakes, whose gap counts for changing back' },
      { key: 'RelativeTargetLane.entityRef', name: 'egoLane', about: 'the vehicle whose lane it leaves and comes back to (the ego)' },
      { key: 'EntityRef.entityRef', name: 'self', about: 'the overtaking vehicle itself (as in Actors): its headway and gap count' },
    ],
    keys: {},
    maneuver: [
      speedFromStart('OvertakingSpeed', 22, 'OvertakingSpeedStart'),
      event(
        'OvertakingPullOut',
        privateAction(
          'OvertakingPullOut',
          laneChange(sinusoidalLaneChange(2), '<RelativeTargetLane parameterAttributes="entityRef,value" entityRef="ego" value="1"/>'),
        ),
        trigger(
          'OvertakingHeadway',
          byEntity(
            'overtaker',
            '<TimeHeadwayCondition parameterAttributes="entityRef,value" entityRef="ego" value="1" freespace="true" coordinateSystem="road" relativeDistanceType="longitudinal" rule="lessThan"/>',
          ),
        ),
        'parallel',
      ),
      event(
        'OvertakingCutBack',
        privateAction(
          'OvertakingCutBack',
          laneChange(sinusoidalLaneChange(2), '<RelativeTargetLane parameterAttributes="entityRef" entityRef="ego" value="0"/>'),
        ),
        overtakenTrigger(),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'swerving-lead',
    title: 'Swerving lead vehicle',
    group: 'Vehicles ahead',
    summary:
      "The vehicle ahead in the ego's lane swerves sideways within the road to a set offset from its lane's centre at a set time, with a set lateral acceleration, stays there for a set time and swerves back to the centre.",
    actor: "the swerving vehicle, ahead in the ego's lane",
    actorName: 'lead',
    groupName: 'SwervingLead',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('lead', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 50, 15), placed('lead', -1, 80, 15)],
    stopAt: 8,
    parameters: [
      { key: 'SimulationTimeCondition.value', name: 'startTime', unit: 's', range: '0..600', about: 'when the swerve starts' },
      {
        key: 'AbsoluteTargetLaneOffset.value',
        name: 'offset',
        unit: 'm',
        range: '-3.5..3.5',
        about: "how far it swerves from its lane's centre line: positive to the left, negative to the right",
      },
      {
        key: 'LaneOffsetActionDynamics.maxLateralAcc',
        name: 'lateralAcceleration',
        unit: 'm/s²',
        range: '0.5..10',
        about: 'the largest lateral acceleration of the swerve, out and back',
      },
      { key: 'Condition.delay', name: 'hold', unit: 's', range: '0..60', about: 'how long it stays at the offset before swerving back' },
    ],
    keys: {},
    maneuver: [
      event(
        'SwerveOut',
        privateAction('SwerveOut', laneOffset('<AbsoluteTargetLaneOffset parameterAttributes="value" value="1.5"/>')),
        trigger('SwerveStart', atTime(1, ' parameterAttributes="value"')),
        'parallel',
      ),
      event(
        'SwerveBack',
        privateAction('SwerveBack', laneOffset('<AbsoluteTargetLaneOffset value="0"/>')),
        afterEvent('SwerveHold', 'SwerveOut', 1),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'traffic-jam-end',
    title: 'End of a traffic jam',
    group: 'Vehicles ahead',
    summary:
      "A queue of vehicles ahead, in the ego's lane and the one beside it, brakes together at a set deceleration down to the jam's speed once the ego's time headway to the last of them is below the one asked: the end of a traffic jam the ego comes up to.",
    actor:
      "the last vehicle of the queue, ahead in the ego's lane (the queue's other vehicles, jam2 and jam3, are actors too: each brakes alike)",
    actorName: 'jam1',
    otherActors: ['jam2', 'jam3'],
    groupName: 'TrafficJamEnd',
    entities: [
      VEHICLE('ego', 'vehicle.lincoln.mkz_2017'),
      VEHICLE('jam1', 'vehicle.audi.tt'),
      VEHICLE('jam2', 'vehicle.tesla.model3'),
      VEHICLE('jam3', 'vehicle.audi.tt'),
    ],
    init: [placed('ego', -1, 20, 25), placed('jam1', -1, 150, 10), placed('jam2', -1, 160, 10), placed('jam3', -2, 154, 10)],
    stopAt: 6.5,
    parameters: [
      { key: 'SpeedActionDynamics.value', name: 'deceleration', unit: 'm/s²', range: '0.5..10', about: 'how hard the queue brakes' },
      {
        key: 'AbsoluteTargetSpeed.value',
        name: 'jamSpeed',
        unit: 'm/s',
        range: '0..30',
        about: 'the speed the queue brakes down to (0: it comes to a stop)',
      },
      {
        key: 'TimeHeadwayCondition.value',
        name: 'headway',
        unit: 's',
        range: '0.2..20',
        about: "the ego's time headway (gap / ego speed) to the last vehicle of the queue when the queue brakes",
      },
      {
        key: 'TimeHeadwayCondition.entityRef',
        name: 'last',
        about: "the last vehicle of the queue in the ego's lane, the headway is measured to",
      },
      { key: 'TriggeringEntities.EntityRef.entityRef', name: 'ego', about: 'the vehicle coming up to the queue, whose headway counts' },
      { key: 'Actors.EntityRef[2].entityRef', name: 'jam2', about: 'the second vehicle of the queue, ahead of jam1 in the ego’s lane' },
      { key: 'Actors.EntityRef[3].entityRef', name: 'jam3', about: 'the third vehicle of the queue, in the lane beside the ego’s' },
    ],
    keys: {
      'TriggeringEntities.EntityRef.entityRef': 'ego',
      'Actors.EntityRef[2].entityRef': 'jam2',
      'Actors.EntityRef[3].entityRef': 'jam3',
    },
    maneuver: event(
      'TrafficJamBrake',
      privateAction(
        'TrafficJamBrake',
        speedAction(
          '<SpeedActionDynamics parameterAttributes="value" dynamicsShape="linear" value="4" dynamicsDimension="rate"/>',
          '<AbsoluteTargetSpeed parameterAttributes="value" value="0"/>',
        ),
      ),
      trigger(
        'TrafficJamHeadway',
        byEntity(
          'ego',
          '<TimeHeadwayCondition parameterAttributes="entityRef,value" entityRef="jam1" value="3" freespace="true" coordinateSystem="road" relativeDistanceType="longitudinal" rule="lessThan"/>',
        ),
      ),
      'parallel',
    ),
  },
  {
    name: 'weather-light-change',
    title: 'Weather and light change',
    group: 'Environment',
    summary:
      'At a set time the environment changes for every entity: time of day, sun, cloud, fog, precipitation and road friction, as a test protocol varies light and weather.',
    actor: 'ego: any entity of the scenario (the change is global; the group needs an actor to be a group)',
    actorName: 'ego',
    groupName: 'WeatherLightChange',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017')],
    init: [placed('ego', -1, 50, 15)],
    stopAt: 4,
    parameters: [
      { key: 'SimulationTimeCondition.value', name: 'startTime', unit: 's', range: '0..600', about: 'when the environment changes' },
      { key: 'TimeOfDay.dateTime', name: 'dateTime', unit: 'ISO 8601', about: 'the date and time of day after the change (local time)' },
      { key: 'Weather.cloudState', name: 'clouds', range: 'free, cloudy, overcast, rainy, skyOff', about: 'the sky' },
      { key: 'Sun.intensity', name: 'sunIntensity', unit: 'lx', range: '0..150000', about: "the sun's illuminance (dusk: about 400)" },
      { key: 'Sun.elevation', name: 'sunElevation', unit: 'rad', range: '-1.571..1.571', about: "the sun's elevation above the horizon" },
      { key: 'Sun.azimuth', name: 'sunAzimuth', unit: 'rad', range: '0..6.283', about: "the sun's azimuth (0 north, pi/2 east)" },
      { key: 'Fog.visualRange', name: 'visibility', unit: 'm', range: '1..100000', about: 'how far one sees through the fog' },
      { key: 'Precipitation.precipitationType', name: 'precipitation', range: 'dry, rain, snow', about: 'what falls' },
      {
        key: 'Precipitation.precipitationIntensity',
        name: 'precipitationIntensity',
        unit: 'mm/h',
        range: '0..100',
        about: 'how much falls',
      },
      { key: 'RoadCondition.frictionScaleFactor', name: 'friction', range: '0..1', about: "the road's friction, 1 dry asphalt" },
    ],
    keys: {},
    maneuver: event(
      'WeatherLightChange',
      `<Action name="WeatherLightChange">
  <GlobalAction>
    <EnvironmentAction>
      <Environment name="AfterChange">
        <TimeOfDay parameterAttributes="dateTime" animation="false" dateTime="2026-11-27T17:30:00"/>
        <Weather parameterAttributes="cloudState" cloudState="rainy">
          <Sun parameterAttributes="intensity,elevation,azimuth" azimuth="4.2" elevation="0.05" intensity="400"/>
          <Fog parameterAttributes="visualRange" visualRange="80"/>
          <Precipitation parameterAttributes="precipitationType,precipitationIntensity" precipitationType="rain" precipitationIntensity="8"/>
        </Weather>
        <RoadCondition parameterAttributes="frictionScaleFactor" frictionScaleFactor="0.6"/>
      </Environment>
    </EnvironmentAction>
  </GlobalAction>
</Action>`,
      trigger('WeatherLightChangeStart', atTime(1, ' parameterAttributes="value"')),
      'parallel',
    ),
  },
  {
    name: 'highway-merge',
    // Its car enters the ego's lane ahead of it: a slower car inserted later goes behind it (docs/library.md).
    queue: 'enters',
    title: 'Highway merge',
    group: 'Vehicles beside',
    summary:
      "On a motorway with an on-ramp (the library's road highway_merge_600m.xodr), a vehicle in the acceleration lane, right of the ego's lane, accelerates from its ramp speed at a set rate to a set speed and merges into the ego's lane ahead of it once the gap is below the one asked.",
    actor: "the merging vehicle, in the acceleration lane right of the ego's",
    actorName: 'merging',
    groupName: 'HighwayMerge',
    road: 'highway_merge_600m.xodr',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('merging', 'vehicle.audi.tt')],
    init: [placed('ego', -2, 20, 25), placed('merging', -3, 60, 15)],
    stopAt: 6,
    parameters: [
      {
        key: 'SpeedActionDynamics.value',
        name: 'acceleration',
        unit: 'm/s²',
        range: '0.5..6',
        about: 'how hard it accelerates from its ramp speed',
      },
      { key: 'AbsoluteTargetSpeed.value', name: 'speed', unit: 'm/s', range: '0..70', about: 'the speed it accelerates to' },
      {
        key: 'RelativeDistanceCondition.value',
        name: 'gap',
        unit: 'm',
        range: '2..100',
        about: 'the gap (bumper to bumper, along the road) ahead of the ego when it starts merging',
      },
      laneChangeTimeParameter('how long the merge takes'),
      { key: 'RelativeDistanceCondition.entityRef', name: 'ego', about: 'the vehicle it merges ahead of' },
      { key: 'RelativeTargetLane.entityRef', name: 'egoLane', about: 'the vehicle whose lane it merges into (the ego)' },
      { key: 'EntityRef.entityRef', name: 'self', about: 'the merging vehicle itself (as in Actors): its gap triggers the merge' },
    ],
    keys: {},
    maneuver: [
      event(
        'MergeAccelerate',
        privateAction(
          'MergeAccelerate',
          speedAction(
            '<SpeedActionDynamics parameterAttributes="value" dynamicsShape="linear" value="2" dynamicsDimension="rate"/>',
            '<AbsoluteTargetSpeed parameterAttributes="value" value="22"/>',
          ),
        ),
        trigger('MergeAccelerateStart', atTime(0)),
        'parallel',
      ),
      event(
        'MergeLaneChange',
        privateAction(
          'MergeLaneChange',
          laneChange(sinusoidalLaneChange(3), '<RelativeTargetLane parameterAttributes="entityRef" entityRef="ego" value="0"/>'),
        ),
        trigger(
          'MergeGap',
          byEntity(
            'merging',
            '<RelativeDistanceCondition parameterAttributes="entityRef,value" entityRef="ego" relativeDistanceType="longitudinal" value="20" freespace="true" rule="lessThan"/>',
          ),
        ),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'crossing-path',
    title: 'Straight crossing path, synchronized arrival',
    group: 'Vehicles oncoming or crossing',
    summary:
      "At the library's crossroads (crossroads.xodr), a vehicle from the road to the ego's right drives straight across the ego's path, adapting its speed so that it reaches the conflict point as the ego reaches a set point before it (or the conflict point itself: a collision course), arriving at a set speed.",
    actor: "the crossing vehicle, on the arm right of the ego's",
    actorName: 'crossing',
    groupName: 'CrossingPath',
    road: 'crossroads.xodr',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('crossing', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 150, 10, { road: 1 }), placed('crossing', -1, 150, 8, { road: 3 })],
    stopAt: 7,
    parameters: synchronizedParameters('crossing', 1.75, '', {
      name: 'arrivalSpeed',
      range: '1..30',
      about: 'the crossing vehicle’s speed at the conflict point',
    }),
    keys: {},
    // The conflict point: the crossing lane (-1 of road 102, x 1.75, from y -10) across the ego's lane centre (y -1.75).
    maneuver: synchronizedArrival('CrossingSynchronize', 'CrossingStart', 1.75, { road: 102, lane: -1, s: 8.25 }, 8),
  },
  {
    name: 'turn-across-path',
    title: 'Turn across path at a junction, from the opposite direction',
    group: 'Vehicles oncoming or crossing',
    summary:
      "At the library's crossroads (crossroads.xodr), a vehicle coming towards the ego from the opposite arm turns left across the ego's lane into the arm on the ego's right, adapting its speed so that it reaches the conflict point (its path across the ego's lane) as the ego reaches a set point before it (or the conflict point itself: a collision course), turning at a set speed. The time gap at the conflict point is the ego's distance short of it over the ego's speed, which the main sets.",
    actor: "the turning vehicle, in the ego's opposite lane on the arm ahead of the ego",
    actorName: 'turning',
    groupName: 'TurnAcrossPath',
    road: 'crossroads.xodr',
    entities: [VEHICLE('ego', 'vehicle.lincoln.mkz_2017'), VEHICLE('turning', 'vehicle.audi.tt')],
    init: [placed('ego', -1, 150, 10, { road: 1 }), placed('turning', 1, 40, 10, { road: 2 })],
    stopAt: 9,
    parameters: synchronizedParameters('turning', 1.63, ", a time gap of (1.63 - egoAt) / the ego's speed", {
      name: 'turnSpeed',
      range: '1..15',
      about: 'the turning vehicle’s speed at the conflict point, which it keeps through the rest of the turn',
    }),
    keys: {},
    // The conflict point: the turn's lane (-1 of road 103, on its reference line, an arc of radius 11.75 about (10, -10)
    // from (10, 1.75)) crosses the ego's lane centre (y -1.75) at x 10 - √70 = 1.63, 11.75 · 0.7924 = 9.311 m into the turn.
    maneuver: synchronizedArrival('TurnSynchronize', 'TurnStart', 1.63, { road: 103, lane: -1, s: 9.311 }, 6),
  },
  {
    name: 'arrive-leave-site',
    title: 'Arrive at a site, stay, leave',
    group: 'Incident site',
    summary:
      "A vehicle (police, ambulance, a tow truck) drives up to a site, a vehicle standing ahead in its lane (a breakdown, a crash), brakes evenly to a stand once the gap to it is below the one asked, over a set distance (so it stands at a gap of the first less the second), stays there a set time, then drives off at a set speed (accelerating at 2 m/s²), pulling out sideways by a set offset from its lane's centre to pass the site.",
    actor: 'the arriving vehicle, behind the site in its lane',
    actorName: 'responder',
    groupName: 'ArriveLeaveSite',
    entities: [VEHICLE('site', 'vehicle.tesla.model3'), VEHICLE('responder', 'vehicle.dodge.charger_police')],
    init: [placed('site', -1, 200, 0), placed('responder', -1, 110, 14)],
    stopAt: 16,
    parameters: [
      {
        key: 'RelativeDistanceCondition.value',
        name: 'brakeGap',
        unit: 'm',
        range: '5..200',
        about: 'the gap (bumper to bumper, along the road) to the site when it starts braking',
      },
      {
        key: 'SpeedActionDynamics.value',
        name: 'brakingDistance',
        unit: 'm',
        range: '1..150',
        about:
          'how far it brakes, at an even deceleration, to a stand: it stands at a gap of brakeGap - brakingDistance behind the site (its speed² / (2 brakingDistance) must stay within its maxDeceleration)',
      },
      { key: 'Condition.delay', name: 'stay', unit: 's', range: '0..600', about: 'how long it stands at the site before it leaves' },
      { key: 'AbsoluteTargetSpeed.value', name: 'leaveSpeed', unit: 'm/s', range: '0.5..70', about: 'the speed it drives off at' },
      {
        key: 'AbsoluteTargetLaneOffset.value',
        name: 'passOffset',
        unit: 'm',
        range: '-7..7',
        about:
          "how far it pulls out from its lane's centre line as it leaves, to pass the site: positive to the left, negative to the right, 0 straight on",
      },
      {
        key: 'LaneOffsetActionDynamics.maxLateralAcc',
        name: 'lateralAcceleration',
        unit: 'm/s²',
        range: '0.5..10',
        about: 'the largest lateral acceleration of the pull-out',
      },
      { key: 'RelativeDistanceCondition.entityRef', name: 'site', about: 'the vehicle at the site, standing ahead in its lane' },
      {
        key: 'EntityRef.entityRef',
        name: 'self',
        about: 'the arriving vehicle itself (as in Actors): its gap to the site triggers the braking',
      },
    ],
    keys: {},
    maneuver: [
      event(
        'SiteArrive',
        privateAction(
          'SiteArrive',
          speedAction(
            '<SpeedActionDynamics parameterAttributes="value" dynamicsShape="linear" value="25" dynamicsDimension="distance"/>',
            '<AbsoluteTargetSpeed value="0"/>',
          ),
        ),
        trigger(
          'SiteGap',
          byEntity(
            'responder',
            '<RelativeDistanceCondition parameterAttributes="entityRef,value" entityRef="site" relativeDistanceType="longitudinal" value="35" freespace="true" coordinateSystem="road" rule="lessThan"/>',
          ),
        ),
        'parallel',
      ),
      event(
        'SiteLeave',
        [
          privateAction(
            'SiteLeaveSpeed',
            speedAction(
              '<SpeedActionDynamics dynamicsShape="linear" value="2" dynamicsDimension="rate"/>',
              '<AbsoluteTargetSpeed parameterAttributes="value" value="10"/>',
            ),
          ),
          privateAction('SiteLeavePullOut', laneOffset('<AbsoluteTargetLaneOffset parameterAttributes="value" value="3.5"/>')),
        ].join('\n'),
        afterEvent('SiteStay', 'SiteArrive', 3),
        'parallel',
      ),
    ].join('\n'),
  },
  {
    name: 'rear-end-collision',
    title: 'Rear-end collision',
    group: 'Incident site',
    summary:
      "A vehicle runs into the one ahead of it in its lane: from a set time it drives at a set speed, never brakes for the vehicle ahead, and stops dead where its front meets the other's rear (a crash, without physics). Several in one lane, each into the one ahead, make a pile-up; its time to collision when it sets off is its gap over its speed (less the speed of the vehicle ahead).",
    actor: 'the vehicle that runs into the one ahead, behind it in its lane',
    actorName: 'follower',
    groupName: 'RearEndCollision',
    entities: [VEHICLE('ahead', 'vehicle.tesla.model3'), VEHICLE('follower', 'vehicle.audi.tt')],
    init: [placed('ahead', -1, 200, 0), placed('follower', -1, 150, 0)],
    stopAt: 8,
    parameters: [
      {
        key: 'AbsoluteTargetSpeed.value',
        name: 'speed',
        unit: 'm/s',
        range: '1..40',
        about: 'the speed it drives at, taken at once, and hits the vehicle ahead at',
      },
      { key: 'SimulationTimeCondition.value', name: 'startTime', unit: 's', range: '0..600', about: 'when it sets off at that speed' },
      { key: 'RelativeDistanceCondition.entityRef', name: 'ahead', about: 'the vehicle ahead in its lane that it runs into' },
      { key: 'EntityRef.entityRef', name: 'self', about: 'the vehicle itself (as in Actors): its gap to the one ahead is what hits' },
    ],
    keys: {},
    maneuver: [
      speedFromStart('RearEndDrive', 12, 'RearEndStart', atTime(1, ' parameterAttributes="value"')),
      event(
        'RearEndImpact',
        privateAction(
          'RearEndImpact',
          speedAction('<SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>', '<AbsoluteTargetSpeed value="0"/>'),
        ),
        trigger(
          'RearEndContact',
          byEntity(
            'follower',
            '<RelativeDistanceCondition parameterAttributes="entityRef" entityRef="ahead" relativeDistanceType="longitudinal" value="0.1" freespace="true" coordinateSystem="road" rule="lessThan"/>',
          ),
        ),
        'parallel',
      ),
    ].join('\n'),
  },
];

/** The doc block a library module opens with (read by server/src/library/modules.ts). @param {Module} module */
function docBlock(module) {
  const parameters = module.parameters.map(
    (parameter) =>
      `parameter ${parameter.key} = ${parameter.name}${parameter.unit ? ` [${parameter.unit}]` : ''}${parameter.range ? ` (${parameter.range})` : ''}: ${parameter.about}`,
  );
  return `<!-- library module
name: ${module.name}
title: ${module.title}
group: ${module.group}
maneuverGroup: ${module.groupName}
actor: ${module.actorName}: ${module.actor}
${module.queue ? `queue: ${module.queue}\n` : ''}summary: ${module.summary}
${parameters.join('\n')}
-->`;
}

/** @param {Module} module @param {string} description @param {string} storyGroup @param {string} comment @param {string} roads */
function scenario(module, description, storyGroup, comment, roads) {
  return `<?xml version="1.0" encoding="UTF-8"?>
${comment}
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-11-27T00:00:00" description="${description}" author="modular2simple library"/>
  <ParameterDeclarations/>
  <CatalogLocations/>
  <RoadNetwork>
    <LogicFile filepath="${roads}/${module.road ?? ROAD}"/>
  </RoadNetwork>
  <Entities>
${indent(module.entities.join('\n'), 4)}
  </Entities>
  <Storyboard>
    <Init>
      <Actions>
${indent(module.init.join('\n'), 8)}
      </Actions>
    </Init>
    <Story name="${module.groupName}Story">
      <Act name="${module.groupName}Act">
${indent(storyGroup, 8)}
${indent(trigger('ActStart', atTime(0)), 8)}
      </Act>
    </Story>
    <StopTrigger>
      <ConditionGroup>
        <Condition name="End" delay="0" conditionEdge="none">
          <ByValueCondition>
            <SimulationTimeCondition value="${module.stopAt}" rule="greaterThan"/>
          </ByValueCondition>
        </Condition>
      </ConditionGroup>
    </StopTrigger>
  </Storyboard>
</OpenSCENARIO>
`;
}

/** @param {string} xml @param {string} key */
function defaultOf(xml, key) {
  const parts = key.split('.');
  const attribute = parts[parts.length - 1];
  const element = parts[parts.length - 2];
  const found = [
    ...xml.matchAll(
      new RegExp(`<${element}\\b[^>]*\\bparameterAttributes="[^"]*\\b${attribute}\\b[^"]*"[^>]*\\s${attribute}="([^"]*)"`, 'g'),
    ),
  ];
  if (found.length === 0) throw new Error(`no default for ${key}`);
  // Read by the last element name only: where elements of that name list the attribute with other values, the module's keys give the value.
  if (found.some((other) => other[1] !== found[0][1]))
    throw new Error(`${key}: ${element} elements that list ${attribute} differ in value; give its example value in the module's keys`);
  return found[0][1];
}

/**
 * The group's Actors: its actor, then any others that act alike. In the module the others list entityRef (keys
 * `Actors.EntityRef[2].entityRef`, ...): flattening sets only the first from the main's group (SPEC 4 step 2).
 * @param {Module} module @param {boolean} inModule
 */
const actorRefs = (module, inModule) =>
  [module.actorName, ...(module.otherActors ?? [])]
    .map((actor, index) => `    <EntityRef${inModule && index > 0 ? ' parameterAttributes="entityRef"' : ''} entityRef="${actor}"/>`)
    .join('\n');

/** @param {Module} module */
export function moduleText(module) {
  const group = `<ManeuverGroup name="${module.groupName}" maximumExecutionCount="1">
  <Actors selectTriggeringEntities="false">
${actorRefs(module, true)}
  </Actors>
  <Maneuver name="${module.groupName}Maneuver">
${indent(module.maneuver, 4)}
  </Maneuver>
</ManeuverGroup>`;
  return scenario(module, `Library module: ${module.title}`, group, docBlock(module), 'roads');
}

/** @param {Module} module */
export function exampleText(module) {
  const moduleXml = moduleText(module);
  const references = module.parameters
    .map(
      (parameter) =>
        `      <ParameterReference key="${parameter.key}" value="${module.keys[parameter.key] ?? defaultOf(moduleXml, parameter.key)}"/>`,
    )
    .join('\n');
  const group = `<ManeuverGroup name="${module.groupName}" maximumExecutionCount="1">
  <Actors selectTriggeringEntities="false">
${actorRefs(module, false)}
  </Actors>
  <ScenarioReference scenarioFileName="library:${module.name}">
    <ManeuverGroupReference maneuverGroupName="${module.groupName}">
${references}
    </ManeuverGroupReference>
  </ScenarioReference>
</ManeuverGroup>`;
  return scenario(
    module,
    `Example of the library module ${module.name}`,
    group,
    `<!-- Example main of the library module ${module.name}: ${module.title}. -->`,
    '../roads',
  );
}

export const LIBRARY_FOLDER = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', 'library');

/** Every file this script writes, by its path in the library. @returns {[string, string][]} */
function libraryFiles() {
  return MODULES.flatMap((module) => [
    [`${module.name}.xosc`, moduleText(module)],
    [`examples/${module.name}.xosc`, exampleText(module)],
  ]);
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  // --check: write nothing, list the files that differ from what this script writes (exit 1 if any).
  const check = process.argv.includes('--check');
  const stale = [];
  fs.mkdirSync(path.join(LIBRARY_FOLDER, 'examples'), { recursive: true });
  for (const [name, text] of libraryFiles()) {
    const file = path.join(LIBRARY_FOLDER, name);
    if (!check) fs.writeFileSync(file, text);
    else if (!fs.existsSync(file) || fs.readFileSync(file, 'utf8') !== text) stale.push(name);
  }
  for (const name of stale) console.log(`library/${name} differs from what scripts/library-build.mjs writes: run it`);
  process.exitCode = stale.length > 0 ? 1 : 0;
}
