import type { ProblemCode } from '../problems';
import type { SchemaVersion } from '../schema/model';
import { CARLA_FACTS } from '../profiles/carla';

/**
 * The value ranges of numeric attributes, per OpenSCENARIO version, each as the ASAM OpenSCENARIO model
 * documents it: the class documentation of the standard's UML model gives many attributes a `Range:`
 * (the bundled XSDs carry no annotations, so the model is the source). Read from the model's
 * documentation as RA Consulting's ASAM OpenSCENARIO API generates it into its code
 * (RA-Consulting-GmbH/openscenario.api.test, `cpp/openScenarioLib/generated/v1_{0,1,2,3}/api/ApiClassInterfacesV1_*.h`,
 * "From OpenSCENARIO class model specification"; for 1.0 and 1.1 also the model itself,
 * `OpenSCENARIO_Ea_1.{0,1}.0.xmi`), once by hand, and written here as our own table with each range's
 * text quoted as its `source`: nothing is read from there at run time. The bounds are parsed from that
 * text, so the table cannot say another range than its source. A range the model does not document is not
 * checked, although RA Consulting's own checker data adds some (LightState luminousIntensity,
 * the override maxRate and maxTorque, animationDuration). The model names a class (an XSD complexType); the
 * XML elements of that class were taken from the bundled XSDs (an `Axle` is a FrontAxle, RearAxle or
 * AdditionalAxle, an `OverrideThrottleAction` a Throttle). A range holds for its class only, so an
 * attribute that means something else under another element (a Brake `value` of BrakeInput, a force or a
 * percentage) is not checked. A file of a later version is read as 1.3 (core/schema/version.ts).
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
  /** The versions whose model documents the range (and whose schema has the attribute). */
  versions: readonly SchemaVersion[];
  /** Where the range is written: the model's documentation of the attribute, its range quoted; and why the check differs, where it does. */
  source: string;
  /** A rule of its own checks this range, with a message of its own (core/semantics/networkChecks.ts). */
  checkedBy?: ProblemCode;
  /** How esmini reads a value outside the range with one clear meaning (read in its sources): a warning that says both (SPEC 12); the first reading that applies. */
  esmini?: SimulatorReading | readonly SimulatorReading[];
  /** How CARLA's ScenarioRunner runs such a value (read in its sources), said instead of esmini's with the simulator carla. */
  carla?: SimulatorReading;
}

export interface SimulatorReading {
  /** What the simulator does with such a value, completing "esmini ..." or "CARLA ScenarioRunner ...". */
  reading: string;
  /** Only when the element's attribute has this value. */
  when?: { attribute: string; value: string };
  /** Only in a file of these versions (esmini reads some values by the file's version). */
  versions?: readonly SchemaVersion[];
}

/** The readings recorded for a simulator, in the order they are tried. */
export function readingsOf(readings: SimulatorReading | readonly SimulatorReading[] | undefined): readonly SimulatorReading[] {
  if (readings === undefined) return [];
  return 'reading' in readings ? [readings] : readings;
}

type Bounds = Pick<ValueRange, 'min' | 'max' | 'minOpen' | 'maxOpen'>;

const ALL: readonly SchemaVersion[] = ['1.0', '1.1', '1.2', '1.3'];
const FROM_1_1: readonly SchemaVersion[] = ['1.1', '1.2', '1.3'];
const FROM_1_2: readonly SchemaVersion[] = ['1.2', '1.3'];
const ONLY_1_3: readonly SchemaVersion[] = ['1.3'];

/** One bound as the model writes it: a number, `inf`, `PI`, `2*PI`, `2PI`, `PI/2`, each with an optional sign. */
function boundOf(text: string, range: string): number | undefined {
  const compact = text.replace(/\s+/g, '');
  if (/^[-+]?inf$/i.test(compact)) return undefined;
  const pi = /^([-+]?)(\d+(?:\.\d+)?)?\*?pi(?:\/(\d+))?$/i.exec(compact);
  if (pi) return (pi[1] === '-' ? -1 : 1) * Number(pi[2] ?? 1) * (Math.PI / Number(pi[3] ?? 1));
  const number = Number(compact);
  if (compact === '' || !Number.isFinite(number)) throw new Error(`ranges.ts: cannot read the bound "${text}" of the range "${range}"`);
  return number;
}

