import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { Problem } from '../../server/src/core/problems';
import { schemaProblems } from '../../server/src/core/diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { vehicleObject } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

/**
 * The rules of ASAM's Quality Checker and of RA Consulting's OpenSCENARIO API checker that no other test
 * breaks and keeps (docs/checker-parity.md names the tests of the others): each broken once, found at its
 * place with our code, and kept once.
 */

function header(revisions = 'revMajor="1" revMinor="3"'): string {
  return `<FileHeader ${revisions} date="2026-01-01T00:00:00" description="parity" author="t"/>`;
}

/** A complete 1.3 scenario with one Event whose action is `action`. */
function scenario(action: string, declarations = '', revisions?: string): string {
  return `<?xml version="1.0"?>
<OpenSCENARIO>
  ${header(revisions)}
  <ParameterDeclarations>${declarations}</ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
${vehicleObject('Ego')}  </Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
          <Maneuver name="M">
            <Event name="E" priority="override">
              <Action name="Act">${action}</Action>
              <StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger><ConditionGroup><Condition name="Start" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
}

const CUSTOM = '<UserDefinedAction><CustomCommandAction type="t">x</CustomCommandAction></UserDefinedAction>';

/** `code:severity:text` of each schema problem (but the version notes), `text` being what its range covers. */
function schemaOf(text: string): string[] {
  return schemaProblems(diskRef('/virtual/parity.xosc'), parseXml(text), new SchemaCheckMemory()).map((problem) =>
    described(text, problem),
  );
}

function messagesOf(text: string): string[] {
  return schemaProblems(diskRef('/virtual/parity.xosc'), parseXml(text), new SchemaCheckMemory()).map((problem) => problem.message);
}

function described(text: string, problem: Problem): string {
  const { start, end } = problem.range;
  const line = text.split('\n')[start.line];
  const covered = start.line === end.line ? line.slice(start.character, end.character) : line.slice(start.character);
  return `${problem.code}:${problem.severity}:${covered}`;
}

async function semanticsOf(text: string): Promise<string[]> {
  const root = temporaryWorkspace({ 'parity.xosc': text });
  const semantics = await analyzeDocument(
    diskRef(path.join(root, 'parity.xosc')),
    parseXml(text),
    new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
    false,
  );
  return semanticProblems(semantics)
    .filter((problem) => problem.severity === 'error' || problem.severity === 'warning')
    .map((problem) => described(text, problem));
}

describe('checker parity: the file itself (ASAM QC xml.*)', () => {
  it('the scenario these tests start from has no problem', async () => {
    assert.deepEqual(schemaOf(scenario(CUSTOM)), []);
    assert.deepEqual(await semanticsOf(scenario(CUSTOM)), []);
  });

  it('xml.root_tag_is_openscenario: another root is an error at its name', () => {
    const text = scenario(CUSTOM).replace('<OpenSCENARIO>', '<Scenario>').replace('</OpenSCENARIO>', '</Scenario>');
    assert.deepEqual(schemaOf(text), ['schema-unknown-element:error:Scenario']);
  });

  it('xml.fileheader_is_present: a file without FileHeader is an error where it belongs, naming it', () => {
    const text = scenario(CUSTOM).replace(header(), '');
    assert.deepEqual(schemaOf(text), ['schema-missing-element:error:ParameterDeclarations']);
    assert.match(messagesOf(text)[0], /lacks the required element <FileHeader>/);
  });

  it('xml.version_is_defined: revMajor/revMinor missing, or no unsignedShort, is an error at the FileHeader', () => {
    const missing = schemaOf(scenario(CUSTOM, '', 'revMajor="1"'));
    assert.ok(missing.includes('schema-missing-attribute:error:FileHeader'), missing.join('\n'));
    const large = schemaOf(scenario(CUSTOM, '', 'revMajor="1" revMinor="70000"'));
    assert.ok(large.includes('schema-value:error:70000'), large.join('\n'));
  });
});

describe("checker parity: RA Consulting's model rules (cardinality, union, version)", () => {
  it('CardinalityCheckerRule, required property: a missing required attribute is an error at the element', () => {
    const text = scenario(CUSTOM).replace('<Event name="E" priority="override">', '<Event name="E">');
    assert.deepEqual(schemaOf(text), ['schema-missing-attribute:error:Event']);
  });

  it('CardinalityCheckerRule, too many and too few: a second StopTrigger and a missing Storyboard Init are errors', () => {
    const twice = schemaOf(scenario(CUSTOM).replace('<StopTrigger/>', '<StopTrigger/><StopTrigger/>'));
    assert.equal(twice.length, 1, twice.join('\n'));
    assert.match(twice[0], /^schema-(cardinality|order):error:StopTrigger$/);
    const noInit = scenario(CUSTOM).replace('<Init><Actions/></Init>', '');
    assert.deepEqual(schemaOf(noInit), ['schema-missing-element:error:Story']);
    assert.match(messagesOf(noInit)[0], /<Storyboard> lacks the required element <Init>/);
  });

  it('UnionCheckerRule, an xsd:choice holds exactly one: two alternatives, or none, are an error', () => {
    const two = schemaOf(
      scenario(`${CUSTOM}<PrivateAction><VisibilityAction graphics="true" sensors="true" traffic="true"/></PrivateAction>`),
    );
    assert.deepEqual(two, ['schema-order:error:PrivateAction']);
    assert.deepEqual(schemaOf(scenario('')), ['schema-missing-element:error:Action']);
  });

  it('VersionCheckerRule: a FileHeader version without a schema of its own is named (information) and read as the nearest', () => {
    const problems = schemaProblems(
      diskRef('/virtual/v.xosc'),
      parseXml(scenario(CUSTOM, '', 'revMajor="1" revMinor="5"')),
      new SchemaCheckMemory(),
    );
    assert.deepEqual(
      problems.map((problem) => `${problem.code}:${problem.severity}: ${problem.message}`),
      ['schema-version:information: no schema for OpenSCENARIO 1.5: checked against the OpenSCENARIO 1.3 schema'],
    );
  });
});

describe("checker parity: RA Consulting's parameter and variable rules", () => {
  it('ParameterDeclarationChecker: a declared value its type cannot take is an error at the value', async () => {
    const broken = await semanticsOf(scenario(CUSTOM, '<ParameterDeclaration name="Speed" parameterType="double" value="RRR1.1"/>'));
    assert.ok(broken.includes('type-mismatch:error:RRR1.1'), broken.join('\n'));
  });

  it('ParameterResolver: a $name no declaration resolves is an error at the use', async () => {
    const text = scenario(CUSTOM).replace('<SimulationTimeCondition value="1"', '<SimulationTimeCondition value="$Late"');
    assert.deepEqual(await semanticsOf(text), ['undeclared-parameter:error:$Late']);
    const declared = text.replace(
      '<ParameterDeclarations>',
      '<ParameterDeclarations><ParameterDeclaration name="Late" parameterType="double" value="2"/>',
    );
    assert.deepEqual(await semanticsOf(declared), []);
  });

  const withVariable = (type: string, value: string, action: string) =>
    scenario(`<GlobalAction><VariableAction variableRef="Flag">${action}</VariableAction></GlobalAction>`).replace(
      '<CatalogLocations/>',
      `<CatalogLocations/>\n  <VariableDeclarations><VariableDeclaration name="Flag" variableType="${type}" value="${value}"/></VariableDeclarations>`,
    );

  it('VariableDeclarationChecker: a declared variable value its type cannot take is an error at the value', async () => {
    const broken = await semanticsOf(withVariable('boolean', 'maybe', '<SetAction value="true"/>'));
    assert.deepEqual(broken, ['type-mismatch:error:maybe']);
    assert.deepEqual(await semanticsOf(withVariable('boolean', 'false', '<SetAction value="true"/>')), []);
  });

  it('VariableActionChecker: an undeclared variable, a SetAction value of another type, a ModifyAction on a string: errors', async () => {
    const undeclared = scenario('<GlobalAction><VariableAction variableRef="Nope"><SetAction value="1"/></VariableAction></GlobalAction>');
    assert.deepEqual(await semanticsOf(undeclared), ['undeclared-variable:error:Nope']);
    assert.deepEqual(await semanticsOf(withVariable('boolean', 'false', '<SetAction value="wrongBoolean"/>')), [
      'type-mismatch:error:wrongBoolean',
    ]);
    const modify = await semanticsOf(withVariable('string', 'a', '<ModifyAction><Rule><AddValue value="1"/></Rule></ModifyAction>'));
    assert.deepEqual(modify, ['type-mismatch:error:<ModifyAction']);
  });
});

describe("checker parity: RA Consulting's DeprecatedChecker (a deprecated attribute written with its replacement)", () => {
  const deprecated = (text: string) =>
    schemaProblems(diskRef('/virtual/deprecated.xosc'), parseXml(text), new SchemaCheckMemory())
      .filter((problem) => problem.code === 'schema-deprecated')
      .map((problem) => `${problem.severity}: ${problem.message}`);
  const override = (brake: string) =>
    scenario(
      `<PrivateAction><ControllerAction><OverrideControllerValueAction><Throttle active="false" value="0"/>${brake}<Clutch active="false" value="0"/><ParkingBrake active="false"><BrakePercent value="0"/></ParkingBrake><SteeringWheel active="false" value="0"/><Gear active="false"><ManualGear number="1"/></Gear></OverrideControllerValueAction></ControllerAction></PrivateAction>`,
    );

  it('Brake value written with a BrakePercent child: a warning naming both (RA Consulting: an error)', () => {
    assert.deepEqual(deprecated(override('<Brake active="false" value="0.5"><BrakePercent value="0.5"/></Brake>')), [
      'warning: Brake.value is deprecated since OpenSCENARIO 1.2 and written together with its replacement <BrakePercent>: leave out value',
    ]);
  });

  it('Brake value alone names what to write instead; the replacement alone is fine', () => {
    assert.deepEqual(deprecated(override('<Brake active="false" value="0.5"/>')), [
      'warning: Brake.value is deprecated since OpenSCENARIO 1.2; write a <BrakePercent> or <BrakeForce> child instead',
    ]);
    assert.deepEqual(deprecated(override('<Brake active="false"><BrakeForce value="500"/></Brake>')), []);
  });
});

describe("checker parity: RA Consulting's catalog loading", () => {
  const withCatalog = (reference: boolean) =>
    scenario(CUSTOM)
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations><VehicleCatalog><Directory path="missing/vehicles"/></VehicleCatalog></CatalogLocations>',
      )
      .replace(
        /<Vehicle name="car"[\s\S]*?<\/Vehicle>/,
        reference ? '<CatalogReference catalogName="VehicleCatalog" entryName="car"/>' : '$&',
      );

  it('a catalog directory that cannot be resolved is an error at its path when a reference needs it, and no problem otherwise', async () => {
    const needed = await semanticsOf(withCatalog(true));
    assert.ok(needed.includes('catalog-directory:error:missing/vehicles'), needed.join('\n'));
    assert.deepEqual(await semanticsOf(withCatalog(false)), []);
  });
});
