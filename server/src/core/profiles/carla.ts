import { SR_ATOMICS, SR_CONFIGURATION, SR_PARSER, SR_REVISION, SR_SCENARIO, SR_TRIGGER_CONDITIONS } from './scenarioRunner';
import { CarlaRelease } from './simulators';
import { SimulatorFact, SimulatorProfile } from './facts';

/*
 * What CARLA's ScenarioRunner does with OpenSCENARIO, read from carla-simulator/scenario_runner at
 * 94ff3b8a (the 0.9.16 release) and checked by loading files through its own loader offline
 * (../shared/carla/FACTS.md, ../shared/carla/check.py). Every fact names the file and line that show it;
 * where the code and Docs/openscenario_support.md disagree the code is the fact. What ScenarioRunner refuses
 * to load or to build is an error (SPEC 12: the scenario means nothing there); what it runs otherwise
 * than written is a warning.
 */
const PARSER = SR_PARSER;
const RUNNER = SR_SCENARIO;
const CONFIGURATION = SR_CONFIGURATION;
const ATOMICS = SR_ATOMICS;
const INIT_NOTE =
  'the Init runs Speed, Teleport, Controller, LaneOffset, LateralDistance, routing and trajectory actions, the first EnvironmentAction, ParameterActions and entity actions only';

/** Where the Init's GlobalActions are read: ParameterActions (_initialize_parameters) and EntityActions (_initialize_actors) only. */
const GLOBAL_INIT_SOURCE = `${RUNNER}:201-215, 598-620`;