/** The bounds of a range as the model documents it: `[0..inf[`, `]0..inf[`, `[0..1]`, `[0;PI]`, `[170...340]`, `[0..2*PI[`. */
export function documentedBounds(range: string): Bounds {
  const parts = /^([[\]])(.+?)(?:\.{2,3}|;)(.+?)([[\]])$/.exec(range.trim());
  if (!parts) throw new Error(`ranges.ts: cannot read the documented range "${range}"`);
  const [, low, minText, maxText, high] = parts;
  const min = boundOf(minText, range);
  const max = boundOf(maxText, range);
  return {
    ...(min === undefined ? {} : { min, ...(low === ']' ? { minOpen: true } : {}) }),
    ...(max === undefined ? {} : { max, ...(high === '[' ? { maxOpen: true } : {}) }),
  };
}

function versionsText(versions: readonly SchemaVersion[]): string {
  return versions.length > 1 ? `${versions[0]}-${versions[versions.length - 1]}` : versions[0];
}

interface RuleOptions extends Pick<ValueRange, 'checkedBy' | 'esmini' | 'carla'> {
  /** Checked with other bounds than documented, and why. */
  checked?: { range: string; why: string };
}

/** The rules of one model class: for each attribute the range its documentation gives (`documented`, quoted as the model writes it), on each element of the class. */
function rules(
  modelClass: string | { modelClass: string; elements: string[] },
  attributes: string[],
  documented: string,
  versions: readonly SchemaVersion[],
  options: RuleOptions = {},
): ValueRange[] {
  const className = typeof modelClass === 'string' ? modelClass : modelClass.modelClass;
  const elements = typeof modelClass === 'string' ? [modelClass] : modelClass.elements;
  const { checked, ...extra } = options;
  const bounds = documentedBounds(checked?.range ?? documented);
  return elements.flatMap((element) =>
    attributes.map((attributeName) => ({
      element,
      ...(element === className ? {} : { modelClass: className }),
      attribute: attributeName,
      ...bounds,
      versions,
      source:
        `ASAM OpenSCENARIO ${versionsText(versions)} model, ${className}.${attributeName}: Range: ${documented}` +
        (checked ? `; checked as ${checked.range}: ${checked.why}` : ''),
      ...extra,
    })),
  );
}

// esmini 3.6 (EnvironmentSimulator/Modules/ScenarioEngine): ScenarioReader.cpp reads each of these, OSCPrivateAction.cpp runs them.
// From 1.1 on esmini takes the magnitude; in a 1.0 file (no displacement) the sign names the side, as measured with esmini 3.6 (qc20).
const MAGNITUDE: readonly SimulatorReading[] = [
  {
    reading: 'uses the absolute value (ScenarioReader.cpp warns "Negative distance ... Using absolute value")',
    versions: ['1.1', '1.2', '1.3'],
  },
];
const LATERAL_SIGN: readonly SimulatorReading[] = [
  ...MAGNITUDE,
  {
    reading:
      'keeps the sign in a 1.0 file, which has no displacement: a negative distance keeps the entity to the right of the referenced entity instead of to its left (ScenarioReader.cpp takes the absolute value only from 1.1; OSCPrivateAction.cpp LatDistanceAction::GetDistanceError)',
    versions: ['1.0'],
  },
];
const LONGITUDINAL_SIGN: readonly SimulatorReading[] = [
  ...MAGNITUDE,
  {
    reading:
      'keeps the sign in a 1.0 file, which has no displacement: a negative distance or timeGap keeps the entity ahead of the referenced entity instead of behind it (ScenarioReader.cpp takes the absolute value only from 1.1; OSCPrivateAction.cpp LongDistanceAction::Step)',
    versions: ['1.0'],
  },
];
const RATE_MAGNITUDE: SimulatorReading = {
  reading: "takes the rate's magnitude, its sign from the direction of the change (OSCPrivateAction.cpp TransitionDynamics::UpdateRate)",
  when: { attribute: 'dynamicsDimension', value: 'rate' },
};
// ScenarioRunner 0.9.16 (../shared/carla): a dimension other than distance is a duration, which ChangeActorTargetSpeed compares with the time since it started.
const SPEED_RATE_AS_DURATION: SimulatorReading = {
  reading: `${CARLA_FACTS.speedRateAsDuration.does} (${CARLA_FACTS.speedRateAsDuration.source})`,
  when: { attribute: 'dynamicsDimension', value: 'rate' },
};

// esmini 3.6 clamps these into the standard's range when it reads them, and runs the scenario (SPEC 12: a warning that says so).
const OVERRIDE_CLAMP: SimulatorReading = {
  reading:
    'clamps it into [0..1] and runs (ScenarioReader.cpp OverrideControllerValueAction, OSCPrivateAction.cpp OverrideControlAction::RangeCheckAndErrorLog)',
};
const PRESSURE_CLAMP: SimulatorReading = {
  reading:
    'clamps it into [80000..120000] Pa, warning "Atmospheric pressure clamped", and runs (OSCEnvironment.cpp SetAtmosphericPressure)',
};
const TEMPERATURE_CLAMP: SimulatorReading = {
  reading: 'clamps it into [170..340] K, warning "Temperature clamped", and runs (OSCEnvironment.cpp SetTemperature)',
};

