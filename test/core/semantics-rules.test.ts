import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../server/src/core/semantics';
import { schemaProblems } from '../../server/src/core/diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { temporaryWorkspace } from '../support/workspace';

/** Issue 18's rules about names, references, parameters and variables: each broken once, at its element, and kept once. */

const HEADER = '<FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="rules" author="t"/>';

function scenario(body: string, head = ''): string {
  return `<?xml version="1.0"?>
<OpenSCENARIO>
  ${HEADER}
  ${head}
  <Entities>
    <ScenarioObject name="Ego"><Vehicle name="car" vehicleCategory="car"/></ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
          <Maneuver name="M">
${body}
          </Maneuver>
        </ManeuverGroup>
      </Act>
    </Story>
  </Storyboard>
</OpenSCENARIO>
`;
}

function event(name: string, action = '<UserDefinedAction><CustomCommandAction type="t"/></UserDefinedAction>'): string {
  return `            <Event name="${name}" priority="override"><Action name="${name}Action">${action}</Action></Event>`;
}

/** `code:severity:text` of every problem found, `text` being what its range covers. */
async function problemsOf(text: string, files: Record<string, string> = {}, name = 'scenario.xosc'): Promise<string[]> {
  const root = temporaryWorkspace({ ...files, [name]: text });
  const store = new ScenarioStore({ scenarioPath: [], root });
  const semantics = await analyzeDocument(diskRef(path.join(root, name)), parseXml(text), new CatalogLoader(store), false);
  const lines = text.split('\n');
  return (
    semanticProblems(semantics)
      // esmini's reading of unsigned types differs (simulator-value), which is not these rules' business.
      .filter((problem) => problem.severity !== 'hint' && problem.code !== 'simulator-value')
      .map(
        (problem) =>
          `${problem.code}:${problem.severity}:${lines[problem.range.start.line].slice(problem.range.start.character, problem.range.end.character)}`,
      )
  );
}

async function messagesOf(text: string, code: string, files: Record<string, string> = {}, name = 'scenario.xosc'): Promise<string[]> {
  const root = temporaryWorkspace({ ...files, [name]: text });
  const store = new ScenarioStore({ scenarioPath: [], root });
  const semantics = await analyzeDocument(diskRef(path.join(root, name)), parseXml(text), new CatalogLoader(store), false);
  return semanticProblems(semantics)
    .filter((problem) => problem.code === code)
    .map((problem) => problem.message);
}

describe('rules: names unique on each level (ASAM QC reference_control.unique_element_names_on_same_level)', () => {
  it('finds the second of two Events named alike in one Maneuver, at its name: a warning while nothing refers to the name (esmini runs both), an error once a reference does (SPEC 12)', async () => {
    const found = await problemsOf(scenario(`${event('Event1')}\n${event('Event1')}`));
    assert.deepEqual(found, ['duplicate-name:warning:Event1']);
    const condition =
      '<StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="Event1" state="endTransition"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>';
    const referenced = scenario(`${event('Event1')}\n${event('Event1')}\n${event('Later').replace('</Action>', `</Action>${condition}`)}`);
    assert.deepEqual(await problemsOf(referenced), ['duplicate-name:error:Event1']);
  });

  it('compares names as their parameters evaluate, and finds two entities of one name', async () => {
    const text = scenario(
      event('E1'),
      '<ParameterDeclarations><ParameterDeclaration name="Other" parameterType="string" value="Ego"/></ParameterDeclarations>',
    ).replace(
      '</ScenarioObject>',
      '</ScenarioObject>\n    <ScenarioObject name="$Other"><Vehicle name="car" vehicleCategory="car"/></ScenarioObject>',
    );
    assert.deepEqual(await problemsOf(text), ['duplicate-name:error:$Other']);
  });

  it('is a warning with simulator esmini, which runs both', async () => {
    const text = scenario(`${event('Event1')}\n${event('Event1')}`);
    const semantics = await analyzeDocument(
      diskRef('/virtual/names.xosc'),
      parseXml(text),
      new CatalogLoader(new ScenarioStore()),
      false,
      'esmini',
    );
    assert.deepEqual(
      semanticProblems(semantics)
        .filter((problem) => problem.code === 'duplicate-name')
        .map((problem) => problem.severity),
      ['warning'],
    );
  });

  it('finds two ManeuverGroups of one name where a condition names them, and leaves them alone otherwise (SPEC: a duplicate nothing refers to harms nobody)', async () => {
    const group = (name: string) =>
      `<ManeuverGroup name="${name}" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"/></ManeuverGroup>`;
    const twice = scenario(event('E')).replace('</Act>', `${group('Twin')}\n${group('Twin')}</Act>`);
    assert.deepEqual(await problemsOf(twice), []);
    const condition =
      '<StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><StoryboardElementStateCondition storyboardElementType="maneuverGroup" storyboardElementRef="Twin" state="endTransition"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>';
    const referenced = twice.replace(
      '<Event name="E" priority="override"><Action name="EAction"><UserDefinedAction><CustomCommandAction type="t"/></UserDefinedAction></Action>',
      `<Event name="E" priority="override"><Action name="EAction"><UserDefinedAction><CustomCommandAction type="t"/></UserDefinedAction></Action>${condition}`,
    );
    assert.deepEqual(await problemsOf(referenced), ['duplicate-name:error:Twin']);
  });

  it('accepts the same name on different levels and in different parents', async () => {
    assert.deepEqual(await problemsOf(scenario(`${event('M')}\n${event('Event2')}`)), []);
  });
});