export const CARLA_PROFILE: SimulatorProfile = {
  simulator: 'carla',
  name: 'CARLA ScenarioRunner',
  repository: 'carla-simulator/scenario_runner',
  revision: SR_REVISION,
  versions: { revMajor: '1', revMinor: '0', source: `${CONFIGURATION}:105`, severity: 'error', exportWrites: true },
  elements: [
    // Refused while the scenario is built: the file fails to load in ScenarioRunner.
    {
      element: 'TrafficAction',
      parent: 'GlobalAction',
      support: 'unsupported',
      severity: 'error',
      in: 'story',
      source: `${PARSER}:1296`,
      note: 'it raises "Global actions are not yet supported"',
    },
    {
      element: 'VisibilityAction',
      support: 'unsupported',
      severity: 'error',
      in: 'story',
      source: `${PARSER}:1454`,
      note: 'it raises "Visibility actions are not yet supported"',
    },
    {
      element: 'AbsoluteTargetLane',
      parent: 'LaneChangeTarget',
      support: 'unsupported',
      severity: 'error',
      source: `${PARSER}:1380-1383`,
      note: 'a lane change reads only RelativeTargetLane, and crashes without one',
    },
    {
      element: 'Clothoid',
      parent: 'Shape',
      support: 'unsupported',
      severity: 'error',
      source: `${PARSER}:622-623`,
      note: 'trajectories are polylines only',
    },
    {
      element: 'Nurbs',
      parent: 'Shape',
      support: 'unsupported',
      severity: 'error',
      source: `${PARSER}:624-625`,
      note: 'trajectories are polylines only',
    },
    {
      element: 'RoutePosition',
      support: 'unsupported',
      severity: 'error',
      source: `${PARSER}:859-860`,
      note: 'it raises "Route positions are not yet supported"',
    },
    {
      element: 'UserDefinedValueCondition',
      support: 'unsupported',
      severity: 'error',
      source: `${PARSER}:1147-1148`,
      note: 'it raises "ByValue UserDefinedValue conditions are not yet supported"',
    },
    // The 0.9.16 regression (commit ab5996d7, PR #1149): ChangeActorWaypoints is built without times.
    {
      element: 'AssignRouteAction',
      support: 'unsupported',
      severity: 'error',
      releases: ['0.9.16'],
      // Export for CARLA writes it as a FollowTrajectoryAction along its lanes where it knows the start and speed, in a story too (export/routeTrajectories.ts).
      exportWritesIn: ['init', 'story'],
      source: `${ATOMICS}:773 (${PARSER}:1508, ${RUNNER}:334)`,
      note: 'building ChangeActorWaypoints without times raises "object of type \'NoneType\' has no len()", a regression of commit ab5996d7 (0.9.15 runs it)',
    },
    {
      element: 'AcquirePositionAction',
      support: 'unsupported',
      severity: 'error',
      releases: ['0.9.16'],
      // Export for CARLA writes it as a FollowTrajectoryAction along its lanes where it knows the start and speed, in a story too (export/routeTrajectories.ts).
      exportWritesIn: ['init', 'story'],
      source: `${ATOMICS}:773 (${PARSER}:1518, ${RUNNER}:347)`,
      note: 'building ChangeActorWaypoints without times raises "object of type \'NoneType\' has no len()", a regression of commit ab5996d7 (0.9.15 runs it)',
    },
    // Run otherwise than written: the Init runs only some actions (FACTS.md) and passes over the rest.
    { element: 'TrafficAction', support: 'ignored', in: 'init', source: GLOBAL_INIT_SOURCE, note: INIT_NOTE },
    { element: 'VisibilityAction', support: 'ignored', in: 'init', source: `${RUNNER}:263-348`, note: INIT_NOTE },
    { element: 'TrafficSignalStateAction', support: 'ignored', in: 'init', source: GLOBAL_INIT_SOURCE, note: INIT_NOTE },
    { element: 'TrafficSignalControllerAction', support: 'ignored', in: 'init', source: GLOBAL_INIT_SOURCE, note: INIT_NOTE },
    { element: 'CustomCommandAction', support: 'ignored', in: 'init', source: GLOBAL_INIT_SOURCE, note: INIT_NOTE },
    { element: 'ActivateControllerAction', support: 'ignored', in: 'init', source: `${RUNNER}:263-348`, note: INIT_NOTE },
    { element: 'LaneChangeAction', support: 'ignored', in: 'init', source: `${RUNNER}:263-348`, note: INIT_NOTE },
    { element: 'LongitudinalDistanceAction', support: 'ignored', in: 'init', source: `${RUNNER}:263-348`, note: INIT_NOTE },
    { element: 'SynchronizeAction', support: 'ignored', in: 'init', source: `${RUNNER}:263-348`, note: INIT_NOTE },
    { element: 'EntitySelection', support: 'ignored', source: `${CONFIGURATION}:236-260` },
    { element: 'ObjectController', support: 'ignored', source: `${CONFIGURATION}:236-260` },
  ],
  attributes: [
    {
      element: 'LongitudinalDistanceAction',
      attribute: 'timeGap',
      supportedValues: [],
      severity: 'error',
      source: `${PARSER}:1362-1363`,
      note: 'it raises "LongitudinalDistanceAction: timeGap is not implemented"',
    },
    {
      element: 'StoryboardElementStateCondition',
      attribute: 'state',
      supportedValues: ['startTransition', 'stopTransition', 'endTransition', 'completeState'],
      severity: 'error',
      source: `${PARSER}:1135-1146`,
      note: 'it raises "Only start, stop, endTransitions and completeState are currently supported"',
    },
    {
      element: '*',
      parent: 'OverrideControllerValueAction',
      attribute: 'active',
      supportedValues: ['false'],
      severity: 'error',
      source: `${PARSER}:545-548`,
      note: 'an active override raises "Controller override actions are not yet supported"',
    },
    {
      element: 'Precipitation',
      attribute: 'precipitationType',
      unsupportedValues: ['snow'],
      severity: 'error',
      source: `${PARSER}:503-504`,
      note: 'it raises "CARLA does not support snow precipitation"',
    },
    {
      element: 'DistanceCondition',
      attribute: 'freespace',
      supportedValues: ['false'],
      source: `${PARSER}:1047, 1073-1075`,
      note: 'the freespace it reads is never passed on: the distance is measured between reference points',
    },
    {
      element: 'LaneChangeActionDynamics',
      attribute: 'dynamicsShape',
      supportedValues: ['linear'],
      source: `${PARSER}:1380-1390`,
      note: 'every lane change is linear',
    },
    {
      element: 'LaneChangeActionDynamics',
      attribute: 'dynamicsDimension',
      supportedValues: ['distance'],
      source: `${PARSER}:1386-1399`,
      note: 'a lane change by time or rate is planned over an infinite distance (distance_lane_change=inf): the value is read as a duration that nothing uses',
      // laneChanges.ts: the distance the actor covers while it moves across (a rate needs the .xodr road's lane widths).
      exportWrites: ['time', 'rate'],
    },
    {
      element: 'Condition',
      attribute: 'conditionEdge',
      unsupportedValues: ['falling', 'risingOrFalling'],
      source: `${PARSER}:865-890`,
      note: 'every condition is latched the first time it holds',
    },
  ],
  catalogFileNames: {
    types: ['Vehicle', 'Controller', 'Pedestrian', 'MiscObject', 'Environment', 'Maneuver', 'Trajectory', 'Route'],
    source: `${CONFIGURATION}:108-144`,
  },
};

