import { fileHeader, openScenarioFile, roadScenario } from './fixtures';

const vehicle = (name: string, maxSpeed: string) =>
  `<Vehicle name="${name}" vehicleCategory="car"><BoundingBox><Center x="1.4" y="0" z="0.9"/><Dimensions width="2" length="4.5" height="1.5"/></BoundingBox><Performance maxSpeed="${maxSpeed}" maxAcceleration="5" maxDeceleration="9"/><Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3" positionZ="0.3"/><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.8" positionX="0" positionZ="0.3"/></Axles><Properties/></Vehicle>`;

/** A catalog file holding a Catalog named VehicleCatalog with `vehicles`. */
const vehicleCatalog = (...vehicles: string[]) =>
  openScenarioFile(`  <Catalog name="VehicleCatalog">${vehicles.join('')}</Catalog>\n`, fileHeader());

/**
 * scenario.xosc and two folders beside it, first/ and second/, written as the Directory of two kinds (esmini searches
 * every catalog directory for any catalog name). second/VehicleCatalog.xosc holds car_blue (maxSpeed 70) and car_red;
 * first/`firstFile` (VehicleCatalog.xosc unless given) a Catalog also named VehicleCatalog holding car_blue (maxSpeed 50).
 * Ego is `entry`, on the road straight.xodr (not written), and each of `others` an object of its own. Ends after 1 s.
 */
export function twoCatalogs(entry: string, firstFile = 'VehicleCatalog.xosc', others: string[] = []): Record<string, string> {
  const scenario = roadScenario({
    logicFile: 'straight.xodr',
    init: `<Private entityRef="Ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="0" laneId="-1" s="20" offset="0"/></Position></TeleportAction></PrivateAction></Private>`,
    groups: [],
  })
    .replace(
      '<CatalogLocations/>',
      '<CatalogLocations><VehicleCatalog><Directory path="first"/></VehicleCatalog><ControllerCatalog><Directory path="second"/></ControllerCatalog></CatalogLocations>',
    )
    .replace(
      /<ScenarioObject name="Ego">.*<\/ScenarioObject>/,
      [entry, ...others]
        .map(
          (name, index) =>
            `<ScenarioObject name="${index === 0 ? 'Ego' : `Other${index}`}"><CatalogReference catalogName="VehicleCatalog" entryName="${name}"/></ScenarioObject>`,
        )
        .join(''),
    )
    .replace(
      /<StopTrigger\/>(\s*<\/Storyboard>)/,
      '<StopTrigger><ConditionGroup><Condition name="end" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>$1',
    );
  return {
    'scenario.xosc': scenario,
    [`first/${firstFile}`]: vehicleCatalog(vehicle('car_blue', '50')),
    'second/VehicleCatalog.xosc': vehicleCatalog(vehicle('car_blue', '70'), vehicle('car_red', '70')),
  };
}