const CATALOG_HEAD = `<?xml version="1.0"?>
<OpenSCENARIO>
  ${HEADER}
  <Catalog name="VehicleCatalog">`;

describe('rules: catalog entries resolve uniquely (ASAM QC reference_control.uniquely_resolvable_entity_references)', () => {
  it('finds the second of two Vehicles named car_white in one catalog', async () => {
    const text = `${CATALOG_HEAD}
    <Vehicle name="car_white" vehicleCategory="car"/>
    <Vehicle name="car_white" vehicleCategory="car"/>
  </Catalog>
</OpenSCENARIO>
`;
    assert.deepEqual(await problemsOf(text, {}, 'VehicleCatalog.xosc'), ['duplicate-catalog-entry:error:car_white']);
  });

  it('accepts entries of distinct names', async () => {
    const text = `${CATALOG_HEAD}
    <Vehicle name="car_white" vehicleCategory="car"/>
    <Vehicle name="car_red" vehicleCategory="car"/>
  </Catalog>
</OpenSCENARIO>
`;
    assert.deepEqual(await problemsOf(text, {}, 'VehicleCatalog.xosc'), []);
  });
});

describe('rules: a catalog entry declares its parameters (ASAM QC parameters.valid_parameter_declaration_in_catalogs)', () => {
  it('is an error at the use of an undeclared parameter', async () => {
    const text = `${CATALOG_HEAD}
    <Vehicle name="car" vehicleCategory="car" mass="$Mass"/>
  </Catalog>
</OpenSCENARIO>
`;
    assert.deepEqual(await problemsOf(text, {}, 'VehicleCatalog.xosc'), ['undeclared-catalog-parameter:error:$Mass']);
  });

  it('accepts a parameter the entry declares', async () => {
    const text = `${CATALOG_HEAD}
    <Vehicle name="car" vehicleCategory="car" mass="$Mass">
      <ParameterDeclarations><ParameterDeclaration name="Mass" parameterType="double" value="1000"/></ParameterDeclarations>
    </Vehicle>
  </Catalog>
</OpenSCENARIO>
`;
    assert.deepEqual(await problemsOf(text, {}, 'VehicleCatalog.xosc'), []);
  });
});

function constrained(type: string, value: string, groups: string[][]): string {
  const written = groups
    .map(
      (group) =>
        `<ConstraintGroup>${group.map((constraint) => `<ValueConstraint rule="${constraint.split(' ')[0]}" value="${constraint.split(' ').slice(1).join(' ')}"/>`).join('')}</ConstraintGroup>`,
    )
    .join('');
  return scenario(
    event('E', `<UserDefinedAction><CustomCommandAction type="$P"/></UserDefinedAction>`),
    `<ParameterDeclarations><ParameterDeclaration name="P" parameterType="${type}" value="${value}">${written}</ParameterDeclaration></ParameterDeclarations>`,
  );
}

