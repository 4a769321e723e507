import { SimulatorFact, SimulatorProfile } from './facts';

// Facts read from esmini/esmini at revision 77028d83e6d402de52f7187e5384d1b1c02b7d1f: the rows marked
// "No" in osc_coverage.txt, kept only where release_notes.md does not announce later support and the
// scenario reader (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp) does
// not implement them either (it does implement VariableCondition, TrafficSignalCondition and
// TrafficSignalStateAction, which osc_coverage.txt still lists as missing).
/** esmini's SMALL_NUMBER (EnvironmentSimulator/Modules/CommonMini/CommonMini.hpp:52, its only definition): its tolerance when it compares numbers. */
export const ESMINI_SMALL_NUMBER = 1e-6;

const COVERAGE = 'osc_coverage.txt';
const READER = 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp';
// How esmini computes values, read in the same revision (release 3.6.0): every parameter value is kept
// as text, `${...}` is the text with each `$name` replaced by that text, evaluated by zserge/expr.
const PARAMETERS = 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/Parameters.cpp';
const SIMPLE_EXPR = 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/simple_expr.c';
const EXPR = 'externals/expr/expr.h';
const COMMON = 'EnvironmentSimulator/Modules/CommonMini/CommonMini.cpp';
const OSC_CONDITION = 'EnvironmentSimulator/Modules/ScenarioEngine/OSCTypeDefs/OSCCondition.cpp';
const STORYBOARD_ELEMENT = 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/StoryboardElement.cpp';
const ENGINE = 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioEngine.cpp';

