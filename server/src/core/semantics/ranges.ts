import type { ProblemCode } from '../problems';
import type { SchemaVersion } from '../schema/model';

/**
 * The value ranges of numeric attributes, per OpenSCENARIO version. Source: the range checker rules of
 * RA Consulting's ASAM OpenSCENARIO API (RA-Consulting-GmbH/openscenario.api.test, the generator's input
 * `RangeCheckerRules_1.{0,1,2,3}.0.json`, derived from the ASAM UML model, and the rules generated from it,
 * `RangeCheckerRulesV1_{0,1,2,3}.cpp`), read once by hand and written here as our own table: nothing is
 * read from there at run time. Their rules name a class of the ASAM model (an XSD complexType); the XML
 * elements of that class were taken from the bundled XSDs (an `Axle` is a FrontAxle, RearAxle or
 * AdditionalAxle, an `OverrideThrottleAction` a Throttle). A rule holds for its class only, so an
 * attribute that means something else under another element (a Brake `value` of BrakeInput, a force or a
 * percentage) is not checked. Their 1.0 and 1.1 rules are the same, and so are their 1.2 and 1.3 ones; a
 * file of a later version is read as 1.3 (core/schema/version.ts). Where their display of a bound differs
 * from the bound they check (DomeImage azimuthOffset shows `PI`, checks 2π), the checked bound is kept.
 * `[0..inf[` reads 0 to infinity; a square bracket turned outward leaves its bound out.
 */
export interface ValueRange {
  /** The XML element the rule is checked on. */
  element: string;
  /** The class of the ASAM model the rule is written for (the element's XSD type), when it is named otherwise. */
  modelClass?: string;
  attribute: string;
  min?: number;
  max?: number;
  /** The bound itself is outside the range. */
  minOpen?: boolean;
  maxOpen?: boolean;
  /** The versions whose rules give the range. */
  versions: readonly SchemaVersion[];
  /** A rule of its own checks this range, with a message of its own (core/semantics/networkChecks.ts). */
  checkedBy?: ProblemCode;
  /** How esmini reads a value outside the range with one clear meaning (read in its sources): a warning that says both (SPEC 12). */
  esmini?: EsminiReading;
}

export interface EsminiReading {
  /** What esmini does with such a value, completing "esmini ...". */
  reading: string;
  /** Only when the element's attribute has this value. */
  when?: { attribute: string; value: string };
}

type Bounds = Pick<ValueRange, 'min' | 'max' | 'minOpen' | 'maxOpen'>;

const ALL: readonly SchemaVersion[] = ['1.0', '1.1', '1.2', '1.3'];
const FROM_1_2: readonly SchemaVersion[] = ['1.2', '1.3'];

const NON_NEGATIVE: Bounds = { min: 0 };
const POSITIVE: Bounds = { min: 0, minOpen: true };
const FRACTION: Bounds = { min: 0, max: 1 };
const AT_LEAST_ONE: Bounds = { min: 1 };
const PLUS_MINUS_PI: Bounds = { min: -Math.PI, max: Math.PI };
const FULL_TURN: Bounds = { min: 0, max: 2 * Math.PI };
const RATE: Bounds = { min: 0, minOpen: true, max: 100 };

/** The rules of one model class: the same bounds for each attribute, on each element of the class. */
function rules(
  modelClass: string | { modelClass: string; elements: string[] },
  attributes: string[],
  bounds: Bounds,
  versions: readonly SchemaVersion[],
  extra: Pick<ValueRange, 'checkedBy' | 'esmini'> = {},
): ValueRange[] {
  const className = typeof modelClass === 'string' ? modelClass : modelClass.modelClass;
  const elements = typeof modelClass === 'string' ? [modelClass] : modelClass.elements;
  return elements.flatMap((element) =>
    attributes.map((attributeName) => ({
      element,
      ...(element === className ? {} : { modelClass: className }),
      attribute: attributeName,
      ...bounds,
      versions,
      ...extra,
    })),
  );
}