describe('rules: ValueConstraintGroups', () => {
  const cases: { type: string; groups: string[][]; breaking: string; keeping: string }[] = [
    { type: 'double', groups: [['greaterOrEqual 0', 'lessThan 10.5']], breaking: '10.5', keeping: '0' },
    { type: 'double', groups: [['greaterThan 0', 'lessOrEqual 1']], breaking: '0', keeping: '1' },
    { type: 'int', groups: [['equalTo 3'], ['equalTo 5']], breaking: '4', keeping: '5' },
    { type: 'unsignedInt', groups: [['notEqualTo 7']], breaking: '7', keeping: '8' },
    { type: 'unsignedShort', groups: [['lessOrEqual 100']], breaking: '101', keeping: '100' },
    { type: 'string', groups: [['equalTo fast'], ['equalTo slow']], breaking: 'medium', keeping: 'slow' },
    { type: 'string', groups: [['notEqualTo none']], breaking: 'none', keeping: 'some' },
    { type: 'boolean', groups: [['equalTo true']], breaking: 'false', keeping: 'true' },
    { type: 'boolean', groups: [['notEqualTo false']], breaking: 'false', keeping: 'true' },
    {
      type: 'dateTime',
      groups: [['greaterThan 2020-01-01T00:00:00', 'lessThan 2021-01-01T00:00:00']],
      breaking: '2021-06-01T12:00:00',
      keeping: '2020-06-01T12:00:00',
    },
  ];
  for (const { type, groups, breaking, keeping } of cases) {
    it(`${type} ${groups.map((group) => group.join(' and ')).join(' or ')}: ${breaking} breaks it at the value, ${keeping} keeps it`, async () => {
      assert.deepEqual(await problemsOf(constrained(type, breaking, groups)), [`value-constraint:error:${breaking}`]);
      assert.deepEqual(await problemsOf(constrained(type, keeping, groups)), []);
    });
  }

  it('names the broken constraint in the message', async () => {
    const [message] = await messagesOf(constrained('double', '12', [['lessThan 10']]), 'value-constraint');
    assert.equal(message, "the value 12 of parameter 'P' breaks its ConstraintGroup: it is not < 10");
  });

  it('finds a rule that does not apply to a string, and a constraint value that is not of the type', async () => {
    assert.deepEqual(await problemsOf(constrained('string', 'a', [['lessThan b']])), ['value-constraint:error:lessThan']);
    assert.deepEqual(await problemsOf(constrained('int', '1', [['lessThan ten']])), ['value-constraint:error:ten']);
  });

  it("checks a value a CatalogReference assigns against the entry parameter's constraints, at the assignment", async () => {
    const catalog = `${CATALOG_HEAD}
    <Vehicle name="car" vehicleCategory="car" mass="$Mass">
      <ParameterDeclarations><ParameterDeclaration name="Mass" parameterType="double" value="1000"><ConstraintGroup><ValueConstraint rule="greaterThan" value="0"/></ConstraintGroup></ParameterDeclaration></ParameterDeclarations>
    </Vehicle>
  </Catalog>
</OpenSCENARIO>
`;
    const reference = (mass: string) =>
      scenario(event('E'), '<CatalogLocations><VehicleCatalog><Directory path="catalogs"/></VehicleCatalog></CatalogLocations>').replace(
        '<Vehicle name="car" vehicleCategory="car"/>',
        `<CatalogReference catalogName="VehicleCatalog" entryName="car"><ParameterAssignments><ParameterAssignment parameterRef="Mass" value="${mass}"/></ParameterAssignments></CatalogReference>`,
      );
    assert.deepEqual(await problemsOf(reference('-5'), { 'catalogs/VehicleCatalog.xosc': catalog }), ['value-constraint:error:-5']);
    assert.deepEqual(await problemsOf(reference('5'), { 'catalogs/VehicleCatalog.xosc': catalog }), []);
  });
});

const VARIABLES =
  '<VariableDeclarations><VariableDeclaration name="Flag" variableType="boolean" value="false"/><VariableDeclaration name="Count" variableType="int" value="0"/></VariableDeclarations>';

function variableAction(inner: string, variable = 'Flag'): string {
  return event('E', `<GlobalAction><VariableAction variableRef="${variable}">${inner}</VariableAction></GlobalAction>`);
}

describe('rules: values given to variables', () => {
  it("a SetAction value that is not of the variable's type, at the value", async () => {
    assert.deepEqual(await problemsOf(scenario(variableAction('<SetAction value="wrongBoolean"/>'), VARIABLES)), [
      'type-mismatch:error:wrongBoolean',
    ]);
    assert.deepEqual(await problemsOf(scenario(variableAction('<SetAction value="true"/>'), VARIABLES)), []);
  });

  it('a ModifyAction on a boolean, at the ModifyAction', async () => {
    const modify = '<ModifyAction><Rule><AddValue value="1"/></Rule></ModifyAction>';
    assert.deepEqual(await problemsOf(scenario(variableAction(modify), VARIABLES)), ['type-mismatch:error:<ModifyAction']);
    assert.deepEqual(await problemsOf(scenario(variableAction(modify, 'Count'), VARIABLES)), []);
  });

  it("accepts a variableRef that names a parameter, as ASAM's checker does", async () => {
    const head = `${VARIABLES}`.replace(
      '<VariableDeclarations>',
      '<ParameterDeclarations><ParameterDeclaration name="Limit" parameterType="int" value="3"/></ParameterDeclarations><VariableDeclarations>',
    );
    assert.deepEqual(await problemsOf(scenario(variableAction('<SetAction value="4"/>', 'Limit'), head)), []);
    assert.deepEqual(await problemsOf(scenario(variableAction('<SetAction value="4"/>', 'Limt'), head)), [
      'undeclared-variable:error:Limt',
    ]);
  });
});

