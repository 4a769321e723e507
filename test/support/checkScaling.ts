/**
 * A schema-valid OpenSCENARIO 1.3 scenario in which every check has work that grows with `size`, with its
 * road and catalog files: `size` siblings of each kind a check walks (catalog references, Init actions,
 * events whose conditions name the previous event, maneuver groups), ten times as many of the kinds
 * written on one line (parameters with constraints and expressions, variables, traffic signal phases and
 * actions, a vehicle's Properties and Files).
 */
export function checkScalingFiles(size: number): Record<string, string> {
  const times = (make: (i: number) => string, count = size): string => Array.from({ length: count }, (_, i) => make(i)).join('\n');
  // Elements of a line each are cheap to hold: ten times as many, so that a check quadratic in them shows.
  const many = 10 * size;
  const speed = (value: string) =>
    `<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="${value}"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>`;
  const vehicle = (name: string, maxSpeed: string, properties = '') =>
    `<Vehicle name="${name}" vehicleCategory="car"><BoundingBox><Center x="1.4" y="0" z="0.9"/><Dimensions width="2" length="4.5" height="1.5"/></BoundingBox><Performance maxSpeed="${maxSpeed}" maxAcceleration="5" maxDeceleration="9"/><Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3" positionZ="0.3"/><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.8" positionX="0" positionZ="0.3"/></Axles><Properties>${properties}</Properties></Vehicle>`;
  const scenario = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2026-01-01T00:00:00" description="scaling" author="test"/>
  <ParameterDeclarations>
${times((i) => `    <ParameterDeclaration name="Speed${i}" parameterType="double" value="${10 + (i % 20)}"><ConstraintGroup><ValueConstraint rule="greaterOrEqual" value="0"/></ConstraintGroup></ParameterDeclaration>`, many)}
${times((i) => `    <ParameterDeclaration name="Gap${i}" parameterType="double" value="\${$Speed${i} * 2 + 1}"/>`, many)}
  </ParameterDeclarations>
  <VariableDeclarations>
${times((i) => `    <VariableDeclaration name="Count${i}" variableType="int" value="0"/>`, many)}
  </VariableDeclarations>
  <CatalogLocations><VehicleCatalog><Directory path="catalogs"/></VehicleCatalog></CatalogLocations>
  <RoadNetwork>
    <LogicFile filepath="road.xodr"/>
    <TrafficSignals><TrafficSignalController name="Lights">
${times((i) => `      <Phase name="Phase${i}" duration="2"><TrafficSignalState trafficSignalId="101" state="on;off;off"/></Phase>`, many)}
    </TrafficSignalController></TrafficSignals>
  </RoadNetwork>
  <Entities>
    <ScenarioObject name="Ego">${vehicle('ego', '50', times((i) => `<Property name="key${i}" value="v"/>`, many) + '\n' + times(() => '<File filepath=""/>', many))}</ScenarioObject>
${times((i) => `    <ScenarioObject name="Car${i}"><CatalogReference catalogName="VehicleCatalog" entryName="car"><ParameterAssignments><ParameterAssignment parameterRef="MaxSpeed" value="$Speed${i}"/></ParameterAssignments></CatalogReference></ScenarioObject>`)}
  </Entities>
  <Storyboard>
    <Init><Actions>
${times((i) => `      <GlobalAction><VariableAction variableRef="Count${i}"><SetAction value="${i}"/></VariableAction></GlobalAction>`, many)}
${times(() => `      <GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="101" state="off;off;on"/></TrafficSignalAction></InfrastructureAction></GlobalAction>`, many)}
      <Private entityRef="Ego">${speed('10')}</Private>
${times((i) => `      <Private entityRef="Car${i}"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="\${$Gap${i} + 10}" offset="0"/></Position></TeleportAction></PrivateAction>${speed(`$Speed${i}`)}<PrivateAction><AppearanceAction><LightStateAction transitionTime="0.5"><LightType><VehicleLight vehicleLightType="lowBeam"/></LightType><LightState mode="on"/></LightStateAction></AppearanceAction></PrivateAction></Private>`)}
    </Actions></Init>
    <Story name="Story">
      <Act name="Act">
        <ManeuverGroup name="Ego" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
          <Maneuver name="Events">
${times((i) => `            <Event name="E${i}" priority="override"><Action name="Go${i}">${speed(`\${$Speed${i} + 1}`)}</Action><StartTrigger><ConditionGroup><Condition name="After${i}" delay="0" conditionEdge="rising"><ByValueCondition><StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="E${Math.max(0, i - 1)}" state="endTransition"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>`)}
          </Maneuver>
        </ManeuverGroup>
${times((i) => `        <ManeuverGroup name="Group${i}" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Car${i}"/></Actors><Maneuver name="Brake"><Event name="Brake" priority="override"><Action name="Brake">${speed('0')}</Action><StartTrigger><ConditionGroup><Condition name="Late" delay="0" conditionEdge="rising"><ByValueCondition><SimulationTimeCondition value="${i % 30}" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>`)}
        <StartTrigger><ConditionGroup><Condition name="Start" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
      </Act>
    </Story>
    <StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="rising"><ByValueCondition><SimulationTimeCondition value="30" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
  </Storyboard>
</OpenSCENARIO>
`;
  const catalog = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2026-01-01T00:00:00" description="vehicles" author="test"/>
  <Catalog name="VehicleCatalog">
    ${vehicle('car', '$MaxSpeed').replace('<BoundingBox>', '<ParameterDeclarations><ParameterDeclaration name="MaxSpeed" parameterType="double" value="50"/></ParameterDeclarations><BoundingBox>')}
  </Catalog>
</OpenSCENARIO>
`;
  const road = `<?xml version="1.0" encoding="UTF-8"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6" name="straight"/>
  <road name="straight" length="500" id="1" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="500"><line/></geometry></planView>
    <lanes><laneSection s="0">
      <center><lane id="0" type="driving" level="false"/></center>
      <right><lane id="-1" type="driving" level="false"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
    <signals><signal id="101" s="50" t="-3"/></signals>
  </road>
</OpenDRIVE>
`;
  return { 'main.xosc': scenario, 'catalogs/VehicleCatalog.xosc': catalog, 'road.xodr': road };
}