// esmini 3.6 (EnvironmentSimulator/Modules/ScenarioEngine): ScenarioReader.cpp reads each of these, OSCPrivateAction.cpp runs them.
const MAGNITUDE: EsminiReading = {
  reading: 'uses the absolute value (ScenarioReader.cpp warns "Negative distance ... Using absolute value")',
};
const RATE_MAGNITUDE: EsminiReading = {
  reading: "takes the rate's magnitude, its sign from the direction of the change (OSCPrivateAction.cpp TransitionDynamics::UpdateRate)",
  when: { attribute: 'dynamicsDimension', value: 'rate' },
};

// esmini 3.6 clamps these into the standard's range when it reads them, and runs the scenario (SPEC 12: a warning that says so).
const OVERRIDE_CLAMP: EsminiReading = {
  reading:
    'clamps it into [0..1] and runs (ScenarioReader.cpp OverrideControllerValueAction, OSCPrivateAction.cpp OverrideControlAction::RangeCheckAndErrorLog)',
};
const PRESSURE_CLAMP: EsminiReading = {
  reading:
    'clamps it into [80000..120000] Pa, warning "Atmospheric pressure clamped", and runs (OSCEnvironment.cpp SetAtmosphericPressure)',
};
const TEMPERATURE_CLAMP: EsminiReading = {
  reading: 'clamps it into [170..340] K, warning "Temperature clamped", and runs (OSCEnvironment.cpp SetTemperature)',
};

const AXLES = { modelClass: 'Axle', elements: ['FrontAxle', 'RearAxle', 'AdditionalAxle'] };
const TRANSITION_DYNAMICS = { modelClass: 'TransitionDynamics', elements: ['LaneChangeActionDynamics', 'SpeedActionDynamics'] };

