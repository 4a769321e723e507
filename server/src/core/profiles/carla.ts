import { SimulatorProfile } from './facts';

// Facts read from carla-simulator/scenario_runner at revision 94ff3b8af752bad2b9d464ad5105868906aa34c0:
// Docs/openscenario_support.md (support tables) and the code that runs a scenario
// (srunner/tools/openscenario_parser.py, srunner/scenarios/open_scenario.py,
// srunner/scenarioconfigs/openscenario_configuration.py). Where the code runs more than the table
// says (EnvironmentAction and SynchronizeAction in a Story; LaneOffsetAction and routing actions in
// Init), the code is taken as the fact, so that working scenarios get no warning.
const DOC = 'Docs/openscenario_support.md';
const PARSER = 'srunner/tools/openscenario_parser.py';
const RUNNER = 'srunner/scenarios/open_scenario.py';
const CONFIGURATION = 'srunner/scenarioconfigs/openscenario_configuration.py';

export const CARLA_PROFILE: SimulatorProfile = {
  simulator: 'carla',
  name: 'CARLA ScenarioRunner',
  repository: 'carla-simulator/scenario_runner',
  revision: '94ff3b8af752bad2b9d464ad5105868906aa34c0',
  versions: { revMajor: '1', revMinor: '0', source: CONFIGURATION },
  elements: [
    {
      element: 'TrafficAction',
      parent: 'GlobalAction',
      support: 'unsupported',
      source: PARSER,
      note: 'global traffic actions raise "Global actions are not yet supported"',
    },
    { element: 'TrafficSignalStateAction', support: 'unsupported', places: { init: false, story: true }, source: DOC },
    { element: 'TrafficSignalControllerAction', support: 'unsupported', places: { init: false, story: true }, source: DOC },
    { element: 'CustomCommandAction', support: 'unsupported', places: { init: false, story: true }, source: DOC },
    { element: 'ActivateControllerAction', support: 'unsupported', places: { init: false, story: true }, source: DOC },
    { element: 'LaneChangeAction', support: 'unsupported', places: { init: false, story: true }, source: DOC },
    { element: 'LongitudinalDistanceAction', support: 'unsupported', places: { init: false, story: true }, source: DOC },
    { element: 'SynchronizeAction', support: 'unsupported', places: { init: false, story: true }, source: RUNNER },
    { element: 'VisibilityAction', support: 'unsupported', source: DOC, note: 'it raises "Visibility actions are not yet supported"' },
    {
      element: 'AbsoluteTargetLane',
      parent: 'LaneChangeTarget',
      support: 'unsupported',
      source: DOC,
      note: 'lane changes are relative to the actor itself (RelativeTargetLane)',
    },
    { element: 'Clothoid', parent: 'Shape', support: 'unsupported', source: PARSER, note: 'trajectories are followed as polylines only' },
    { element: 'Nurbs', parent: 'Shape', support: 'unsupported', source: PARSER, note: 'trajectories are followed as polylines only' },
    { element: 'RoutePosition', support: 'unsupported', source: DOC, note: 'it raises "Route positions are not yet supported"' },
    { element: 'UserDefinedValueCondition', support: 'unsupported', source: DOC },
    { element: 'EntitySelection', support: 'ignored', source: DOC },
    { element: 'ObjectController', support: 'ignored', source: DOC },
  ],
  attributes: [
    { element: 'LongitudinalDistanceAction', attribute: 'timeGap', supportedValues: [], source: DOC, note: 'only distance is implemented' },
    {
      element: 'DistanceCondition',
      attribute: 'freespace',
      supportedValues: ['false'],
      source: DOC,
      note: 'the distance is measured between reference points',
    },
    {
      element: 'StoryboardElementStateCondition',
      attribute: 'state',
      supportedValues: ['startTransition', 'stopTransition', 'endTransition', 'completeState'],
      source: PARSER,
      note: 'only start, stop and end transitions and completeState are implemented',
    },
    {
      element: '*',
      parent: 'OverrideControllerValueAction',
      attribute: 'active',
      supportedValues: ['false'],
      source: PARSER,
      note: 'every override must be inactive',
    },
    {
      element: 'LaneChangeActionDynamics',
      attribute: 'dynamicsShape',
      supportedValues: ['linear'],
      source: DOC,
      note: 'every lane change is linear',
    },
  ],
  catalogFileNames: {
    types: ['Vehicle', 'Controller', 'Pedestrian', 'MiscObject', 'Environment', 'Maneuver', 'Trajectory', 'Route'],
    source: CONFIGURATION,
  },
  expressionsNotEvaluated: { source: PARSER },
};
