import { closestMatch, editDistance } from '../text';

/**
 * CARLA's ScenarioRunner as the profile (./carla.ts) and the export (../export/) know it: its releases, the
 * revision and files the facts were read from, and the maps CARLA loads by name.
 */

/** The ScenarioRunner releases whose facts differ (`--carla`, the `modular2simple.carla.release` setting). */
export const CARLA_RELEASES = ['0.9.15', '0.9.16'] as const;
export type CarlaRelease = (typeof CARLA_RELEASES)[number];

export function isCarlaRelease(value: string): value is CarlaRelease {
  return (CARLA_RELEASES as readonly string[]).includes(value);
}

/** carla-simulator/scenario_runner at the 0.9.16 release (`v0.9.16`). */
export const SR_REVISION = '94ff3b8af752bad2b9d464ad5105868906aa34c0';
export const SR_PARSER = 'srunner/tools/openscenario_parser.py';
export const SR_SCENARIO = 'srunner/scenarios/open_scenario.py';
export const SR_CONFIGURATION = 'srunner/scenarioconfigs/openscenario_configuration.py';
export const SR_ATOMICS = 'srunner/scenariomanager/scenarioatomics/atomic_behaviors.py';
export const SR_TRIGGER_CONDITIONS = 'srunner/scenariomanager/scenarioatomics/atomic_trigger_conditions.py';
export const SR_SCHEMA = 'srunner/openscenario/OpenSCENARIO.xsd';

/**
 * CARLA's maps that `client.load_world` knows in 0.9.15 and 0.9.16 (carla.readthedocs.io `core_map`,
 * "CARLA maps"; the same list as ../shared/carla's mock `CARLA_MAPS`). ScenarioRunner loops on
 * `get_map().name != town` after loading (SR_CONFIGURATION `_set_carla_town`), so any other name fails.
 */
export const CARLA_TOWNS: readonly string[] = [
  'Town01',
  'Town01_Opt',
  'Town02',
  'Town02_Opt',
  'Town03',
  'Town03_Opt',
  'Town04',
  'Town04_Opt',
  'Town05',
  'Town05_Opt',
  'Town06',
  'Town06_Opt',
  'Town07',
  'Town07_Opt',
  'Town10HD',
  'Town10HD_Opt',
  'Town11',
  'Town12',
  'Town13',
  'Town15',
];

/**
 * The CARLA town a road name was likely meant to be (`Town5`, `town05` for Town05), or undefined: one letter off at
 * most, as every town is named TownNN and a looser match would offer one for any number (Town99 for Town01).
 */
export function closestTown(name: string): string | undefined {
  const town = closestMatch(name, CARLA_TOWNS);
  return town !== undefined && editDistance(name.toLowerCase(), town.toLowerCase()) <= 1 ? town : undefined;
}

/** The Property by which ScenarioRunner takes a vehicle as the ego (SR_CONFIGURATION `_extract_vehicle_information`). */
export const EGO_PROPERTY = { name: 'type', value: 'ego_vehicle' } as const;

const EGO_NAMES = /^(ego|hero|ego_vehicle|egovehicle)$/i;

/** Whether a vehicle's name says it is the ego: ego, hero, ego_vehicle, or a name holding ego or hero. */
export function namedAsEgo(name: string): boolean {
  return EGO_NAMES.test(name) || /ego|hero/i.test(name);
}

/**
 * The vehicle the CARLA export marks as the ego when the scenario marks none, of the scenario's vehicles in order:
 * the one named ego or hero (or ego_vehicle), else one whose name holds ego or hero, else the first.
 */
export function egoByName(vehicles: readonly string[]): string | undefined {
  return vehicles.find((name) => EGO_NAMES.test(name)) ?? vehicles.find((name) => /ego|hero/i.test(name)) ?? vehicles[0];
}

/** How far (m) ScenarioRunner may move a LanePosition along the road from where OpenSCENARIO puts it before it counts as elsewhere. */
const LANE_OFFSET_TOLERANCE = 0.01;

/**
 * Where ScenarioRunner puts a LanePosition moved by `offset` (CARLA_FACTS.laneOffsetSide): to the right of the lane's
 * heading in CARLA (along s on a negative lane id, against it on a positive one) turned by `h`, as road s and t from the
 * lane's centre, where OpenSCENARIO puts it at t = `offset`. `place`: there ('as-written'), on the other side of the
 * lane's centre ('mirrored'), or moved along the road by more than LANE_OFFSET_TOLERANCE ('along').
 */
export function scenarioRunnerOffsetPlace(
  laneId: number,
  h: number,
  offset: number,
): { along: number; across: number; place: 'as-written' | 'mirrored' | 'along' } {
  const heading = h + (laneId > 0 ? Math.PI : 0);
  const along = offset * Math.sin(heading);
  const across = -offset * Math.cos(heading);
  const place = Math.abs(along) > LANE_OFFSET_TOLERANCE ? 'along' : across > 0 === offset > 0 ? 'as-written' : 'mirrored';
  return { along, across, place };
}