describe('rules: variables used in a catalog entry', () => {
  const catalog = `<?xml version="1.0"?>
<OpenSCENARIO>
  ${HEADER}
  <Catalog name="ManeuverCatalog">
    <Maneuver name="Flip">
${variableAction('<SetAction value="true"/>')}
    </Maneuver>
  </Catalog>
</OpenSCENARIO>
`;
  const referencing = (head: string) =>
    scenario('', `<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>${head}`)
      .replace('<Maneuver name="M">', '<CatalogReference catalogName="ManeuverCatalog" entryName="Flip"/>')
      .replace('</Maneuver>\n        </ManeuverGroup>', '</ManeuverGroup>');

  it('is no error in the catalog, but a note that the referencing scenarios declare it', async () => {
    assert.deepEqual(await problemsOf(catalog, {}, 'ManeuverCatalog.xosc'), ['undeclared-variable:information:Flag']);
  });

  it('is an error at the CatalogReference of a scenario that does not declare it, none in one that does', async () => {
    const files = { 'catalogs/ManeuverCatalog.xosc': catalog };
    assert.deepEqual(await problemsOf(referencing(''), files), ['undeclared-variable:error:Flip']);
    assert.deepEqual(await problemsOf(referencing(VARIABLES), files), []);
  });
});

describe('rules: a parameter value against the type that uses it', () => {
  const head =
    '<ParameterDeclarations><ParameterDeclaration name="testDouble" parameterType="string" value="RRR1.1"/><ParameterDeclaration name="Speed" parameterType="double" value="1"/></ParameterDeclarations>';
  it("a ParameterAction SetAction value that the parameter's type cannot take, at the value", async () => {
    const set = (value: string) =>
      scenario(
        event('E', `<GlobalAction><ParameterAction parameterRef="Speed"><SetAction value="${value}"/></ParameterAction></GlobalAction>`),
        head,
      );
    assert.deepEqual(await problemsOf(set('$testDouble')), ['type-mismatch:error:$testDouble']);
    assert.deepEqual(await problemsOf(set('2.5')), []);
  });
});

