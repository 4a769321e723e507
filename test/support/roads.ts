/** A straight road along x from (0, 0), 200 m, lanes 1 and -1 (3.5 m driving) and -2 (2 m sidewalk): the project's own small road fixture. */
export const STRAIGHT_ROAD = `<?xml version="1.0" encoding="UTF-8"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6" name="straight"/>
  <road name="straight" length="200" id="1" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
    <lanes>
      <laneSection s="0">
        <left><lane id="1" type="driving" level="false"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
        <center><lane id="0" type="driving" level="false"/></center>
        <right>
          <lane id="-1" type="driving" level="false"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
          <lane id="-2" type="sidewalk" level="false"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane>
        </right>
      </laneSection>
    </lanes>
  </road>
</OpenDRIVE>
`;

/** A scenario on `roadFile` with the given Init Privates and Story body. */
export function sceneScenario(roadFile: string, init: string, story = '', parameters = ''): string {
  return `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-01-01T00:00:00" description="scene" author="test"/>
  <ParameterDeclarations>${parameters}</ParameterDeclarations>
  <RoadNetwork><LogicFile filepath="${roadFile}"/></RoadNetwork>
  <Entities>
    <ScenarioObject name="ego"><Vehicle name="car" vehicleCategory="car"><BoundingBox><Center x="1.5" y="0" z="0.9"/><Dimensions width="2" length="5" height="1.8"/></BoundingBox></Vehicle></ScenarioObject>
    <ScenarioObject name="other"><CatalogReference catalogName="VehicleCatalog" entryName="car_red"/></ScenarioObject>
    <ScenarioObject name="third"><Vehicle name="car" vehicleCategory="car"/></ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions>${init}</Actions></Init>
    ${story}
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
}

export function teleport(entity: string, position: string): string {
  return `<Private entityRef="${entity}"><PrivateAction><TeleportAction><Position>${position}</Position></TeleportAction></PrivateAction></Private>`;
}

/** A road file with one road and signal 101 on it. */
export const SIGNAL_ROAD = `<?xml version="1.0"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6"/>
  <road id="1" length="100" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
    <lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes>
    <signals><signal id="101" s="50" t="-3"/></signals>
  </road>
</OpenDRIVE>
`;
