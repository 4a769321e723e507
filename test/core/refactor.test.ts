import * as assert from 'node:assert/strict';
import { applyEdits } from '../../server/src/core/flatten/edits';
import { buildModel } from '../../server/src/core/model';
import { extractGroup, tunableAttributes } from '../../server/src/core/refactor/extractGroup';
import { CatalogFileText, extractToCatalog } from '../../server/src/core/refactor/extractCatalog';
import { makeOverridableEdit } from '../../server/src/core/refactor/makeOverridable';
import { attribute, descendants, parseXml, XmlElement } from '../../server/src/core/xml';
import { fileHeader, openScenarioFile } from '../support/fixtures';

const SCENARIO = openScenarioFile(
  `  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="12"/>
  </ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="ego">
      <Vehicle name="car" vehicleCategory="car">
        <Performance maxSpeed="$Speed" maxAcceleration="5" maxDeceleration="9"/>
      </Vehicle>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup name="Go" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="ego"/>
          </Actors>
          <Maneuver name="First">
            <Event name="E1" priority="overwrite">
              <Action name="A1">
                <PrivateAction><LongitudinalAction><SpeedAction>
                  <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
                  <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget>
                </SpeedAction></LongitudinalAction></PrivateAction>
              </Action>
            </Event>
          </Maneuver>
          <Maneuver name="Second">
            <Event name="E2" priority="overwrite">
              <Action name="A2">
                <PrivateAction><TeleportAction><Position><RelativeObjectPosition entityRef="ego" dx="1" dy="0"/></Position></TeleportAction></PrivateAction>
              </Action>
            </Event>
          </Maneuver>
        </ManeuverGroup>
      </Act>
    </Story>
  </Storyboard>
`,
  fileHeader(),
);

function named(root: XmlElement | undefined, element: string, name: string): XmlElement {
  const found =
    root &&
    descendants(root).find(
      (candidate) => candidate.name === element && candidate.attributes.some((item) => item.name === 'name' && item.value === name),
    );
  assert.ok(found, `${element} ${name}`);
  return found;
}