export const ESMINI_PROFILE: SimulatorProfile = {
  simulator: 'esmini',
  name: 'esmini',
  repository: 'esmini/esmini',
  revision: '77028d83e6d402de52f7187e5384d1b1c02b7d1f',
  oldestRevMajor: {
    revMajor: 1,
    source: 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioEngine.cpp:454-459',
    refusal: 'OpenSCENARIO v{stated} not supported. Please migrate scenario to v1.0 or higher and try again.',
  },
  elements: [
    {
      element: 'ModifyAction',
      parent: 'ParameterAction',
      support: 'unsupported',
      source: COVERAGE,
      note: 'only SetAction is implemented for parameters; a VariableAction can modify',
    },
    { element: 'TrafficSourceAction', support: 'unsupported', source: COVERAGE },
    { element: 'TrafficSinkAction', support: 'unsupported', source: COVERAGE },
    { element: 'TrafficStopAction', support: 'unsupported', source: COVERAGE },
    {
      element: 'TrafficSignalControllerAction',
      support: 'unsupported',
      source: READER,
      note: 'it logs "TrafficSignalAction ... not supported yet"',
    },
    { element: 'AnimationAction', support: 'unsupported', source: COVERAGE },
    {
      element: 'UserDefinedLight',
      parent: 'LightType',
      support: 'unsupported',
      source: READER,
      note: 'only vehicle lights are implemented',
    },
    { element: 'SensorReferenceSet', support: 'ignored', source: COVERAGE },
    {
      element: 'RelativeAngleCondition',
      support: 'unsupported',
      severity: 'error',
      source: `${READER}:4615-5051`,
      note: 'it reads the entity conditions up to AngleCondition and refuses the scenario on this one ("Entity condition RelativeAngleCondition not supported")',
    },
    {
      element: 'GeoPosition',
      support: 'unsupported',
      severity: 'error',
      source: `${READER}:1854-2259`,
      note: 'its position reader has no GeoPosition and refuses the scenario ("Failed parse position in node Position")',
    },
    {
      element: 'ExternalObjectReference',
      support: 'unsupported',
      source: `${COVERAGE}, ${READER}:1656-1660`,
      note: 'it logs "ExternalObjectReference not supported yet" and reads no ScenarioObject after it',
    },
    { element: 'EntitySelection', support: 'unsupported', source: COVERAGE },
    { element: 'TimeOfDayCondition', support: 'unsupported', source: COVERAGE, note: 'the condition is ignored' },
    { element: 'UserDefinedValueCondition', support: 'unsupported', source: COVERAGE, note: 'the condition is ignored' },
    { element: 'TrafficSignalControllerCondition', support: 'unsupported', source: COVERAGE, note: 'the condition is ignored' },
    {
      element: 'Stochastic',
      parent: 'ParameterValueDistribution',
      support: 'unsupported',
      source: COVERAGE,
      note: 'only deterministic distributions are implemented',
    },
    { element: 'UsedArea', support: 'ignored', source: COVERAGE },
    { element: 'DomeImage', support: 'ignored', source: COVERAGE },
    { element: 'TrafficSignals', parent: 'RoadNetwork', support: 'ignored', source: COVERAGE },
  ],
  attributes: [
    {
      element: 'LateralDistanceAction',
      attribute: 'displacement',
      unsupportedValues: ['any'],
      severity: 'error',
      source: `${READER}:3130-3148`,
      note: 'it reads only leftToReferencedEntity and rightToReferencedEntity and refuses the scenario on any other value written ("Unsupported displacement type: any"); without the attribute it takes \'any\'',
    },
    {
      element: 'TrafficSwarmAction',
      attribute: 'velocity',
      whenAbsent: true,
      severity: 'error',
      source: `${READER}:2466-2467`,
      note: 'it reads velocity with std::stod, which stops it when the attribute is absent ("Exception: stod"); the standard makes it optional (deprecated from 1.2 on)',
    },
    { element: 'Route', attribute: 'closed', supportedValues: ['false'], source: COVERAGE, note: 'closed routes are not implemented' },
    {
      element: '*',
      attribute: 'coordinateSystem',
      unsupportedValues: ['lane'],
      // An AngleCondition measures against the lane's driving direction (OSCCondition.cpp TrigByAngle); a Euclidean distance has no coordinate system.
      notOn: ['AngleCondition'],
      unlessAttribute: { attribute: 'relativeDistanceType', values: ['euclidianDistance', 'cartesianDistance'] },
      source: `${COVERAGE}, EnvironmentSimulator/Modules/RoadManager/RoadManager.cpp:11837-11843, 11932-11938`,
      note: 'it falls back to road coordinates for lateral and longitudinal distances ("Lane coordinateSystem not supported yet")',
    },
  ],
  valueRules: {
    substitution: {
      does: "replaces each $name inside ${...} by the parameter's value as text before evaluating",
      source: `${PARAMETERS}:381-398`,
    },
    keywords: {
      does: "rewrites 'not ', 'and ', 'or ', 'true ', 'false ' (with the blank) to !, &&, ||, 1, 0 and leaves them as words otherwise",
      source: `${PARAMETERS}:441-447`,
    },
    numbers: { does: 'reads a number as digits and dots only: an exponent (1E3) is a word', source: `${EXPR}:497-505` },
    textGluing: {
      does: "reads an expression with an unknown word as text and glues it, dropping each run of blanks that holds a '+'",
      source: `${EXPR}:340-347, 910-935`,
    },
    remainder: { does: 'computes % as C remainder(), to the nearest multiple: 7 % 4 is -1', source: `${EXPR}:378-380` },
    divisionByZero: { does: 'divides by zero to inf (and 0/0 or x % 0 to nan, which stops it)', source: `${EXPR}:375-377` },
    round: { does: 'rounds with rint(), half to even: round(2.5) is 2', source: `${SIMPLE_EXPR}:19-25` },
    sign: { does: 'gives sign(0) = 1', source: `${SIMPLE_EXPR}:113-119` },
    comparisons: { does: 'evaluates comparisons and booleans as the numbers 1 and 0', source: `${EXPR}:393-439` },
    resultText: {
      does: 'writes a number result with six decimals (std::to_string), so a value used later is rounded to 1e-6',
      source: `${PARAMETERS}:455-459`,
    },
    declarationName: {
      does: 'finds a parameter declared as name="$X" under $X (it compares with and without the \'$\')',
      source: `${PARAMETERS}:90-100`,
    },
    intConversion: {
      does: 'reads an int with atoi(): the fraction is cut off and a value outside the int range wraps',
      source: `${PARAMETERS}:535-539, ${COMMON}:1031-1034`,
    },
    booleanConversion: { does: "reads a boolean as true only when its text is exactly 'true'", source: `${PARAMETERS}:545-554` },
    doubleConversion: {
      does: 'reads a double with atof(): the longest prefix that is a number, 0 when none',
      source: `${PARAMETERS}:540-544, ${COMMON}:1036-1039`,
    },
    declarationText: {
      does: "puts a parameter's text as written where $name is used (getParameter returns the declaration's value attribute)",
      source: `${PARAMETERS}:73-88`,
    },
    redeclaration: {
      does: 'uses the last of two declarations of one name: it puts each declaration before the earlier ones and looks a name up from the front ("Parameter X redefined. Previous value A will be shadowed by B")',
      source: `${PARAMETERS}:566-582, 73-88`,
    },
    failure: { does: 'stops the scenario with "Failed to evaluate the expression"', source: `${PARAMETERS}:449-453` },
  },
};

