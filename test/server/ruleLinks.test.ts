import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CodeAction, Diagnostic } from 'vscode-languageserver/node';
import { QC_RULE_DESCRIPTIONS } from '../../server/src/core/rules';
import { EXPECTED_RULES, qcRuleHref, RULE_FILES } from '../support/qcRuleFiles';
import { problemCodeOf } from '../support/diagnostics';
import { BARE_XML_DECLARATION, MANEUVER_CATALOG, fileHeader, openScenarioFile } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';
import { applyEdits } from '../support/textEdits';

const SCENARIO = openScenarioFile(
  `  <Entities>
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
`,
  fileHeader({ description: 'links', author: 't' }),
  BARE_XML_DECLARATION,
);

/** Each diagnostic names its rule: ASAM's Quality Checker uid, linked to its description, where that checker has the rule; the project's code otherwise (issue 18, item 2). */
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

  it("names and links a rule of ASAM QC, and names the project's own rules by their code, unlinked", async () => {
    const uri = await client.openFile(path.join(root, 'links.xosc'));
    const diagnostics = await client.diagnosticsOf(
      uri,
      (list) =>
        list.some((diagnostic) => problemCodeOf(diagnostic) === 'duplicate-name') &&
        list.some((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-parameter'),
    );
    const duplicate = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'duplicate-name');
    assert.equal(duplicate?.code, 'asam.net:xosc:1.2.0:reference_control.unique_element_names_on_same_level');
    assert.equal(
      duplicate?.codeDescription?.href,
      'https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md#check_asam_xosc_reference_control_unique_element_names_on_same_level',
    );
    const undeclared = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-parameter');
    assert.equal(undeclared?.code, 'undeclared-parameter');
    assert.equal(undeclared?.codeDescription, undefined);
  });
});

describe('language server: each rule of ASAM QC the project maps is the code of its diagnostics', function () {
  this.timeout(120_000);
  let client: TestClient;
  let root: string;
  const found = new Map<string, Diagnostic[]>();

  before(async function () {
    root = temporaryWorkspace(RULE_FILES);
    client = await TestClient.start({ root, schema: true });
    for (const file of new Set(EXPECTED_RULES.map(([name]) => name))) {
      const codes = EXPECTED_RULES.filter(([name]) => name === file).map(([, code]) => code);
      const uri = await client.openFile(path.join(root, file));
      found.set(
        file,
        await client.diagnosticsOf(uri, (list) => codes.every((code) => list.some((d) => problemCodeOf(d) === code)), 30_000),
      );
    }
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('covers every rule of ASAM QC that a problem maps to', () => {
    const covered = new Set(EXPECTED_RULES.map(([, , qcRule]) => qcRule).filter((qcRule) => qcRule !== undefined));
    assert.deepEqual([...covered].sort(), Object.keys(QC_RULE_DESCRIPTIONS).sort());
  });

  it('every diagnostic carries its project code in data.code, whatever its code names', () => {
    for (const [file, diagnostics] of found)
      for (const diagnostic of diagnostics) assert.ok(problemCodeOf(diagnostic), `${file}: ${JSON.stringify(diagnostic)}`);
  });

  for (const [file, code, qcRule] of EXPECTED_RULES) {
    it(`${file}: ${code} is ${qcRule ?? 'its own rule'}`, () => {
      const diagnostics = found.get(file) ?? [];
      const diagnostic = diagnostics.find((candidate) => problemCodeOf(candidate) === code && candidate.code === (qcRule ?? code));
      assert.ok(
        diagnostic,
        diagnostics.map((candidate) => `${problemCodeOf(candidate)} ${candidate.code}: ${candidate.message}`).join('\n'),
      );
      assert.equal(diagnostic.source, 'modular2simple');
      assert.deepEqual(diagnostic.codeDescription, qcRule ? { href: qcRuleHref(qcRule) } : undefined);
    });
  }

  it('a FileHeader out of order is not missing: valid_schema, not fileheader_is_present', async () => {
    const text = `<?xml version="1.0"?>
<OpenSCENARIO>
  <Entities/>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="d" author="t"/>
  <Storyboard><Init><Actions/></Init><StopTrigger/></Storyboard>
</OpenSCENARIO>
`;
    const uri = await client.open(fileUri(path.join(root, 'late.xosc')), text);
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.some((d) => problemCodeOf(d) === 'schema-missing-element'));
    const missing = diagnostics.find((d) => problemCodeOf(d) === 'schema-missing-element') as Diagnostic;
    assert.match(String(missing.message), /lacks the required elements <FileHeader>/);
    assert.equal(missing.code, 'asam.net:xosc:1.0.0:xml.valid_schema');
    assert.ok(!diagnostics.some((d) => d.code === 'asam.net:xosc:1.0.0:xml.fileheader_is_present'), JSON.stringify(diagnostics));
  });

  it('quick fixes still apply to a diagnostic whose code is a QC rule: the root element is renamed, a FileHeader inserted', async () => {
    const cases: [file: string, code: string, title: RegExp, fixed: RegExp][] = [
      ['root.xosc', 'schema-unknown-element', /^Change to <OpenSCENARIO>$/, /^<\?xml[^>]*>\n<OpenSCENARIO>[\s\S]*<\/OpenSCENARIO>\n$/],
      ['headerless.xosc', 'schema-missing-element', /^Insert <FileHeader>$/, /<OpenSCENARIO>\s*<FileHeader /],
    ];
    for (const [file, code, title, fixed] of cases) {
      const diagnostic = (found.get(file) ?? []).find((candidate) => problemCodeOf(candidate) === code) as Diagnostic;
      assert.match(String(diagnostic.code), /^asam\.net:xosc:/);
      const uri = fileUri(path.join(root, file));
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
      const action = actions.find((candidate) => title.test(candidate.title));
      assert.ok(action, actions.map((candidate) => candidate.title).join(', '));
      assert.match(applyEdits(RULE_FILES[file], action.edit?.changes?.[uri] ?? []), fixed);
    }
  });
});

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
      await client.diagnosticsOf(catalogUri, (list) => list.some((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-variable'))
    ).filter((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-variable');
    assert.equal(note.severity, 3, 'information');
    const related = (note.relatedInformation ?? []).map((item) => `${path.basename(item.location.uri)}: ${item.message}`).sort();
    assert.deepEqual(related, ["declares.xosc: declares variable 'Flag'", "lacks.xosc: does not declare variable 'Flag' (an error there)"]);
    const lacksUri = await client.openFile(path.join(root, 'lacks.xosc'));
    const errors = (
      await client.diagnosticsOf(lacksUri, (list) => list.some((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-variable'))
    ).filter((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-variable');
    assert.deepEqual(
      errors.map((diagnostic) => diagnostic.severity),
      [1],
    );
  });
});