export const VALUE_RANGES: readonly ValueRange[] = [
  ...rules('AbsoluteSpeed', ['value'], NON_NEGATIVE, ALL),
  // 1.2 names the element of the class AnimationAction AnimationStateAction; 1.3 names it AnimationAction.
  ...rules({ modelClass: 'AnimationAction', elements: ['AnimationStateAction'] }, ['animationDuration'], NON_NEGATIVE, ['1.2']),
  ...rules('AnimationAction', ['animationDuration'], NON_NEGATIVE, ['1.3']),
  ...rules('AnimationFile', ['timeOffset'], NON_NEGATIVE, FROM_1_2),
  ...rules('AnimationState', ['state'], FRACTION, FROM_1_2),
  ...rules(AXLES, ['maxSteering'], { min: 0, max: Math.PI }, ALL, {
    esmini: { reading: 'reads maxSteering and uses it nowhere (ScenarioReader.cpp), so the run is the same' },
  }),
  ...rules(AXLES, ['positionX', 'positionZ', 'trackWidth'], NON_NEGATIVE, ALL),
  ...rules(AXLES, ['wheelDiameter'], POSITIVE, ALL),
  ...rules('Clothoid', ['curvatureDot'], NON_NEGATIVE, ALL, {
    esmini: { reading: 'reads curvatureDot as curvaturePrime, whose range has no bound (ScenarioReader.cpp)' },
  }),
  ...rules('Clothoid', ['startTime'], NON_NEGATIVE, ALL),
  ...rules('Clothoid', ['stopTime'], POSITIVE, ALL),
  ...rules('ColorCmyk', ['cyan', 'magenta', 'yellow', 'key'], FRACTION, FROM_1_2),
  ...rules('ColorRgb', ['red', 'green', 'blue'], FRACTION, FROM_1_2),
  ...rules('Condition', ['delay'], NON_NEGATIVE, ALL),
  ...rules('ControlPoint', ['time'], NON_NEGATIVE, ALL),
  ...rules('ControllerDistributionEntry', ['weight'], POSITIVE, ALL),
  ...rules('Dimensions', ['width', 'length', 'height'], NON_NEGATIVE, ALL),
  ...rules('DirectionOfTravelDistribution', ['same', 'opposite'], NON_NEGATIVE, FROM_1_2),
  ...rules('DistanceCondition', ['value'], NON_NEGATIVE, ALL),
  ...rules('DomeImage', ['azimuthOffset'], FULL_TURN, FROM_1_2),
  ...rules('DynamicConstraints', ['maxSpeed', 'maxAcceleration', 'maxDeceleration'], NON_NEGATIVE, ALL),
  ...rules('DynamicConstraints', ['maxAccelerationRate', 'maxDecelerationRate'], NON_NEGATIVE, FROM_1_2),
  ...rules('EndOfRoadCondition', ['duration'], NON_NEGATIVE, ALL),
  ...rules('Event', ['maximumExecutionCount'], AT_LEAST_ONE, ALL),
  ...rules('Fog', ['visualRange'], NON_NEGATIVE, ALL),
  ...rules('GeoPosition', ['altitude'], NON_NEGATIVE, FROM_1_2),
  ...rules('GeoPosition', ['latitude', 'longitude'], PLUS_MINUS_PI, FROM_1_2),
  ...rules('GeoPosition', ['latitudeDeg'], { min: -90, max: 90 }, FROM_1_2),
  // Their data gives longitudeDeg a latitude's [-90..90], which would refuse every place east of 90 degrees (Beijing, Tokyo).
  ...rules('GeoPosition', ['longitudeDeg'], { min: -180, max: 180 }, FROM_1_2),
  ...rules('LaneOffsetActionDynamics', ['maxLateralAcc'], NON_NEGATIVE, ALL),
  ...rules('LanePosition', ['s'], NON_NEGATIVE, ALL),
  ...rules('LateralDistanceAction', ['distance'], NON_NEGATIVE, ALL, { esmini: MAGNITUDE }),
  ...rules('LightState', ['luminousIntensity', 'flashingOnDuration', 'flashingOffDuration'], NON_NEGATIVE, FROM_1_2),
  ...rules('LightStateAction', ['transitionTime'], NON_NEGATIVE, FROM_1_2, { checkedBy: 'negative-transition-time' }),
  ...rules('LongitudinalDistanceAction', ['distance', 'timeGap'], NON_NEGATIVE, ALL, { esmini: MAGNITUDE }),
  ...rules('ManeuverGroup', ['maximumExecutionCount'], AT_LEAST_ONE, ALL),
  ...rules('MiscObject', ['mass'], NON_NEGATIVE, ALL),
  ...rules('Nurbs', ['order'], { min: 2 }, ALL),
  ...rules('OffroadCondition', ['duration'], NON_NEGATIVE, ALL),
  ...rules({ modelClass: 'OverrideBrakeAction', elements: ['Brake'] }, ['value'], FRACTION, ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules({ modelClass: 'OverrideClutchAction', elements: ['Clutch'] }, ['value'], FRACTION, ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules({ modelClass: 'OverrideClutchAction', elements: ['Clutch'] }, ['maxRate'], RATE, FROM_1_2),
  ...rules({ modelClass: 'OverrideParkingBrakeAction', elements: ['ParkingBrake'] }, ['value'], FRACTION, ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules({ modelClass: 'OverrideSteeringWheelAction', elements: ['SteeringWheel'] }, ['maxRate'], RATE, FROM_1_2),
  ...rules({ modelClass: 'OverrideSteeringWheelAction', elements: ['SteeringWheel'] }, ['maxTorque'], POSITIVE, FROM_1_2),
  ...rules({ modelClass: 'OverrideThrottleAction', elements: ['Throttle'] }, ['value'], FRACTION, ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules('Performance', ['maxAcceleration', 'maxDeceleration'], NON_NEGATIVE, ALL),
  ...rules('Performance', ['maxAccelerationRate', 'maxDecelerationRate'], NON_NEGATIVE, FROM_1_2),
  ...rules('Phase', ['duration'], NON_NEGATIVE, ALL, { checkedBy: 'non-positive-phase-duration' }),
  ...rules({ modelClass: 'PositionInLaneCoordinates', elements: ['FromLaneCoordinates'] }, ['pathS'], NON_NEGATIVE, ALL),
  ...rules('Precipitation', ['intensity'], FRACTION, ALL),
  ...rules('ReachPositionCondition', ['tolerance'], NON_NEGATIVE, ALL),
  ...rules('RelativeClearanceCondition', ['distanceForward', 'distanceBackward'], NON_NEGATIVE, FROM_1_2),
  ...rules('RelativeDistanceCondition', ['value'], NON_NEGATIVE, ALL),
  ...rules('RoadCondition', ['frictionScaleFactor'], NON_NEGATIVE, ALL),
  ...rules('RoadPosition', ['s'], NON_NEGATIVE, FROM_1_2),
  ...rules('SpeedProfileEntry', ['time'], NON_NEGATIVE, FROM_1_2),
  ...rules('StandStillCondition', ['duration'], NON_NEGATIVE, ALL),
  ...rules('Sun', ['azimuth'], FULL_TURN, ALL),
  ...rules('Sun', ['elevation'], PLUS_MINUS_PI, ALL),
  ...rules('Sun', ['intensity'], NON_NEGATIVE, ALL),
  ...rules('Sun', ['illuminance'], NON_NEGATIVE, FROM_1_2),
  ...rules('TimeHeadwayCondition', ['value'], NON_NEGATIVE, ALL),
  ...rules('TimeToCollisionCondition', ['value'], NON_NEGATIVE, ALL),
  ...rules('Timing', ['scale'], POSITIVE, ALL),
  ...rules('TrafficSignalController', ['delay'], NON_NEGATIVE, ALL),
  ...rules('TrafficSinkAction', ['radius', 'rate'], NON_NEGATIVE, ALL),
  ...rules('TrafficSourceAction', ['radius', 'rate', 'velocity'], NON_NEGATIVE, ALL),
  ...rules('TrafficSwarmAction', ['innerRadius', 'semiMajorAxis', 'semiMinorAxis', 'velocity'], NON_NEGATIVE, ALL),
  ...rules(TRANSITION_DYNAMICS, ['value'], NON_NEGATIVE, ALL, { esmini: RATE_MAGNITUDE }),
  ...rules('TraveledDistanceCondition', ['value'], NON_NEGATIVE, ALL),
  ...rules('VehicleCategoryDistributionEntry', ['weight'], NON_NEGATIVE, ALL),
  ...rules('VehicleRoleDistributionEntry', ['weight'], NON_NEGATIVE, FROM_1_2),
  ...rules('Weather', ['temperature'], { min: 170, max: 340 }, FROM_1_2, { esmini: TEMPERATURE_CLAMP }),
  ...rules('Weather', ['atmosphericPressure'], { min: 80000, max: 120000 }, FROM_1_2, { esmini: PRESSURE_CLAMP }),
  ...rules('Wind', ['direction'], { min: 0, max: 2 * Math.PI, maxOpen: true }, FROM_1_2),
  ...rules('Wind', ['speed'], NON_NEGATIVE, FROM_1_2),
];

/** The ranges checked in a file of `version`, by element name. */
const rangesByVersion = new Map<SchemaVersion, ReadonlyMap<string, readonly ValueRange[]>>();

export function valueRangesOf(version: SchemaVersion): ReadonlyMap<string, readonly ValueRange[]> {
  let byElement = rangesByVersion.get(version);
  if (!byElement) {
    const map = new Map<string, ValueRange[]>();
    for (const range of VALUE_RANGES) {
      if (!range.versions.includes(version)) continue;
      const list = map.get(range.element);
      if (list) list.push(range);
      else map.set(range.element, [range]);
    }
    rangesByVersion.set(version, (byElement = map));
  }
  return byElement;
}

export function inRange(value: number, range: Bounds): boolean {
  if (range.min !== undefined && (range.minOpen ? value <= range.min : value < range.min)) return false;
  if (range.max !== undefined && (range.maxOpen ? value >= range.max : value > range.max)) return false;
  return true;
}

/** A bound as the standard's model documentation writes it: `PI`, `2PI`, `-PI`, else the number. */
function boundText(value: number): string {
  if (Math.abs(value - 2 * Math.PI) < 1e-12) return '2PI';
  if (Math.abs(value - Math.PI) < 1e-12) return 'PI';
  if (Math.abs(value + Math.PI) < 1e-12) return '-PI';
  return String(value);
}

/** The range as the standard writes it: `[0..1]`, `[0..inf[`, `]0..inf[`, `[0..2PI[`. */
export function rangeText(range: Bounds): string {
  const low = range.min === undefined ? ']-inf' : `${range.minOpen ? ']' : '['}${boundText(range.min)}`;
  const high = range.max === undefined ? 'inf[' : `${boundText(range.max)}${range.maxOpen ? '[' : ']'}`;
  return `${low}..${high}`;
}