describe('refactorings in the core (issue 19)', function () {
  it('suggests numbers, entity references and enumeration values, never the name or the actor', function () {
    const document = parseXml(SCENARIO);
    const group = buildModel(document).groups[0];
    const choices = tunableAttributes(document, group, new Set(['ego'])) ?? [];
    const suggested = choices.filter((choice) => choice.suggested).map((choice) => `${choice.label}=${choice.value}`);
    assert.ok(suggested.includes('AbsoluteTargetSpeed.value=10'));
    assert.ok(suggested.includes('RelativeObjectPosition.entityRef=ego'));
    assert.ok(suggested.includes('SpeedActionDynamics.dynamicsShape=step'));
    assert.ok(!suggested.includes('Event.name=E1'));
    assert.ok(!choices.some((choice) => choice.label === 'ManeuverGroup.name' || choice.label === 'EntityRef.entityRef'));
  });

  it('extracts a group with the chosen attributes listed and a reference that sets only its name', async function () {
    const document = parseXml(SCENARIO);
    const group = buildModel(document).groups[0];
    const speed = (tunableAttributes(document, group, new Set()) ?? []).find((choice) => choice.label === 'AbsoluteTargetSpeed.value');
    assert.ok(speed);
    const taken = new Set(['/work/Go.xosc']);
    const extracted = await extractGroup({
      file: '/work/main.xosc',
      text: SCENARIO,
      document,
      group,
      chosen: [speed.id],
      entityNames: new Set(['ego']),
      exists: async (file) => taken.has(file),
    });
    assert.equal(extracted.file, '/work/Go_2.xosc');
    assert.deepEqual(extracted.parameters, ['ManeuverGroup.name', 'AbsoluteTargetSpeed.value']);
    assert.match(extracted.text, /<AbsoluteTargetSpeed parameterAttributes="value" value="10"\/>/);
    assert.match(extracted.replacement.text, /<ScenarioReference scenarioFileName="Go_2.xosc">/);
    assert.match(extracted.replacement.text, /<ParameterReference key="name" value="Go"\/>/);
    assert.doesNotMatch(extracted.replacement.text, /AbsoluteTargetSpeed/);
  });

  it('adds an attribute to parameterAttributes, or the list itself', function () {
    const text = '<A parameterAttributes="x" x="1" y="2"/>';
    const element = parseXml(text).root as XmlElement;
    const edit = makeOverridableEdit(element, attribute(element, 'y') as NonNullable<ReturnType<typeof attribute>>);
    assert.equal(applyEdits(text, edit ? [edit] : []), '<A parameterAttributes="x,y" x="1" y="2"/>');
    assert.equal(makeOverridableEdit(element, attribute(element, 'x') as NonNullable<ReturnType<typeof attribute>>), undefined);
    const bare = parseXml('<B z="3"/>').root as XmlElement;
    const added = makeOverridableEdit(bare, attribute(bare, 'z') as NonNullable<ReturnType<typeof attribute>>);
    assert.equal(applyEdits('<B z="3"/>', added ? [added] : []), '<B parameterAttributes="z" z="3"/>');
  });

  it('moves a vehicle into a new catalog, passing the scenario parameter it uses, and opens an empty CatalogLocations', async function () {
    const document = parseXml(SCENARIO);
    const vehicle = named(document.root, 'Vehicle', 'car');
    const extracted = await extractToCatalog({
      file: '/work/main.xosc',
      document,
      element: vehicle,
      catalogsIn: async () => [],
      exists: async () => false,
    });
    assert.equal(extracted.catalog.path, '/work/Catalogs/VehicleCatalog.xosc');
    assert.ok(extracted.catalog.create);
    const catalog = parseXml(extracted.catalog.text ?? '');
    assert.deepEqual(catalog.problems, []);
    assert.match(
      extracted.catalog.text ?? '',
      /<Vehicle name="car" vehicleCategory="car">\s*<ParameterDeclarations>\s*<ParameterDeclaration name="Speed" parameterType="double" value="12"\/>/,
    );
    const after = applyEdits(SCENARIO, extracted.edits);
    assert.deepEqual(parseXml(after).problems, []);
    assert.match(
      after,
      /<CatalogLocations>\s*<VehicleCatalog>\s*<Directory path="Catalogs"\/>\s*<\/VehicleCatalog>\s*<\/CatalogLocations>/,
    );
    assert.match(
      after,
      /<CatalogReference catalogName="VehicleCatalog" entryName="car">\s*<ParameterAssignments>\s*<ParameterAssignment parameterRef="Speed" value="\$Speed"\/>/,
    );
  });

  it("puts a maneuver's CatalogReference before the group's maneuvers, as the schema orders them, and reuses an equal entry", async function () {
    const document = parseXml(SCENARIO);
    const second = named(document.root, 'Maneuver', 'Second');
    const existing: CatalogFileText = {
      path: '/work/Catalogs/Maneuvers.xosc',
      text: `<?xml version="1.0"?>\n<OpenSCENARIO>\n  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="c" author="c"/>\n  <Catalog name="Moves">\n    <Maneuver name="Second">\n      <ParameterDeclarations>\n        <ParameterDeclaration name="Dx" parameterType="double" value="5"/>\n      </ParameterDeclarations>\n      <Event name="E2" priority="overwrite">\n        <Action name="A2">\n          <PrivateAction><TeleportAction><Position><RelativeObjectPosition entityRef="ego" dx="$Dx" dy="0"/></Position></TeleportAction></PrivateAction>\n        </Action>\n      </Event>\n    </Maneuver>\n  </Catalog>\n</OpenSCENARIO>\n`,
    };
    const extracted = await extractToCatalog({
      file: '/work/main.xosc',
      document,
      element: second,
      catalogsIn: async () => [existing],
      exists: async () => true,
    });
    assert.ok(extracted.reused);
    assert.deepEqual(extracted.catalog.edits, []);
    const after = applyEdits(SCENARIO, extracted.edits);
    assert.deepEqual(parseXml(after).problems, []);
    const group = named(parseXml(after).root, 'ManeuverGroup', 'Go');
    assert.deepEqual(
      group.children.map((child) => child.name),
      ['Actors', 'CatalogReference', 'Maneuver'],
    );
    assert.match(
      after,
      /<CatalogReference catalogName="Moves" entryName="Second">\s*<ParameterAssignments>\s*<ParameterAssignment parameterRef="Dx" value="1"\/>/,
    );
  });
});

describe('refactorings in the core: CatalogLocations written on one line (issue 19)', function () {
  it('adds the location on lines of its own', async function () {
    const text = SCENARIO.replace(
      '<CatalogLocations/>',
      '<CatalogLocations><RouteCatalog><Directory path="r"/></RouteCatalog></CatalogLocations>',
    );
    const document = parseXml(text);
    const extracted = await extractToCatalog({
      file: '/work/main.xosc',
      document,
      element: named(document.root, 'Vehicle', 'car'),
      catalogsIn: async () => [],
      exists: async () => false,
    });
    const after = applyEdits(text, extracted.edits);
    assert.deepEqual(parseXml(after).problems, []);
    assert.match(
      after,
      /<\/RouteCatalog>\n\s*<VehicleCatalog>\n\s*<Directory path="Catalogs"\/>\n\s*<\/VehicleCatalog>\n\s*<\/CatalogLocations>/,
    );
  });
});

describe('refactorings in the core: what cannot move into a catalog (issue 19)', function () {
  it('refuses a maneuver that tests a scenario parameter by name', async function () {
    const text = SCENARIO.replace(
      '<Event name="E1" priority="overwrite">',
      '<Event name="E1" priority="overwrite">\n              <StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><ParameterCondition parameterRef="Speed" value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>',
    );
    const document = parseXml(text);
    await assert.rejects(
      extractToCatalog({
        file: '/work/main.xosc',
        document,
        element: named(document.root, 'Maneuver', 'First'),
        catalogsIn: async () => [],
        exists: async () => false,
      }),
      /ParameterCondition names the scenario parameter 'Speed'/,
    );
  });
});
