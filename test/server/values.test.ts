import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  CodeAction,
  Diagnostic,
  DiagnosticSeverity,
  Hover,
  InlayHint,
  MarkupContent,
  TextEdit,
  WorkspaceEdit,
} from 'vscode-languageserver/node';
import { TestClient } from './harness';
import { SERVER_WAIT_MS } from '../support/wait';
import { applyEdits, inside } from '../support/textEdits';
import { problemCodeOf } from '../support/diagnostics';
import { temporaryWorkspace } from '../support/workspace';
import { fileHeader, openScenarioFile } from '../support/fixtures';

/** A storyboard whose one Event `eventName` runs a CustomCommandAction of `type` holding `command`. */
function storyboard(eventName: string, type: string, command: string): string {
  return `  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"/>
          <Maneuver name="M">
            <Event name="${eventName}" priority="override">
              <Action name="Act"><UserDefinedAction><CustomCommandAction type="${type}">${command}</CustomCommandAction></UserDefinedAction></Action>
              <StartTrigger/>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
`;
}

/** Values and severities by SPEC 12 (issue 17) over JSON-RPC: hover, inlay hints, diagnostics and their quick fixes. */
const VALUES = openScenarioFile(
  `  <ParameterDeclarations>
    <ParameterDeclaration name="Mod" parameterType="double" value="\${7 % 4}"/>
    <ParameterDeclaration name="HeadwayTime_Brake" parameterType="double" value="0.7"/>
    <ParameterDeclaration name="RedLightDistance" parameterType="string" value="50"/>
    <ParameterDeclaration name="$TargetBrakeDistance" parameterType="double" value="30"/>
    <ParameterDeclaration name="Minus" parameterType="int" value="-5.0"/>
    <ParameterDeclaration name="Stop" parameterType="double" value="\${$RedLightDistance - 6}"/>
    <ParameterDeclaration name="Brake" parameterType="double" value="\${$TargetBrakeDistance + $Minus + HeadwayTime_Brake}"/>
  </ParameterDeclarations>
${storyboard('${BrakeCondition_HWT + _ + $HeadwayTime_Brake}', 'x', '${round(2.5)}')}`,
  fileHeader({ description: 'values' }),
);

const lineOf = (needle: string) => VALUES.slice(0, VALUES.indexOf(needle)).split('\n').length - 1;

/** One name declared twice in one scope: the standard's references read the first, esmini the last (Parameters.cpp:566-582). */
const TWICE = openScenarioFile(
  `  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="10"/>
    <ParameterDeclaration name="Speed" parameterType="double" value="20"/>
    <ParameterDeclaration name="Double" parameterType="double" value="\${$Speed * 2}"/>
  </ParameterDeclarations>
${storyboard('E', '$Speed', 'x')}`,
  fileHeader({ description: 'declared twice' }),
);

