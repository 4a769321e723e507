/**
 * What CARLA and its ScenarioRunner accept, as data with its source named: the maps, the blueprints and
 * the default blueprint for each kind of entity. The export (./carla.ts) and its checks read these.
 */

import { closestMatch } from '../text';

export {
  CARLA_RELEASES,
  CARLA_TOWNS,
  closestTown,
  EGO_PROPERTY,
  egoByName,
  isCarlaRelease,
  namedAsEgo,
  SR_ATOMICS,
  SR_CONFIGURATION,
  SR_PARSER,
  SR_REVISION,
  SR_SCENARIO,
  SR_SCHEMA,
  SR_TRIGGER_CONDITIONS,
} from '../profiles/scenarioRunner';
export type { CarlaRelease } from '../profiles/scenarioRunner';

/**
 * The vehicle blueprints of CARLA 0.9.15 and 0.9.16 (carla-simulator/carla `Docs/catalogue_vehicles.md`
 * at 0a16e29c, "Blueprint ID" of each entry). ScenarioRunner spawns a Vehicle's `name` as the blueprint
 * (SR_CONFIGURATION `_extract_vehicle_information`, `CarlaDataProvider.create_blueprint`).
 */
export const CARLA_VEHICLE_BLUEPRINTS: readonly string[] = [
  'vehicle.audi.a2',
  'vehicle.audi.etron',
  'vehicle.audi.tt',
  'vehicle.bh.crossbike',
  'vehicle.bmw.grandtourer',
  'vehicle.carlamotors.carlacola',
  'vehicle.carlamotors.firetruck',
  'vehicle.chevrolet.impala',
  'vehicle.citroen.c3',
  'vehicle.diamondback.century',
  'vehicle.dodge.charger_2020',
  'vehicle.dodge.charger_police',
  'vehicle.dodge.charger_police_2020',
  'vehicle.ford.ambulance',
  'vehicle.ford.crown',
  'vehicle.ford.mustang',
  'vehicle.gazelle.omafiets',
  'vehicle.harley-davidson.low_rider',
  'vehicle.jeep.wrangler_rubicon',
  'vehicle.kawasaki.ninja',
  'vehicle.lincoln.mkz_2017',
  'vehicle.lincoln.mkz_2020',
  'vehicle.mercedes.coupe',
  'vehicle.mercedes.coupe_2020',
  'vehicle.mercedes.sprinter',
  'vehicle.micro.microlino',
  'vehicle.mini.cooper_s',
  'vehicle.mini.cooper_s_2021',
  'vehicle.mitsubishi.fusorosa',
  'vehicle.nissan.micra',
  'vehicle.nissan.patrol',
  'vehicle.nissan.patrol_2021',
  'vehicle.seat.leon',
  'vehicle.sixwheeltruck.sixwheeltruck',
  'vehicle.tesla.cybertruck',
  'vehicle.tesla.model3',
  'vehicle.toyota.prius',
  'vehicle.vespa.zx125',
  'vehicle.volkswagen.t2',
  'vehicle.volkswagen.t2_2021',
  'vehicle.yamaha.yzf',
];

/** `walker.pedestrian.0001` to `0049`: CARLA's walkers (carla-simulator/carla `Docs/catalogue_pedestrians.md`). */
export const CARLA_WALKER_BLUEPRINTS: readonly string[] = Array.from(
  { length: 49 },
  (_, index) => `walker.pedestrian.${String(index + 1).padStart(4, '0')}`,
);

/** Why a blueprint table's entry will not do (`name` mapped to what CARLA has no blueprint of, with the closest it has), or undefined. */
export function unknownBlueprintProblem(name: string, blueprint: string): string | undefined {
  if (isCarlaBlueprint(blueprint)) return undefined;
  const closest = closestMatch(blueprint, [...CARLA_VEHICLE_BLUEPRINTS, ...CARLA_WALKER_BLUEPRINTS]);
  return (
    `the blueprint table maps '${name}' to '${blueprint}', which is no CARLA 0.9.15/0.9.16 blueprint (vehicle.*, walker.pedestrian.0001-0049 or static.prop.*)` +
    (closest ? `; did you mean '${closest}'?` : '')
  );
}

/** Whether CARLA has the blueprint; `static.prop.*` props are many and taken as they are written. */
export function isCarlaBlueprint(name: string): boolean {
  return CARLA_VEHICLE_BLUEPRINTS.includes(name) || CARLA_WALKER_BLUEPRINTS.includes(name) || /^static\.prop\.[a-z0-9_]+$/.test(name);
}

/**
 * The blueprint given to a vehicle whose name is no CARLA blueprint, by its `vehicleCategory`: the export's
 * choice, so that the file spawns what its category says (ScenarioRunner would pick `vehicle.*` at random
 * among the category's blueprints, `CarlaDataProvider.create_blueprint`). The user overrides it by name.
 */
export const DEFAULT_VEHICLE_BLUEPRINTS: Readonly<Record<string, string>> = {
  car: 'vehicle.tesla.model3',
  van: 'vehicle.mercedes.sprinter',
  truck: 'vehicle.carlamotors.carlacola',
  trailer: 'vehicle.carlamotors.carlacola',
  semitrailer: 'vehicle.carlamotors.carlacola',
  bus: 'vehicle.mitsubishi.fusorosa',
  motorbike: 'vehicle.yamaha.yzf',
  bicycle: 'vehicle.diamondback.century',
  train: 'vehicle.carlamotors.carlacola',
  tram: 'vehicle.mitsubishi.fusorosa',
};

export const DEFAULT_WALKER_BLUEPRINT = 'walker.pedestrian.0001';
