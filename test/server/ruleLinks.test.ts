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

  it('links a rule of ASAM QC to its description, and leaves the project\'s own rules unlinked', async () => {
    const uri = await client.openFile(path.join(root, 'links.xosc'));
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.some((diagnostic) => diagnostic.code === 'duplicate-name') && list.some((diagnostic) => diagnostic.code === 'undeclared-parameter'));
    const duplicate = diagnostics.find((diagnostic) => diagnostic.code === 'duplicate-name');
    assert.equal(duplicate?.codeDescription?.href, 'https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md#check_asam_xosc_reference_control_unique_element_names_on_same_level');
    const undeclared = diagnostics.find((diagnostic) => diagnostic.code === 'undeclared-parameter');
    assert.equal(undeclared?.codeDescription, undefined);
  });
});