/** A fact of ScenarioRunner that a check of its own applies (core/semantics/checks/carla.ts): what it does, where the code shows it. */
export interface CarlaFact extends SimulatorFact {
  /** The releases the fact holds for; every release when absent. */
  releases?: readonly CarlaRelease[];
}

/** The facts the CARLA checks apply, by name. */
export const CARLA_FACTS = {
  expressionNumber: {
    does: 'does not evaluate ${...}: a number or choice written so fails its 1.0 schema, and its parser raises "could not convert" (it reads only literals and $names)',
    source: `${PARSER}:129-148`,
    severity: 'error',
  },
  expressionText: {
    does: 'does not evaluate ${...}: this text attribute is kept as the characters written',
    source: `${PARSER}:157-159`,
    severity: 'warning',
  },
  parameterNotResolved: {
    does: 'reads this attribute as written, without resolving $parameters (only values it wraps in ParameterRef are resolved)',
    source: `${PARSER}:879 (delay), ${CONFIGURATION}:164-165 (LogicFile), ${PARSER}:363-366 (catalogName)`,
    severity: 'error',
  },
  noRoadNetwork: {
    does: 'takes the CARLA town from RoadNetwork/LogicFile; without one it fails ("CARLA level not defined")',
    source: `${CONFIGURATION}:164-181, 417-418`,
    severity: 'error',
  },
  roadFileMissing: {
    does: 'loads an .xodr LogicFile from the scenario\'s folder and fails when it does not exist ("The provided RoadNetwork ... does not exist")',
    source: `${CONFIGURATION}:167-171`,
    severity: 'error',
  },
  unknownTown: {
    does: 'loads a LogicFile that is not an .xodr as a CARLA map, and fails for a name that is not one',
    source: `${CONFIGURATION}:208-209`,
    severity: 'error',
  },
  catalogNotLoaded: {
    does: 'reads each catalog type only from <Directory>/<Type>Catalog.xosc beside the scenario, keyed by the catalog name, and fails on a reference to a catalog or entry it did not read (KeyError)',
    source: `${CONFIGURATION}:108-144, ${PARSER}:363-366`,
    severity: 'error',
  },
  catalogNameShared: {
    does: 'keeps catalogs in one table by name, across types: the catalog read later replaces the one of the same name',
    source: `${CONFIGURATION}:112, 141-144`,
    severity: 'error',
  },
  catalogSchema: {
    does: 'validates every catalog file it reads against its bundled OpenSCENARIO 1.0 schema and fails on the first error',
    source: `${CONFIGURATION}:75-83, 138-139`,
    severity: 'error',
  },
  catalogEntityRef: {
    does: 'replaces only the $parameters an entry declares or its reference assigns; an entityRef left as a $name names no actor ("Cannot find actor ... for condition")',
    source: `${PARSER}:383-421, 914`,
    severity: 'error',
  },
  controllerActionParts: {
    does: "reads a ControllerAction's AssignControllerAction and then iterates its OverrideControllerValueAction; without either it crashes (StopIteration, \"'NoneType' object is not iterable\")",
    source: `${PARSER}:528, 545-546`,
    severity: 'error',
  },
  freespaceRequired: {
    does: 'reads these flags with strtobool, which crashes when one is absent (the 1.0 schema requires them)',
    source: `${PARSER}:948, 974, 1047, 1049`,
    severity: 'error',
  },
  eventPriority: {
    does: 'ignores Event priority: the events of a maneuver all run, each when its start trigger holds',
    source: `${RUNNER}:425-427`,
    severity: 'warning',
  },
  eventRepetition: {
    does: "ignores an Event's maximumExecutionCount: the event runs once",
    source: `${RUNNER}:425-427`,
    severity: 'warning',
  },
  triggeringEntitiesRule: {
    does: 'ignores triggeringEntitiesRule: the condition is evaluated for the last entity listed only',
    source: `${PARSER}:888-890`,
    severity: 'warning',
  },
  actStopTrigger: {
    does: "OR-s the conditions of one group of an Act's StopTrigger (the standard AND-s them)",
    source: `${RUNNER}:492-496`,
    severity: 'warning',
  },
  storyboardStopTrigger: {
    does: "ignores the Storyboard's StopTrigger except ParameterConditions named criteria_*, which become test criteria",
    source: `${RUNNER}:572-590`,
    severity: 'warning',
  },
  blueprint: {
    does: 'spawns the CARLA blueprint this name gives; a name that is not one (such as an esmini catalog name) falls back to a default of the category',
    source: `${CONFIGURATION}:299, 321`,
    severity: 'warning',
  },
  speedRateAsDuration: {
    does: "reads a SpeedAction's rate as a duration in seconds: it hands the target speed to the actor's controller at once, which reaches it at its own pace, and ends the action when that many seconds have passed, at its first tick for a negative rate",
    source: `${PARSER}:1314-1320, ${ATOMICS}:516, 560`,
    severity: 'warning',
  },
  speedShapeIgnored: {
    does: "does not read a SpeedAction's dynamicsShape: it hands the target speed to the actor's controller at once, which reaches it at its own pace",
    source: `${PARSER}:1308-1320, ${ATOMICS}:516`,
    severity: 'warning',
  },
  laneOffsetShapeIgnored: {
    does: 'does not read a LaneOffsetAction\'s dynamics ("Parsing of the different Dynamic shapes is missing"): the offset is reached as the actor\'s controller drives, whatever the shape',
    source: `${PARSER}:1402-1404`,
    severity: 'warning',
  },
  laneOffsetMaxLateralAccIgnored: {
    does: 'does not read a LaneOffsetAction\'s dynamics ("Parsing of the different Dynamic shapes is missing"), maxLateralAcc included: the offset is reached as the actor\'s controller drives, whatever the acceleration',
    source: `${PARSER}:1402-1404, ${RUNNER}:279`,
    severity: 'warning',
  },
  initActorSequence: {
    does: "builds each actor's Init as one sequence: its controller, then one routing or lateral atomic (of a FollowTrajectory, AssignRoute, AcquirePosition, LaneOffset or LateralDistance action, the last one written; the others are not built), then its start speed (ChangeActorTargetSpeed), set only once that atomic has ended",
    source: `${RUNNER}:255-359`,
    severity: 'warning',
  },
  trajectoryTimesSetSpeed: {
    does: "drives a vehicle (NpcVehicleControl, its default controller) to each trajectory vertex at the speed its time asks, with or without timing; a time already past asks the vertex's distance in a thousandth of a second, full speed",
    source: `srunner/scenariomanager/actorcontrols/npc_vehicle_control.py:103-113, ${PARSER}:1509-1513`,
    severity: 'warning',
  },
  trajectoryEndRaises: {
    does: "raises IndexError (list index out of range) in a vehicle's controller at the tick after the vehicle reaches its trajectory's last vertex, which ends the run: NpcVehicleControl keeps the vertex times once ChangeActorWaypoints has ended, and CARLA's LocalPlanner has emptied its plan by then (its done(), which ends that atomic, is an empty plan; set_global_plan stops it making more), so it reads the time at the index one past the last",
    source: `srunner/scenariomanager/actorcontrols/npc_vehicle_control.py:103-111, 125-127, srunner/scenariomanager/actorcontrols/basic_control.py:71-82, ${ATOMICS}:882-886, scenario_runner.py:445, 458-461; CARLA PythonAPI agents/navigation/local_planner.py set_global_plan, run_step, done, get_plan`,
    severity: 'warning',
  },
  walkerWalksAtSetSpeed: {
    does: 'walks a pedestrian (PedestrianControl, its default controller) straight towards each trajectory vertex in turn at the speed its speed actions set, reading no vertex times, and heads for the next once within 1 m of one; with no vertex left, or none given, it walks straight ahead the way it faces',
    source:
      'srunner/scenariomanager/actorcontrols/pedestrian_control.py:41-77, srunner/scenariomanager/actorcontrols/actor_control.py:69-70',
    severity: 'warning',
  },
  walkerSpeedChangeOnTrajectory: {
    does: "keeps a pedestrian on its trajectory when a SpeedAction changes its speed: the SpeedAction only sets its controller's target speed (a longitudinal command, ChangeActorTargetSpeed), which ends no running ChangeActorWaypoints (that ends at its last vertex or at another waypoint command), and the walker controller walks towards its next vertex at the target speed it holds at each tick",
    source: `${ATOMICS}:516, 542, 857, 882-886 (ChangeActorTargetSpeed, ChangeActorWaypoints), srunner/scenariomanager/actorcontrols/actor_control.py:97-119, srunner/scenariomanager/actorcontrols/pedestrian_control.py:57-70`,
    severity: 'warning',
  },
  vehicleSpeedChangeOnTrajectory: {
    does: "keeps a vehicle on its trajectory when a SpeedAction changes its speed, and drives it by the vertex times all the same: the SpeedAction only sets its controller's target speed (ChangeActorTargetSpeed), which ends no running ChangeActorWaypoints, and NpcVehicleControl replaces that target at every tick by the speed the next vertex's time asks; once an Init trajectory ends, the actor's Init sequence sets its Init speed again",
    source: `${ATOMICS}:516, 542, 857, 882-886 (ChangeActorTargetSpeed, ChangeActorWaypoints), srunner/scenariomanager/actorcontrols/npc_vehicle_control.py:103-113, ${RUNNER}:356-357`,
    severity: 'warning',
  },
  conditionsCountFromTheirStart: {
    does: "counts a SimulationTimeCondition's time and a TraveledDistanceCondition's distance from when the condition is first ticked (its Act has started), not from the run's start",
    source: `srunner/scenariomanager/timer.py:108-126 (SimulationTimeCondition.initialise, update), ${SR_TRIGGER_CONDITIONS}:1211-1228 (DriveDistance.initialise, update), ${PARSER}:1029-1032, 1124-1128`,
    severity: 'warning',
  },
  longitudinalGapBehindOnly: {
    does: "keeps a LongitudinalDistanceAction's gap only while the reference is ahead of the actor (KeepLongitudinalGap: is_within_distance of 0 to 90 degrees); an actor ahead of its reference is driven at its maximum speed instead",
    source: `${ATOMICS}:4576-4592`,
    severity: 'warning',
  },
  negativeStartSpeed: {
    does: 'raises AttributeError "Speed value of actor ... must be positive" while it loads a scenario whose Init gives an actor a negative AbsoluteTargetSpeed (a start backwards)',
    source: `${CONFIGURATION}:396-406 (_get_actor_speed)`,
    severity: 'error',
  },
  parameterComparedAsText: {
    does: 'compares a parameter that no ParameterAction sets as its declared text against a number at every tick: lessThan and greaterThan raise TypeError, a value that is no number (true, false, text) raises ValueError, and the scenario stops there',
    source: `${CONFIGURATION}:234, ${PARSER}:143-147, 189-214, ${SR_TRIGGER_CONDITIONS}:1459-1477`,
    severity: 'error',
  },
  parameterNeverEqual: {
    does: 'compares a parameter that no ParameterAction sets as its declared text against a number at every tick: equalTo never holds',
    source: `${CONFIGURATION}:234, ${PARSER}:189-190, ${SR_TRIGGER_CONDITIONS}:1459-1477`,
    severity: 'warning',
  },
  parameterSetAfterCondition: {
    does: "holds a parameter that only the stories' ParameterActions set as its declared text until one of them runs, and a lessThan or greaterThan ParameterCondition ticked before that raises TypeError; it ticks the stories in document order (an Act's StartTrigger before its maneuvers, an Event's StartTrigger before its actions), so none of them can run before this condition's first tick, and the scenario stops there",
    source: `${CONFIGURATION}:234, ${PARSER}:189-214, ${SR_TRIGGER_CONDITIONS}:1459-1477, ${RUNNER}:369-385, 425-454, 482-503`,
    severity: 'error',
  },
  parameterSetInStoryOrder: {
    does: "holds a parameter that only the stories' ParameterActions set as its declared text until one of them runs, and a lessThan or greaterThan ParameterCondition ticked before that raises TypeError: whether one runs first depends on when its event starts and on the order it ticks the stories in (document order; an Act's StartTrigger before its maneuvers and its StopTrigger after them, an Event's StartTrigger before its actions)",
    source: `${CONFIGURATION}:234, ${PARSER}:189-214, ${SR_TRIGGER_CONDITIONS}:1459-1477, ${RUNNER}:369-385, 425-454, 482-503`,
    severity: 'warning',
  },
  parameterNotEqualAsDeclared: {
    does: "holds a parameter that only the stories' ParameterActions set as its declared text until one of them runs, and equalTo a number does not hold on that text: a condition that holds on the declared value waits for one of them instead",
    source: `${CONFIGURATION}:234, ${PARSER}:189-190, ${SR_TRIGGER_CONDITIONS}:1459-1477`,
    severity: 'warning',
  },
  parameterValueNotNumber: {
    does: 'converts the value a ParameterCondition compares with to a number at every tick, and raises ValueError at the first tick where it is no number (true, false, text), whatever a ParameterAction set the parameter to',
    source: `${PARSER}:1102, 143-147, 189-214, ${SR_TRIGGER_CONDITIONS}:1472-1477`,
    severity: 'error',
  },
  laneOffsetSide: {
    does: "moves a LanePosition by its offset to the right of the heading CARLA's waypoint has, turned by the Orientation's h (whatever its type), and that heading runs along the road on a right lane (negative id) and against it on a left lane, where OpenSCENARIO (and esmini) measure the offset along t, to the left of the road's reference line",
    source: `${PARSER}:827-857 (LanePosition), LibCarla road/Lane.cpp Lane::ComputeTransform (yaw + 180 for a positive lane id)`,
    severity: 'warning',
  },
  noEgo: {
    does: 'runs the ScenarioObjects whose Property type is "ego_vehicle" as the ego; this scenario marks none',
    source: `${CONFIGURATION}:301-313, 420-421`,
    severity: 'warning',
  },
} as const satisfies Record<string, CarlaFact>;

export type CarlaFactName = keyof typeof CARLA_FACTS;