/** What esmini does beyond one element or attribute at a time, read in the same revision. */
export const ESMINI_FACTS = {
  triggeringActors: {
    does: 'takes a ManeuverGroup\'s actors only from the EntityRefs of its Actors, never from selectTriggeringEntities, and refuses to load a private action with none ("PrivateAction ... missing actor(s). SelectTriggeringEntities feature not supported yet")',
    source: `${READER}:5424-5444, 5304-5310`,
    severity: 'error',
  },
  entitiesAfterExternal: {
    does: 'stops reading the Entities at an ExternalObjectReference (parseEntities returns there), so a ScenarioObject after it does not exist for esmini, which refuses a reference to it ("Failed to find object")',
    source: `${READER}:1656-1660, 270-281`,
    severity: 'error',
  },
  routeOrientationOrder: {
    does: "applies a RoutePosition's Orientation only to an InRoutePosition it reads after it (it reads the children in the order written; the standard lets them stand in any order), so an Orientation written after the InRoutePosition is dropped (the entity then faces along the route; in a lane of positive id, against it)",
    source: `${READER}:2102-2212`,
    severity: 'warning',
  },
  edgeAtFirstEvaluation: {
    does: "checks a condition's edge only from its second evaluation (CheckEdge answers false until the condition has been evaluated once), and evaluates a Story's Act StartTriggers from time 0 and an Event's from the step its Act starts: a rising edge of a condition that already holds at its first evaluation, and never turns from false to true after it, never fires (esmini logs \"simulationTime = 0 condition used with edge rising which could be missed\" for an Event's)",
    source: `${OSC_CONDITION}:205-238, 282-291, ${STORYBOARD_ELEMENT}:127-160, 174-204, ${ENGINE}:140-161, ${READER}:5334-5350`,
    severity: 'warning',
  },
  simulationTimeZeroAfterStart: {
    does: "evaluates an Event's StartTrigger from the step its Act starts, and holds SimulationTimeCondition equalTo within 1e-6 (SMALL_NUMBER): equalTo 0 in an Event whose Act starts after time 0 never holds",
    source: `${STORYBOARD_ELEMENT}:127-160, 174-204, ${OSC_CONDITION}:56-88`,
    severity: 'warning',
  },
  steadyStateStop: {
    does: 'refuses a SynchronizeAction whose FinalSpeed is an AbsoluteSpeed of 0 or less with a steady state ("SynchronizeAction steady state with 0 or negative final speed is not supported")',
    source: `${READER}:3269-3282`,
    severity: 'error',
  },
} as const satisfies Record<string, SimulatorFact>;

export type EsminiFactName = keyof typeof ESMINI_FACTS;