describe('rules: deprecated elements, attributes and values are warnings naming the replacement (both official checkers)', () => {
  const deprecatedOf = (text: string) =>
    schemaProblems(diskRef('/virtual/deprecated.xosc'), parseXml(text), new SchemaCheckMemory())
      .filter((problem) => problem.code === 'schema-deprecated')
      .map((problem) => `${problem.severity}: ${problem.message}`);
  const weather = (attributes: string) =>
    scenario(
      event(
        'E',
        `<GlobalAction><EnvironmentAction><Environment name="env"><TimeOfDay animation="false" dateTime="2026-01-01T12:00:00"/><Weather ${attributes}/><RoadCondition frictionScaleFactor="1"/></Environment></EnvironmentAction></GlobalAction>`,
      ),
    );

  it('a deprecated attribute: a warning that names what to write instead', () => {
    assert.deepEqual(deprecatedOf(weather('cloudState="free"')), [
      'warning: Weather.cloudState is deprecated since OpenSCENARIO 1.2; write fractionalCloudCover instead',
    ]);
  });

  it('a deprecated attribute written together with its replacement: a warning naming both', () => {
    assert.deepEqual(deprecatedOf(weather('cloudState="free" fractionalCloudCover="zeroOktas"')), [
      'warning: Weather.cloudState is deprecated since OpenSCENARIO 1.2 and written together with its replacement fractionalCloudCover: leave out cloudState',
    ]);
  });

  // esmini15's finding: leaving velocity out, as 'leave out velocity' said, makes a file esmini refuses (ScenarioReader.cpp:2466-2467).
  it('TrafficSwarmAction velocity, deprecated: the advice keeps it for esmini, which refuses the action without it, and says why', () => {
    const swarm = (speedRange: string, velocity = ' velocity="10"') =>
      scenario(
        event(
          'E',
          `<GlobalAction><TrafficAction><TrafficSwarmAction innerRadius="10" semiMajorAxis="100" semiMinorAxis="50" numberOfVehicles="2" offset="0"${velocity}><CentralObject entityRef="Ego"/>${speedRange}</TrafficSwarmAction></TrafficAction></GlobalAction>`,
        ),
      );
    const esmini =
      'keep velocity while the scenario runs in esmini, which reads velocity alone and refuses the action without it (it reads velocity with std::stod, which stops it when the attribute is absent ("Exception: stod"); the standard makes it optional (deprecated from 1.2 on); EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:2466-2467)';
    assert.deepEqual(deprecatedOf(swarm('<InitialSpeedRange lowerLimit="5" upperLimit="15"/>')), [
      `warning: TrafficSwarmAction.velocity is deprecated since OpenSCENARIO 1.2 and written together with its replacement <InitialSpeedRange>: ${esmini}; leave it out only for a simulator that reads <InitialSpeedRange>`,
    ]);
    assert.deepEqual(deprecatedOf(swarm('')), [
      `warning: TrafficSwarmAction.velocity is deprecated since OpenSCENARIO 1.2; write <InitialSpeedRange> as well, and ${esmini}`,
    ]);
    assert.deepEqual(deprecatedOf(swarm('<InitialSpeedRange lowerLimit="5" upperLimit="15"/>', '')), []);
  });

  it('a deprecated value and a deprecated element', () => {
    const text = scenario(event('E')).replace('priority="override"', 'priority="overwrite"');
    assert.deepEqual(deprecatedOf(text), [
      "warning: the value 'overwrite' of Event.priority is deprecated in OpenSCENARIO 1.2; write 'override'",
    ]);
    const parameterAction = scenario(
      event('E', '<GlobalAction><ParameterAction parameterRef="P"><SetAction value="1"/></ParameterAction></GlobalAction>'),
      '<ParameterDeclarations><ParameterDeclaration name="P" parameterType="int" value="0"/></ParameterDeclarations>',
    );
    assert.deepEqual(deprecatedOf(parameterAction), [
      'warning: <ParameterAction> is deprecated since OpenSCENARIO 1.2; write <VariableAction> on a variable instead',
      'warning: <SetAction> is deprecated since OpenSCENARIO 1.2; write the <SetAction> of a <VariableAction> instead',
    ]);
  });

  it("carries the standard's form for the quick fix where only a name or a value changes", () => {
    const suggestions = (text: string) =>
      schemaProblems(diskRef('/virtual/deprecated.xosc'), parseXml(text), new SchemaCheckMemory())
        .filter((problem) => problem.code === 'schema-deprecated')
        .map((problem) => problem.data);
    assert.deepEqual(suggestions(scenario(event('E')).replace('priority="override"', 'priority="overwrite"')), [
      { suggestion: 'override' },
    ]);
    assert.deepEqual(suggestions(weather('cloudState="free"')), [undefined], 'cloudState and fractionalCloudCover take other values');
    // Sun.intensity is deprecated from 1.3 on (illuminance).
    const sun = weather('fractionalCloudCover="zeroOktas"')
      .replace(
        '<Weather fractionalCloudCover="zeroOktas"/>',
        '<Weather fractionalCloudCover="zeroOktas"><Sun azimuth="0" elevation="1" intensity="1000"/></Weather>',
      )
      .replace('revMinor="2"', 'revMinor="3"');
    assert.deepEqual(suggestions(sun), [{ suggestion: 'illuminance' }]);
  });

  it("nothing in the standard's current forms", () => {
    assert.deepEqual(deprecatedOf(weather('fractionalCloudCover="zeroOktas"')), []);
  });
});

describe('rules: the constant pi', () => {
  it('is named a constant from OpenSCENARIO 1.4 on in a 1.3 file', async () => {
    const text = scenario(
      event('E'),
      '<ParameterDeclarations><ParameterDeclaration name="Half" parameterType="double" value="${pi / 2}"/></ParameterDeclarations>',
    ).replace('revMinor="2"', 'revMinor="3"');
    const messages = await messagesOf(text, 'nonstandard-expression');
    assert.equal(messages.length, 1);
    assert.match(messages[0], /^'pi' is a constant from OpenSCENARIO 1\.4 on, not of 1\.3/);
  });
});
