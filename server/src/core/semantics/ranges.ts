/**
 * The value ranges the standard gives for numeric attributes. Source: the ASAM OpenSCENARIO XML
 * 1.2/1.3 model documentation (each attribute's "Range: [a..b]" note; `[0..inf[` reads 0 to infinity,
 * a square bracket turned outward leaves its bound out). The XSD files themselves carry no
 * documentation, so the table is kept here as data. Only ranges that hold wherever the element
 * stands are listed (a `Brake value` is a percentage under `brakePercent` but a force under
 * `brakeForce`, so it is not). LightStateAction transitionTime and Phase duration have rules of
 * their own (core/semantics/networkChecks.ts).
 */
export interface ValueRange {
  element: string;
  attribute: string;
  min?: number;
  max?: number;
  /** The bound itself is outside the range. */
  minOpen?: boolean;
  maxOpen?: boolean;
}

const NON_NEGATIVE = { min: 0 } as const;
const FRACTION = { min: 0, max: 1 } as const;

function each(element: string, attributes: string[], range: Omit<ValueRange, 'element' | 'attribute'>): ValueRange[] {
  return attributes.map((attributeName) => ({ element, attribute: attributeName, ...range }));
}

export const VALUE_RANGES: readonly ValueRange[] = [
  // Environment.
  ...each('RoadCondition', ['frictionScaleFactor'], NON_NEGATIVE),
  ...each('Fog', ['visualRange'], NON_NEGATIVE),
  ...each('Sun', ['intensity', 'illuminance'], NON_NEGATIVE),
  ...each('Sun', ['azimuth'], { min: 0, max: 2 * Math.PI }),
  ...each('Sun', ['elevation'], { min: -Math.PI, max: Math.PI }),
  ...each('Precipitation', ['intensity'], FRACTION),
  ...each('Precipitation', ['precipitationIntensity'], NON_NEGATIVE),
  ...each('Weather', ['temperature'], { min: 170, max: 340 }),
  ...each('Weather', ['atmosphericPressure'], { min: 80000, max: 120000 }),
  ...each('Wind', ['direction'], { min: 0, max: 2 * Math.PI, maxOpen: true }),
  ...each('Wind', ['speed'], NON_NEGATIVE),
  // Lights and colours.
  ...each('ColorRgb', ['red', 'green', 'blue'], FRACTION),
  ...each('ColorCmyk', ['cyan', 'magenta', 'yellow', 'key'], FRACTION),
  ...each('LightState', ['luminousIntensity', 'flashingOnDuration', 'flashingOffDuration'], NON_NEGATIVE),
  ...each('AnimationState', ['state'], FRACTION),
  // Controller overrides: pedal and brake positions are fractions.
  ...each('OverrideThrottleAction', ['value'], FRACTION),
  ...each('OverrideThrottleAction', ['maxRate'], NON_NEGATIVE),
  ...each('OverrideBrakeAction', ['value'], FRACTION),
  ...each('OverrideClutchAction', ['value'], FRACTION),
  ...each('OverrideClutchAction', ['maxRate'], NON_NEGATIVE),
  ...each('OverrideParkingBrakeAction', ['value'], FRACTION),
  ...each('Brake', ['maxRate'], NON_NEGATIVE),
  // Entities.
  ...each('Dimensions', ['width', 'length', 'height'], NON_NEGATIVE),
  ...each('Vehicle', ['mass'], NON_NEGATIVE),
  ...each('Pedestrian', ['mass'], NON_NEGATIVE),
  ...each('Axle', ['maxSteering'], { min: 0, max: Math.PI }),
  ...each('Axle', ['wheelDiameter'], { min: 0, minOpen: true }),
  ...each('Axle', ['trackWidth'], NON_NEGATIVE),
  ...each('Performance', ['maxSpeed', 'maxAcceleration', 'maxDeceleration', 'maxAccelerationRate', 'maxDecelerationRate'], NON_NEGATIVE),
  ...each(
    'DynamicConstraints',
    ['maxSpeed', 'maxAcceleration', 'maxDeceleration', 'maxAccelerationRate', 'maxDecelerationRate'],
    NON_NEGATIVE,
  ),
  // Actions.
  ...each('TransitionDynamics', ['value'], NON_NEGATIVE),
  ...each('SpeedProfileEntry', ['time'], NON_NEGATIVE),
  ...each('TrafficSwarmAction', ['innerRadius', 'semiMajorAxis', 'semiMinorAxis'], NON_NEGATIVE),
  // Distributions (variations): a variance and a weight are not negative.
  ...each('NormalDistribution', ['variance'], NON_NEGATIVE),
  ...each('LogNormalDistribution', ['variance'], NON_NEGATIVE),
  ...each('ProbabilityDistributionSetElement', ['weight'], NON_NEGATIVE),
];

function boundText(value: number): string {
  if (Math.abs(value - 2 * Math.PI) < 1e-12) return '2π';
  if (Math.abs(value - Math.PI) < 1e-12) return 'π';
  if (Math.abs(value + Math.PI) < 1e-12) return '-π';
  return String(value);
}

/** The range as the standard writes it: `[0..1]`, `[0..inf[`, `]0..inf[`. */
export function rangeText(range: ValueRange): string {
  const low = range.min === undefined ? ']-inf' : `${range.minOpen ? ']' : '['}${boundText(range.min)}`;
  const high = range.max === undefined ? 'inf[' : `${boundText(range.max)}${range.maxOpen ? '[' : ']'}`;
  return `${low}..${high}`;
}
