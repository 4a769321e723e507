import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { api, type InsideTests, open, requireServerFeature, revertAndClose, waitFor, waitForPage, workspaceRoot } from './helpers';
import { EMPTY_INIT, fileHeader, parameterDeclarations, scenarioDocument, story, vehicleObject } from '../../support/fixtures';
import { screenshot } from './harnessClient';

const UNIQUE_NAMES = 'asam.net:xosc:1.2.0:reference_control.unique_element_names_on_same_level';
const VALID_SCHEMA = 'asam.net:xosc:1.0.0:xml.valid_schema';
/** Where ASAM's checker documents its rules, one anchor per rule. */
const CHECKER_DOC = 'https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md';

/** The Problems panel's filter "Show Active File Only" (a toggle). */
const TOGGLE_ACTIVE_FILE_ONLY = 'workbench.actions.workbench.panel.markers.view.toggleActiveFile';

/** A diagnostic's code as the VS Code API gives it: the rule's uid with the link to its description, or a plain code. */
function codeOf(diagnostic: vscode.Diagnostic): string | { value: string; target: string } | undefined {
  const code = diagnostic.code;
  if (code === undefined) return undefined;
  if (typeof code !== 'object') return String(code);
  return { value: String(code.value), target: code.target.toString(true) };
}

/** Issue 18 item 2 as a person sees it: each diagnostic names its rule, ASAM's Quality Checker uid where that checker has one. */
export const ruleTests: InsideTests = {
  ruleCodes: async function () {
    requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
    requireServerFeature(this, 'quick fixes', !!api().serverCapabilities()?.codeActionProvider);
    const file = path.join(workspaceRoot(), 'rule_codes.xosc');
    fs.writeFileSync(file, RULE_CODES);
    // The file is gone again after this test, so that the other tests see the example workspace as it is.
    try {
      await showRuleCodes();
    } finally {
      await vscode.commands.executeCommand('workbench.action.closePanel');
      await revertAndClose();
      fs.rmSync(file, { force: true });
    }
  },
};

async function showRuleCodes(): Promise<void> {
  const editor = await open('rule_codes.xosc');
  const uri = editor.document.uri;
  const find = (message: RegExp): vscode.Diagnostic | undefined =>
    vscode.languages.getDiagnostics(uri).find((diagnostic) => message.test(diagnostic.message));
  const [duplicate, unused, badValue] = await waitFor('the three problems of the scenario', () => {
    const found = [find(/two children named 'Event1'/), find(/'UnusedSpeed' is never used/), find(/'risng' is not a valid value/)];
    return found.every((diagnostic) => diagnostic !== undefined) ? (found as vscode.Diagnostic[]) : undefined;
  });
  // The rule ASAM's checker knows: its uid, linked to its description.
  assert.deepEqual(codeOf(duplicate), {
    value: UNIQUE_NAMES,
    target: `${CHECKER_DOC}#check_asam_xosc_reference_control_unique_element_names_on_same_level`,
  });
  assert.deepEqual(codeOf(badValue), { value: VALID_SCHEMA, target: `${CHECKER_DOC}#check_asam_xosc_xml_valid_schema` });
  // A rule of the project's own: its code, unlinked.
  assert.equal(codeOf(unused), 'unused-parameter');
  assert.equal(duplicate.source, 'modular2simple');

  // The Problems panel shows the rule after the source, as a link; only this file's problems, so that its rows are drawn.
  await vscode.commands.executeCommand('workbench.actions.view.problems');
  await vscode.commands.executeCommand(TOGGLE_ACTIVE_FILE_ONLY);
  try {
    editor.revealRange(duplicate.range, vscode.TextEditorRevealType.InCenter);
    editor.selection = new vscode.Selection(duplicate.range.start, duplicate.range.start);
    // Both rows: the panel draws its rows as it gets to them, so one row shown says nothing of the other.
    await waitForPage(UNIQUE_NAMES, '.markers-panel');
    await waitForPage(VALID_SCHEMA, '.markers-panel');
    await screenshot('the Problems panel names each rule (ASAM QC uid)');
  } finally {
    await vscode.commands.executeCommand(TOGGLE_ACTIVE_FILE_ONLY);
  }

  // The quick fix of a diagnostic whose code is an ASAM QC rule is still offered, and applies.
  const actions = await vscode.commands.executeCommand<vscode.CodeAction[]>(
    'vscode.executeCodeActionProvider',
    uri,
    badValue.range,
    vscode.CodeActionKind.QuickFix.value,
  );
  const change = actions.find((action) => action.title === "Change to 'rising'");
  assert.ok(change?.edit, `no fix "Change to 'rising'" among: ${actions.map((action) => action.title).join(', ')}`);
  assert.ok(await vscode.workspace.applyEdit(change.edit), 'the quick fix did not apply');
  assert.match(editor.document.getText(), /<Condition name="AtOnce" delay="0" conditionEdge="rising">/);
  await waitFor(
    'the fixed value to check clean',
    () => (!find(/'risng' is not a valid value/) && find(/two children named 'Event1'/)) || undefined,
  );
}

/** The Act: two Events named Event1 in one Maneuver, the first started by a conditionEdge misspelt. */
const ACT = `      <Act name="Act">
        <ManeuverGroup name="Group" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="Ego"/>
          </Actors>
          <Maneuver name="Maneuver">
            <Event name="Event1" priority="parallel">
              <Action name="First">
                <UserDefinedAction>
                  <CustomCommandAction type="first"/>
                </UserDefinedAction>
              </Action>
              <StartTrigger>
                <ConditionGroup>
                  <Condition name="AtOnce" delay="0" conditionEdge="risng">
                    <ByValueCondition>
                      <SimulationTimeCondition value="0" rule="greaterThan"/>
                    </ByValueCondition>
                  </Condition>
                </ConditionGroup>
              </StartTrigger>
            </Event>
            <Event name="Event1" priority="parallel">
              <Action name="Second">
                <UserDefinedAction>
                  <CustomCommandAction type="second"/>
                </UserDefinedAction>
              </Action>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger>
          <ConditionGroup>
            <Condition name="ActStart" delay="0" conditionEdge="none">
              <ByValueCondition>
                <SimulationTimeCondition value="0" rule="greaterThan"/>
              </ByValueCondition>
            </Condition>
          </ConditionGroup>
        </StartTrigger>
      </Act>
`;

/** One Maneuver with two Events named Event1, a parameter nothing uses and a conditionEdge misspelt; schema-valid otherwise. */
const RULE_CODES = scenarioDocument({
  header: fileHeader({ description: 'rule codes', author: 'tests' }),
  parameters: parameterDeclarations([['UnusedSpeed', 'double', '10']], 4),
  catalogLocations: '',
  roadNetwork: '',
  entities: vehicleObject('Ego'),
  storyboard: `${EMPTY_INIT}${story('Story', ACT)}    <StopTrigger/>\n`,
});
