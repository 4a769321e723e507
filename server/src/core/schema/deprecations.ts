/*
 * What the standard writes instead of each deprecated element, attribute and value (ASAM OpenSCENARIO XML
 * 1.1-1.3 model documentation; the schema itself only marks them `deprecated`). Both official checkers
 * report a deprecated construct as a warning (SPEC 12); the message names the replacement.
 */

import { ESMINI_PROFILE } from '../profiles/esmini';

export interface Replacement {
  /** What to write instead, in words. */
  instead: string;
  /** The attributes of the same element that replace a deprecated attribute (written together: both named). */
  attributes?: readonly string[];
  /** The child elements that replace a deprecated attribute (written together: both named, as RA Consulting's checker does). */
  elements?: readonly string[];
  /** The attribute's new name when only the name changed (same unit and values): the quick fix renames it. */
  rename?: string;
  /** A simulator that reads the deprecated attribute alone and refuses the scenario without it: it stays (`note`, `source`: the simulator's fact). */
  keptFor?: { simulator: string; note: string; source: string };
}

/** esmini's fact that it refuses a TrafficSwarmAction without velocity (core/profiles/esmini.ts): it never reads <InitialSpeedRange>. */
function esminiNeeds(element: string, attributeName: string): Replacement['keptFor'] {
  const fact = ESMINI_PROFILE.attributes.find((each) => each.element === element && each.attribute === attributeName && each.whenAbsent);
  if (!fact) throw new Error(`no esmini fact for ${element} without ${attributeName}`);
  return { simulator: ESMINI_PROFILE.name, note: fact.note, source: fact.source };
}

/** `Type.attribute` and `Type.Element` (the element's parent type) keys. */
const REPLACEMENTS: Record<string, Replacement> = {
  'ActivateControllerAction.controllerRef': { instead: 'objectControllerRef', attributes: ['objectControllerRef'] },
  'AssignControllerAction.Controller': { instead: '<ObjectController>' },
  'AssignControllerAction.CatalogReference': { instead: '<ObjectController> holding the CatalogReference' },
  'Clothoid.curvatureDot': { instead: 'curvaturePrime', attributes: ['curvaturePrime'], rename: 'curvaturePrime' },
  'DistanceCondition.alongRoute': {
    instead: 'coordinateSystem and relativeDistanceType',
    attributes: ['coordinateSystem', 'relativeDistanceType'],
  },
  'TimeHeadwayCondition.alongRoute': {
    instead: 'coordinateSystem and relativeDistanceType',
    attributes: ['coordinateSystem', 'relativeDistanceType'],
  },
  'TimeToCollisionCondition.alongRoute': {
    instead: 'coordinateSystem and relativeDistanceType',
    attributes: ['coordinateSystem', 'relativeDistanceType'],
  },
  'EntityCondition.ReachPositionCondition': { instead: '<DistanceCondition> with the tolerance as its value, rule lessThan' },
  'FollowTrajectoryAction.Trajectory': { instead: '<TrajectoryRef>' },
  'FollowTrajectoryAction.CatalogReference': { instead: '<TrajectoryRef> holding the CatalogReference' },
  'GeoPosition.latitude': { instead: 'latitudeDeg (in degrees, latitude is in radians)', attributes: ['latitudeDeg'] },
  'GeoPosition.longitude': { instead: 'longitudeDeg (in degrees, longitude is in radians)', attributes: ['longitudeDeg'] },
  'GeoPosition.height': { instead: 'altitude', attributes: ['altitude'] },
  'GlobalAction.ParameterAction': { instead: '<VariableAction> on a variable' },
  'ParameterAction.SetAction': { instead: 'the <SetAction> of a <VariableAction>' },
  'ParameterAction.ModifyAction': { instead: 'the <ModifyAction> of a <VariableAction>' },
  'OverrideBrakeAction.value': { instead: 'a <BrakePercent> or <BrakeForce> child', elements: ['BrakePercent', 'BrakeForce'] },
  'OverrideParkingBrakeAction.value': { instead: 'a <BrakePercent> or <BrakeForce> child', elements: ['BrakePercent', 'BrakeForce'] },
  'OverrideGearAction.number': { instead: 'a <ManualGear> or <AutomaticGear> child', elements: ['ManualGear', 'AutomaticGear'] },
  'Pedestrian.model': { instead: 'model3d', attributes: ['model3d'], rename: 'model3d' },
  'Precipitation.intensity': {
    instead: 'precipitationIntensity',
    attributes: ['precipitationIntensity'],
    rename: 'precipitationIntensity',
  },
  'PrivateAction.ActivateControllerAction': { instead: '<ControllerAction> holding the <ActivateControllerAction>' },
  'Sun.intensity': { instead: 'illuminance', attributes: ['illuminance'], rename: 'illuminance' },
  'TrafficSourceAction.TrafficDefinition': { instead: '<TrafficDistribution>' },
  'TrafficSwarmAction.TrafficDefinition': { instead: '<TrafficDistribution>' },
  'TrafficSourceAction.velocity': { instead: 'speed', attributes: ['speed'], rename: 'speed' },
  'TrafficSwarmAction.velocity': {
    instead: '<InitialSpeedRange>',
    elements: ['InitialSpeedRange'],
    keptFor: esminiNeeds('TrafficSwarmAction', 'velocity'),
  },
  'Weather.cloudState': { instead: 'fractionalCloudCover', attributes: ['fractionalCloudCover'] },
};

/** The standard's value for a deprecated enumeration value, by the value. */
const VALUE_REPLACEMENTS: Record<string, string> = {
  integer: 'int',
  overwrite: 'override',
  cartesianDistance: 'euclidianDistance',
};

/** The replacement of a deprecated attribute or child element of a type. */
export function replacementOf(typeName: string, name: string): Replacement | undefined {
  return Object.hasOwn(REPLACEMENTS, `${typeName}.${name}`) ? REPLACEMENTS[`${typeName}.${name}`] : undefined;
}

/** The standard's value instead of a deprecated enumeration value. */
export function valueReplacementOf(value: string): string | undefined {
  return Object.hasOwn(VALUE_REPLACEMENTS, value) ? VALUE_REPLACEMENTS[value] : undefined;
}