const AXLES = { modelClass: 'Axle', elements: ['FrontAxle', 'RearAxle', 'AdditionalAxle'] };
// Each element of the class has its own simulator readings.
const LANE_CHANGE_DYNAMICS = { modelClass: 'TransitionDynamics', elements: ['LaneChangeActionDynamics'] };
const SPEED_DYNAMICS = { modelClass: 'TransitionDynamics', elements: ['SpeedActionDynamics'] };

// Each documented range is the model's text of the last version listed; older models write the same bounds as `[0;PI]`, `[0..2PI]`, `[170...340]`.
export const VALUE_RANGES: readonly ValueRange[] = [
  ...rules('AbsoluteSpeed', ['value'], '[0..inf[', ALL),
  ...rules('AnimationFile', ['timeOffset'], '[0..inf[', FROM_1_2),
  ...rules('AnimationState', ['state'], '[0..1]', FROM_1_2),
  ...rules(AXLES, ['maxSteering'], '[0..PI]', ALL, {
    esmini: { reading: 'reads maxSteering and uses it nowhere (ScenarioReader.cpp), so the run is the same' },
  }),
  ...rules(AXLES, ['positionX', 'positionZ', 'trackWidth'], '[0..inf[', ALL),
  ...rules(AXLES, ['wheelDiameter'], ']0..inf[', ALL),
  ...rules('Clothoid', ['curvatureDot'], '[0..inf[', ALL, {
    esmini: { reading: 'reads curvatureDot as curvaturePrime, whose range has no bound (ScenarioReader.cpp)' },
  }),
  ...rules('Clothoid', ['startTime'], '[0..inf[', ALL),
  ...rules('Clothoid', ['stopTime'], ']0..inf[', ALL),
  // The 1.2 model documents the colours too, but only the 1.3 schema has them.
  ...rules('ColorCmyk', ['cyan', 'magenta', 'yellow', 'key'], '[0..1]', ONLY_1_3),
  ...rules('ColorRgb', ['red', 'green', 'blue'], '[0..1]', ONLY_1_3),
  ...rules('Condition', ['delay'], '[0..inf[', ALL),
  ...rules('ControlPoint', ['time'], '[0..inf[', ALL),
  ...rules('ControllerDistributionEntry', ['weight'], ']0..inf[', ALL),
  ...rules('Dimensions', ['width', 'length', 'height'], '[0..inf[', ALL),
  ...rules('DirectionOfTravelDistribution', ['same', 'opposite'], '[0..inf[', FROM_1_2),
  ...rules('DistanceCondition', ['value'], '[0..inf[', ALL),
  ...rules('DomeImage', ['azimuthOffset'], '[0..2*PI]', FROM_1_2),
  ...rules('DynamicConstraints', ['maxSpeed', 'maxAcceleration', 'maxDeceleration'], '[0..inf[', ALL),
  ...rules('DynamicConstraints', ['maxAccelerationRate', 'maxDecelerationRate'], '[0..inf[', FROM_1_2),
  ...rules('EndOfRoadCondition', ['duration'], '[0..inf[', ALL),
  ...rules('Event', ['maximumExecutionCount'], '[1..inf[', ALL),
  ...rules('Fog', ['visualRange'], '[0..inf[', ALL),
  ...rules('GeoPosition', ['altitude'], '[0..inf[', FROM_1_2),
  ...rules('GeoPosition', ['latitude'], '[-PI..PI]', FROM_1_1),
  ...rules('GeoPosition', ['longitude'], '[-PI/2..PI/2]', FROM_1_1, {
    checked: {
      range: '[-PI..PI]',
      why: "the model swaps latitude's and longitude's ranges; its GeoPosition.longitudeDeg is [-180..180], and [-PI/2..PI/2] would refuse every place east of 90 degrees (Beijing, Tokyo)",
    },
  }),
  ...rules('GeoPosition', ['latitudeDeg'], '[-90..90]', FROM_1_2),
  ...rules('GeoPosition', ['longitudeDeg'], '[-180..180]', FROM_1_2),
  ...rules('LaneOffsetActionDynamics', ['maxLateralAcc'], '[0..inf[', ALL),
  ...rules('LanePosition', ['s'], '[0..inf[', ALL),
  ...rules('LateralDistanceAction', ['distance'], '[0..inf[', ALL, { esmini: LATERAL_SIGN }),
  ...rules('LongitudinalDistanceAction', ['distance', 'timeGap'], '[0..inf[', ALL, { esmini: LONGITUDINAL_SIGN }),
  ...rules('ManeuverGroup', ['maximumExecutionCount'], '[1..inf[', ALL),
  ...rules('MiscObject', ['mass'], '[0..inf[', ALL),
  ...rules('Nurbs', ['order'], '[2..inf[', ALL),
  ...rules('OffroadCondition', ['duration'], '[0..inf[', ALL),
  ...rules({ modelClass: 'OverrideBrakeAction', elements: ['Brake'] }, ['value'], '[0..1]', ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules({ modelClass: 'OverrideClutchAction', elements: ['Clutch'] }, ['value'], '[0..1]', ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules({ modelClass: 'OverrideParkingBrakeAction', elements: ['ParkingBrake'] }, ['value'], '[0..1]', ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules({ modelClass: 'OverrideThrottleAction', elements: ['Throttle'] }, ['value'], '[0..1]', ALL, { esmini: OVERRIDE_CLAMP }),
  ...rules('Performance', ['maxAcceleration', 'maxDeceleration'], '[0..inf[', ALL),
  ...rules('Performance', ['maxAccelerationRate', 'maxDecelerationRate'], '[0..inf[', FROM_1_2),
  ...rules('Phase', ['duration'], '[0..inf[', ALL, { checkedBy: 'non-positive-phase-duration' }),
  ...rules({ modelClass: 'PositionInLaneCoordinates', elements: ['FromLaneCoordinates'] }, ['pathS'], '[0..inf[', ALL),
  ...rules('Precipitation', ['intensity'], '[0..1]', ALL),
  ...rules('ReachPositionCondition', ['tolerance'], '[0..inf[', ALL),
  ...rules('RelativeClearanceCondition', ['distanceForward', 'distanceBackward'], '[0..inf[', FROM_1_2),
  ...rules('RelativeDistanceCondition', ['value'], '[0..inf[', ALL),
  ...rules('RoadCondition', ['frictionScaleFactor'], '[0..inf[', ALL),
  // The 1.0 and 1.1 models document RoadPosition s without a range.
  ...rules('RoadPosition', ['s'], '[0..inf[', FROM_1_2),
  ...rules('SpeedProfileEntry', ['time'], '[0..inf[', FROM_1_2),
  ...rules('StandStillCondition', ['duration'], '[0..inf[', ALL),
  ...rules('Sun', ['azimuth'], '[0..2*PI]', ALL),
  ...rules('Sun', ['elevation'], '[-PI..PI]', ALL),
  ...rules('Sun', ['intensity'], '[0..inf[', ALL),
  ...rules('Sun', ['illuminance'], '[0..inf[', ONLY_1_3),
  ...rules('TimeHeadwayCondition', ['value'], '[0..inf[', ALL),
  ...rules('TimeToCollisionCondition', ['value'], '[0..inf[', ALL),
  ...rules('Timing', ['scale'], ']0..inf[', ALL),
  ...rules('TrafficSignalController', ['delay'], '[0..inf[', ALL),
  ...rules('TrafficSinkAction', ['radius', 'rate'], '[0..inf[', ALL),
  ...rules('TrafficSourceAction', ['radius', 'rate', 'velocity'], '[0..inf[', ALL),
  ...rules('TrafficSwarmAction', ['innerRadius', 'semiMajorAxis', 'semiMinorAxis', 'velocity'], '[0..inf[', ALL),
  ...rules(LANE_CHANGE_DYNAMICS, ['value'], '[0..inf[', ALL, { esmini: RATE_MAGNITUDE }),
  ...rules(SPEED_DYNAMICS, ['value'], '[0..inf[', ALL, { esmini: RATE_MAGNITUDE, carla: SPEED_RATE_AS_DURATION }),
  ...rules('TraveledDistanceCondition', ['value'], '[0..inf[', ALL),
  ...rules('VehicleCategoryDistributionEntry', ['weight'], '[0..inf[', ALL),
  ...rules('VehicleRoleDistributionEntry', ['weight'], '[0..inf[', FROM_1_2),
  ...rules('Weather', ['temperature'], '[170..340]', FROM_1_1, { esmini: TEMPERATURE_CLAMP }),
  ...rules('Weather', ['atmosphericPressure'], '[80000..120000]', FROM_1_1, { esmini: PRESSURE_CLAMP }),
  ...rules('Wind', ['direction'], '[0..2*PI[', FROM_1_1),
  ...rules('Wind', ['speed'], '[0..inf[', FROM_1_1),
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
