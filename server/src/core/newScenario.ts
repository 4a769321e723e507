import { isDrivingLane, Lane, laneWidth, Road, RoadNetwork } from './opendrive/road';
import { SchemaVersion } from './schema/model';
import { escapeAttributeValue } from './xml';

/** Where the new scenario places its ego: a lane position that exists on the road network. */
export interface EgoPlacement {
  roadId: string;
  laneId: number;
  s: number;
}

/** Narrower than this, a lane is only starting or ending at `s` (a widening), no place for a car. */
const MIN_LANE_WIDTH = 1;

/** Right-hand lanes first, nearest the centre first (esmini's default driving side), then the left ones. */
function byPreference(a: Lane, b: Lane): number {
  if (Math.sign(a.id) !== Math.sign(b.id)) return a.id < 0 ? -1 : 1;
  return Math.abs(a.id) - Math.abs(b.id);
}

function placementOn(road: Road): EgoPlacement | undefined {
  for (const section of road.laneSections) {
    if (section.length <= 0) continue;
    // A little way into the section (at most 10 m), so the car stands wholly on it where it can.
    const s = Math.round((section.s + Math.min(10, section.length / 2)) * 100) / 100;
    const lane = section.lanes
      .filter(isDrivingLane)
      .sort(byPreference)
      .find((candidate) => laneWidth(section, candidate, s) >= MIN_LANE_WIDTH);
    if (lane) return { roadId: road.id, laneId: lane.id, s };
  }
  return undefined;
}

/** The first road (outside junctions if there is one) with a driving lane: the lane nearest its centre on the right, a little way in. */
export function egoPlacement(network: RoadNetwork): EgoPlacement | undefined {
  const outside = network.roads.filter((road) => road.junction === '-1');
  const inside = network.roads.filter((road) => road.junction !== '-1');
  for (const road of [...outside, ...inside]) {
    const placement = placementOn(road);
    if (placement) return placement;
  }
  return undefined;
}

export interface NewScenarioOptions {
  version: SchemaVersion;
  /** The road network's path as the scenario writes it (relative to the scenario's folder, `/`-separated). */
  roadFile: string;
  ego: EgoPlacement;
  now?: Date;
}

/**
 * A main scenario to build on: the road network, an ego (a Vehicle written out, no catalog needed)
 * on a lane that exists, driving at a steady speed, and one Story/Act whose ManeuverGroup is where
 * `ScenarioReference`s go; it stops after 20 s. Valid against the schema of every 1.x version.
 */
export function newMainScenario(options: NewScenarioOptions): string {
  const [revMajor, revMinor] = options.version.split('.');
  const date = (options.now ?? new Date()).toISOString().replace(/\.\d{3}Z$/, '');
  const { roadId, laneId, s } = options.ego;
  return `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
\t<FileHeader revMajor="${revMajor}" revMinor="${revMinor}" date="${date}" description="A new modular scenario" author=""/>
\t<ParameterDeclarations>
\t\t<ParameterDeclaration name="EgoSpeed" parameterType="double" value="10"/>
\t</ParameterDeclarations>
\t<CatalogLocations/>
\t<RoadNetwork>
\t\t<LogicFile filepath="${escapeAttributeValue(options.roadFile)}"/>
\t</RoadNetwork>
\t<Entities>
\t\t<ScenarioObject name="Ego">
\t\t\t<Vehicle name="car" vehicleCategory="car">
\t\t\t\t<BoundingBox>
\t\t\t\t\t<Center x="1.4" y="0" z="0.75"/>
\t\t\t\t\t<Dimensions width="2" length="5" height="1.5"/>
\t\t\t\t</BoundingBox>
\t\t\t\t<Performance maxSpeed="70" maxAcceleration="10" maxDeceleration="10"/>
\t\t\t\t<Axles>
\t\t\t\t\t<FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="2.98" positionZ="0.4"/>
\t\t\t\t\t<RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/>
\t\t\t\t</Axles>
\t\t\t\t<Properties/>
\t\t\t</Vehicle>
\t\t</ScenarioObject>
\t</Entities>
\t<Storyboard>
\t\t<Init>
\t\t\t<Actions>
\t\t\t\t<Private entityRef="Ego">
\t\t\t\t\t<PrivateAction>
\t\t\t\t\t\t<TeleportAction>
\t\t\t\t\t\t\t<Position>
\t\t\t\t\t\t\t\t<LanePosition roadId="${escapeAttributeValue(roadId)}" laneId="${laneId}" s="${s}" offset="0"/>
\t\t\t\t\t\t\t</Position>
\t\t\t\t\t\t</TeleportAction>
\t\t\t\t\t</PrivateAction>
\t\t\t\t\t<PrivateAction>
\t\t\t\t\t\t<LongitudinalAction>
\t\t\t\t\t\t\t<SpeedAction>
\t\t\t\t\t\t\t\t<SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
\t\t\t\t\t\t\t\t<SpeedActionTarget>
\t\t\t\t\t\t\t\t\t<AbsoluteTargetSpeed value="$EgoSpeed"/>
\t\t\t\t\t\t\t\t</SpeedActionTarget>
\t\t\t\t\t\t\t</SpeedAction>
\t\t\t\t\t\t</LongitudinalAction>
\t\t\t\t\t</PrivateAction>
\t\t\t\t</Private>
\t\t\t</Actions>
\t\t</Init>
\t\t<Story name="Story">
\t\t\t<Act name="Act">
\t\t\t\t<ManeuverGroup name="EgoBehaviour" maximumExecutionCount="1">
\t\t\t\t\t<Actors selectTriggeringEntities="false">
\t\t\t\t\t\t<EntityRef entityRef="Ego"/>
\t\t\t\t\t</Actors>
\t\t\t\t\t<!-- Import behaviours here: type < for a ScenarioReference. -->
\t\t\t\t</ManeuverGroup>
\t\t\t\t<StartTrigger>
\t\t\t\t\t<ConditionGroup>
\t\t\t\t\t\t<Condition name="ActStart" delay="0" conditionEdge="none">
\t\t\t\t\t\t\t<ByValueCondition>
\t\t\t\t\t\t\t\t<SimulationTimeCondition value="0" rule="greaterThan"/>
\t\t\t\t\t\t\t</ByValueCondition>
\t\t\t\t\t\t</Condition>
\t\t\t\t\t</ConditionGroup>
\t\t\t\t</StartTrigger>
\t\t\t</Act>
\t\t</Story>
\t\t<StopTrigger>
\t\t\t<ConditionGroup>
\t\t\t\t<Condition name="End" delay="0" conditionEdge="rising">
\t\t\t\t\t<ByValueCondition>
\t\t\t\t\t\t<SimulationTimeCondition value="20" rule="greaterThan"/>
\t\t\t\t\t</ByValueCondition>
\t\t\t\t</Condition>
\t\t\t</ConditionGroup>
\t\t</StopTrigger>
\t</Storyboard>
</OpenSCENARIO>
`;
}
