import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { temporaryWorkspace } from '../support/workspace';
import { TestClient } from './harness';

const SCENARIO = `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="links" author="t"/>
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
            <Event name="Event1" priority="override"><Action name="A1"><UserDefinedAction><CustomCommandAction type="t"/></UserDefinedAction></Action></Event>
            <Event name="Event1" priority="override"><Action name="A2"><UserDefinedAction><CustomCommandAction type="$Missing"/></UserDefinedAction></Action></Event>
          </Maneuver>
        </ManeuverGroup>
      </Act>
    </Story>
  </Storyboard>
</OpenSCENARIO>
`;

/** Each diagnostic names its rule: the project's code, linked to ASAM's description where its Quality Checker has the rule (issue 18, item 2). */
describe('language server: diagnostics link their ASAM Quality Checker rule', function () {
  this.timeout(60_000);
  let client: TestClient;
  let root: string;

  before(async function () {
    root = temporaryWorkspace({ 'links.xosc': SCENARIO });
    client = await TestClient.start({ root });
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it("links a rule of ASAM QC to its description, and leaves the project's own rules unlinked", async () => {
    const uri = await client.openFile(path.join(root, 'links.xosc'));
    const diagnostics = await client.diagnosticsOf(
      uri,
      (list) =>
        list.some((diagnostic) => diagnostic.code === 'duplicate-name') &&
        list.some((diagnostic) => diagnostic.code === 'undeclared-parameter'),
    );
    const duplicate = diagnostics.find((diagnostic) => diagnostic.code === 'duplicate-name');
    assert.equal(
      duplicate?.codeDescription?.href,
      'https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md#check_asam_xosc_reference_control_unique_element_names_on_same_level',
    );
    const undeclared = diagnostics.find((diagnostic) => diagnostic.code === 'undeclared-parameter');
    assert.equal(undeclared?.codeDescription, undefined);
  });
});

const MANEUVER_CATALOG = `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="maneuvers" author="t"/>
  <Catalog name="ManeuverCatalog">
    <Maneuver name="Flip">
      <Event name="E" priority="override"><Action name="A"><GlobalAction><VariableAction variableRef="Flag"><SetAction value="true"/></VariableAction></GlobalAction></Action></Event>
    </Maneuver>
  </Catalog>
</OpenSCENARIO>
`;

function referencing(variables: string): string {
  return SCENARIO.replace(
    '<Entities>',
    `${variables}<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>\n  <Entities>`,
  ).replace(/<Maneuver name="M">[\s\S]*<\/Maneuver>/, '<CatalogReference catalogName="ManeuverCatalog" entryName="Flip"/>');
}

describe('language server: a variable of a catalog entry names the scenarios that reference the entry', function () {
  this.timeout(60_000);
  let client: TestClient;
  let root: string;

  before(async function () {
    root = temporaryWorkspace({
      'catalogs/ManeuverCatalog.xosc': MANEUVER_CATALOG,
      'declares.xosc': referencing(
        '<VariableDeclarations><VariableDeclaration name="Flag" variableType="boolean" value="false"/></VariableDeclarations>\n  ',
      ),
      'lacks.xosc': referencing(''),
    });
    client = await TestClient.start({ root });
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('notes in the catalog which referencing scenario declares it and which does not; the one that does not has an error', async () => {
    const catalogUri = await client.openFile(path.join(root, 'catalogs', 'ManeuverCatalog.xosc'));
    const [note] = (
      await client.diagnosticsOf(catalogUri, (list) => list.some((diagnostic) => diagnostic.code === 'undeclared-variable'))
    ).filter((diagnostic) => diagnostic.code === 'undeclared-variable');
    assert.equal(note.severity, 3, 'information');
    const related = (note.relatedInformation ?? []).map((item) => `${path.basename(item.location.uri)}: ${item.message}`).sort();
    assert.deepEqual(related, ["declares.xosc: declares variable 'Flag'", "lacks.xosc: does not declare variable 'Flag' (an error there)"]);
    const lacksUri = await client.openFile(path.join(root, 'lacks.xosc'));
    const errors = (
      await client.diagnosticsOf(lacksUri, (list) => list.some((diagnostic) => diagnostic.code === 'undeclared-variable'))
    ).filter((diagnostic) => diagnostic.code === 'undeclared-variable');
    assert.deepEqual(
      errors.map((diagnostic) => diagnostic.severity),
      [1],
    );
  });
});