describe('values as the simulator computes them, and the severity policy (JSON-RPC)', function () {
  let root: string;
  const clients: TestClient[] = [];

  before(() => {
    root = temporaryWorkspace({ 'values.xosc': VALUES, 'twice.xosc': TWICE });
  });

  after(async () => {
    for (const client of clients) await client.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  async function open(settings: Record<string, unknown>, file = 'values.xosc'): Promise<{ client: TestClient; uri: string }> {
    const client = await TestClient.start({ root, settings });
    clients.push(client);
    return { client, uri: await client.openFile(path.join(root, file)) };
  }

  it('publishes the lenient forms and the values esmini computes otherwise as warnings, with no error', async function () {
    const { client, uri } = await open({});
    const diagnostics = await client.diagnosticsOf(uri);
    const shown = diagnostics
      .filter((diagnostic) => diagnostic.severity !== DiagnosticSeverity.Hint)
      .map((diagnostic) => `${diagnostic.range.start.line}:${String(problemCodeOf(diagnostic))}:${diagnostic.severity}`);
    assert.deepEqual(
      shown.sort(),
      [
        `${lineOf('name="Mod"')}:simulator-value:2`,
        `${lineOf('name="$TargetBrakeDistance"')}:lenient-value:2`,
        `${lineOf('name="Minus"')}:lenient-value:2`,
        `${lineOf('name="Stop"')}:lenient-value:2`,
        `${lineOf('name="Brake"')}:lenient-value:2`,
        // esmini reads the bare word as text: '30 + -5.0 + HeadwayTime_Brake' glued, whose double is 30.
        `${lineOf('name="Brake"')}:simulator-value:2`,
        `${lineOf('<Event name=')}:lenient-value:2`,
      ].sort(),
    );
    const modulo = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'simulator-value');
    assert.match(
      String(modulo?.message ?? ''),
      /esmini computes -1 where the standard gives 3: esmini computes % as C remainder\(\).*expr\.h:378-380/,
    );
  });

  it('fixes each to the standard form', async function () {
    const { client, uri } = await open({});
    const diagnostics = (await client.diagnosticsOf(uri)).filter((diagnostic) => problemCodeOf(diagnostic) === 'lenient-value');
    let text = VALUES;
    const edits: TextEdit[] = [];
    for (const diagnostic of diagnostics) {
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
      const fix = actions.find((action) => action.isPreferred);
      assert.ok(fix?.edit, `a fix for ${diagnostic.message}`);
      edits.push(...((fix.edit as WorkspaceEdit).changes?.[uri] ?? []));
    }
    text = applyEdits(text, edits);
    for (const written of [
      'name="TargetBrakeDistance"',
      'parameterType="int" value="-5"',
      'name="RedLightDistance" parameterType="double"',
      '$TargetBrakeDistance + $Minus + $HeadwayTime_Brake',
      '<Event name="BrakeCondition_HWT_0.7"',
    ]) {
      assert.ok(text.includes(written), `${written} in\n${text}`);
    }
  });

  it("shows the standard's value in hover and inlay hints, and esmini's beside it where it differs", async function () {
    const { client, uri } = await open({});
    const hints = await client.request<InlayHint[]>('textDocument/inlayHint', {
      textDocument: { uri },
      range: { start: { line: 0, character: 0 }, end: { line: 100, character: 0 } },
    });
    const label = (needle: string) => hints.find((hint) => hint.position.line === lineOf(needle))?.label;
    assert.equal(label('name="Mod"'), '= 3 (esmini -1)');
    assert.equal(label('name="Stop"'), '= 44');
    assert.equal(label('name="Brake"'), '= 25.7 (esmini 30)');
    assert.equal(label('<Event name='), '= BrakeCondition_HWT_0.7');
    const hover = await client.request<Hover>('textDocument/hover', client.at(uri, inside(VALUES, '${7 % 4}', 3)));
    assert.match(
      (hover.contents as MarkupContent).value,
      /= \*\*3\*\* \(double\); by the standard 3, by esmini -1 \(esmini computes % as C remainder/,
    );
    const use = await client.request<Hover>('textDocument/hover', client.at(uri, inside(VALUES, '$TargetBrakeDistance +', 3)));
    assert.match(
      (use.contents as MarkupContent).value,
      /- `\$TargetBrakeDistance` = 30 \(double\), declared in `<OpenSCENARIO>` on line 8/,
    );
  });

  it("with modular2simple.simulator = esmini, gives esmini's value first and names the standard's", async function () {
    const { client, uri } = await open({ simulator: 'esmini' });
    // The settings arrive after the first analysis: ask again until the analysis under them answers.
    const range = { start: { line: 0, character: 0 }, end: { line: 100, character: 0 } };
    let label: InlayHint['label'] | undefined;
    for (let attempt = 0, deadline = Date.now() + SERVER_WAIT_MS; label !== '= -1 (standard 3)' && Date.now() < deadline; attempt++) {
      if (attempt > 0) await new Promise((resolve) => setTimeout(resolve, 100));
      const hints = await client.request<InlayHint[]>('textDocument/inlayHint', { textDocument: { uri }, range });
      label = hints.find((hint) => hint.position.line === lineOf('name="Mod"'))?.label;
    }
    assert.equal(label, '= -1 (standard 3)');
    const diagnostics: Diagnostic[] = await client.diagnosticsOf(uri);
    assert.ok(
      !diagnostics.some((diagnostic) => diagnostic.severity === DiagnosticSeverity.Error),
      diagnostics.map((diagnostic) => diagnostic.message).join('\n'),
    );
  });

  it("a parameter declared twice: hover and inlay hints show the last declaration's value with esmini, as esmini reads it, and name it beside the standard's", async function () {
    const twiceLine = (needle: string) => TWICE.slice(0, TWICE.indexOf(needle)).split('\n').length - 1;
    const range = { start: { line: 0, character: 0 }, end: { line: 100, character: 0 } };
    const labelOf = async (client: TestClient, uri: string) =>
      (await client.request<InlayHint[]>('textDocument/inlayHint', { textDocument: { uri }, range })).find(
        (hint) => hint.position.line === twiceLine('name="Double"'),
      )?.label;
    const standard = await open({}, 'twice.xosc');
    assert.equal(await labelOf(standard.client, standard.uri), '= 20 (esmini 40)');
    const esmini = await open({ simulator: 'esmini' }, 'twice.xosc');
    // The settings arrive after the first analysis: ask again until the analysis under them answers.
    let label: InlayHint['label'] | undefined;
    for (let attempt = 0, deadline = Date.now() + SERVER_WAIT_MS; label !== '= 40 (standard 20)' && Date.now() < deadline; attempt++) {
      if (attempt > 0) await new Promise((resolve) => setTimeout(resolve, 100));
      label = await labelOf(esmini.client, esmini.uri);
    }
    assert.equal(label, '= 40 (standard 20)');
    const use = await esmini.client.request<Hover>('textDocument/hover', esmini.client.at(esmini.uri, inside(TWICE, 'type="$Speed"', 8)));
    assert.match((use.contents as MarkupContent).value, /^\*\*\$Speed\*\* = 20 \(double\)/);
    const inExpression = await esmini.client.request<Hover>(
      'textDocument/hover',
      esmini.client.at(esmini.uri, inside(TWICE, '$Speed * 2', 3)),
    );
    const hovered = (inExpression.contents as MarkupContent).value;
    assert.match(
      hovered,
      /^`\$\{\$Speed \* 2\}` = \*\*40\*\* \(double\); by the standard 20, by esmini 40 \(esmini uses the last of two declarations of one name/,
    );
    // The declaration esmini reads: the second, on its line (1-based).
    assert.ok(
      hovered.includes(`- \`$Speed\` = 20 (double), declared in \`<OpenSCENARIO>\` on line ${twiceLine('value="20"') + 1}`),
      hovered,
    );
  });
});
