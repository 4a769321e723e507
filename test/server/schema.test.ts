import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import {
  CodeAction,
  CompletionItem,
  CompletionItemTag,
  Diagnostic,
  DiagnosticTag,
  Hover,
  MarkupContent,
  TextEdit,
} from 'vscode-languageserver/node';
import { checkSchema } from '../../server/src/core/schema/validate';
import { parseXml } from '../../server/src/core/xml';
import { fileUri, TestClient } from './harness';
import { problemCodeOf } from '../support/diagnostics';
import { at, cursor, positionAt } from '../support/cursor';
import { temporaryWorkspace } from '../support/workspace';
import { applyEdits, textAt } from '../support/textEdits';

/** A small scenario valid against every schema version; `{MINOR}` is its revMinor, `{ROOT}` goes after ParameterDeclarations. */
const TEMPLATE = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="{MINOR}" date="2024-01-01T00:00:00" description="schema test" author="test"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="TargetSpeed" parameterType="double" value="20"/>
  </ParameterDeclarations>
{ROOT}  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="ego">
      <CatalogReference catalogName="VehicleCatalog" entryName="car"/>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Init>
      <Actions>
{ACTIONS}      </Actions>
    </Init>
    <Story name="story">
      <Act name="act">
        <ManeuverGroup maximumExecutionCount="1" name="group">
          <Actors selectTriggeringEntities="false"/>
        </ManeuverGroup>
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;

function scenario(minor: string, parts: { root?: string; actions?: string } = {}): string {
  return TEMPLATE.replace('{MINOR}', minor)
    .replace('{ROOT}', () => parts.root ?? '')
    .replace('{ACTIONS}', () => parts.actions ?? '');
}

function messageOf(diagnostic: Diagnostic): string {
  return typeof diagnostic.message === 'string' ? diagnostic.message : '';
}

function labels(items: CompletionItem[] | { items: CompletionItem[] } | null): string[] {
  const list = Array.isArray(items) ? items : (items?.items ?? []);
  return list.map((item) => item.label);
}

function itemsOf(items: CompletionItem[] | { items: CompletionItem[] } | null): CompletionItem[] {
  return Array.isArray(items) ? items : (items?.items ?? []);
}

describe('server: OpenSCENARIO schema completion, hover and validation (over JSON-RPC)', function () {
  let client: TestClient;
  let root: string;

  before(async () => {
    root = temporaryWorkspace({});
    client = await TestClient.start({ root, schema: true });
  });

  /** The schema's diagnostics of a file (other checks, such as unused parameters, are tested elsewhere). */
  const schemaDiagnostics = async (uri: string, predicate: (list: Diagnostic[]) => boolean = () => true) => {
    const only = (list: Diagnostic[]) => list.filter((diagnostic) => String(problemCodeOf(diagnostic)).startsWith('schema-'));
    return only(await client.diagnosticsOf(uri, (list) => predicate(only(list))));
  };

  after(async () => {
    await client.stop();
    const errors = client.logs.filter((line) => /failed|Error/.test(line));
    assert.deepEqual(errors, [], 'the server logged a failure');
  });

  it('a valid scenario of each version gets no diagnostic', async () => {
    for (const minor of ['0', '1', '2', '3']) {
      const uri = await client.open(fileUri(path.join(root, `valid_${minor}.xosc`)), scenario(minor));
      assert.deepEqual(await schemaDiagnostics(uri), [], `1.${minor}`);
    }
  });

  it('an element of 1.2 is an error in a 1.0 file, naming the version that has it, and valid in a 1.2 file', async () => {
    const root12 = scenario('2', { root: '  <VariableDeclarations/>\n' });
    const root10 = scenario('0', { root: '  <VariableDeclarations/>\n' });
    const uri10 = await client.open(fileUri(path.join(root, 'variables_10.xosc')), root10);
    const uri12 = await client.open(fileUri(path.join(root, 'variables_12.xosc')), root12);
    const in10 = await schemaDiagnostics(uri10, (list) => list.length > 0);
    assert.equal(in10.length, 1, in10.map(messageOf).join('\n'));
    assert.equal(problemCodeOf(in10[0]), 'schema-unknown-element');
    assert.equal(textAt(root10, in10[0].range), 'VariableDeclarations');
    assert.match(messageOf(in10[0]), /<OpenSCENARIO> has no child <VariableDeclarations> in OpenSCENARIO 1\.0/);
    assert.match(messageOf(in10[0]), /belongs to OpenSCENARIO 1\.2, 1\.3; the FileHeader states 1\.0/);
    assert.deepEqual(await schemaDiagnostics(uri12), []);
  });

  it('completion of child elements differs between a 1.0 and a 1.2 file, with snippets filling required attributes', async () => {
    const marked = (minor: string) => cursor(scenario(minor, { root: '  <|\n' }));
    const results: Record<string, CompletionItem[]> = {};
    for (const minor of ['0', '2']) {
      const { text, position } = marked(minor);
      const uri = await client.open(fileUri(path.join(root, `complete_${minor}.xosc`)), text);
      results[minor] = itemsOf(await client.request('textDocument/completion', client.at(uri, position)));
    }
    assert.ok(labels(results['2']).includes('VariableDeclarations'), labels(results['2']).join(', '));
    assert.ok(!labels(results['0']).includes('VariableDeclarations'), labels(results['0']).join(', '));
    assert.ok(labels(results['0']).includes('CatalogLocations'));
    // Actions of Init: a child snippet that fills the required attributes.
    const { text, position } = cursor(scenario('0', { actions: '        <|\n' }));
    const uri = await client.open(fileUri(path.join(root, 'complete_actions.xosc')), text);
    const items = itemsOf(await client.request('textDocument/completion', client.at(uri, position)));
    assert.deepEqual(labels(items), ['GlobalAction', 'UserDefinedAction', 'Private']);
    const privateItem = items.find((item) => item.label === 'Private');
    // With its required child, so that the inserted element is valid (the editor indents the tab).
    assert.equal((privateItem?.textEdit as TextEdit).newText, '<Private entityRef="${1}">\n\t<PrivateAction/>$0\n</Private>');
    assert.equal((items.find((item) => item.label === 'GlobalAction')?.textEdit as TextEdit).newText, '<GlobalAction>$0</GlobalAction>');
  });

  it('completion in a half-typed file: the required child first, in content-model order', async () => {
    const text = `<?xml version="1.0"?>\n<OpenSCENARIO>\n  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="d" author="a"/>\n  <CatalogLocations/>\n  <RoadNetwork/>\n  <Entities/>\n  <Storyboard>\n    <Init><Actions/></Init>\n    <`;
    const uri = await client.open(fileUri(path.join(root, 'half.xosc')), text);
    const items = itemsOf(await client.request('textDocument/completion', client.at(uri, positionAt(text, text.length))));
    const sorted = [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? ''));
    // OpenSCENARIO 1.0 wants at least one Story before the StopTrigger.
    assert.deepEqual(labels(sorted), ['Story']);
    assert.match(sorted[0].detail ?? '', /^required/);
  });

  it('completes attribute names (required first, written ones left out), enumeration values and $parameters', async () => {
    const attributes = cursor(
      scenario('0').replace('<ParameterDeclaration name="TargetSpeed"', '<ParameterDeclaration name="TargetSpeed" |'),
    );
    const uri = await client.open(fileUri(path.join(root, 'attributes.xosc')), attributes.text);
    const names = itemsOf(await client.request('textDocument/completion', client.at(uri, attributes.position)));
    assert.deepEqual(labels(names), []);
    const open = cursor(
      scenario('0', {
        actions:
          '        <Private entityRef="ego"><PrivateAction><LongitudinalAction><SpeedAction |/></LongitudinalAction></PrivateAction></Private>\n',
      }),
    );
    const uri2 = await client.open(fileUri(path.join(root, 'attributes2.xosc')), open.text);
    assert.deepEqual(labels(await client.request('textDocument/completion', client.at(uri2, open.position))), []);
    const dynamics = scenario('0', {
      actions:
        '        <Private entityRef="ego"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="" value="$" /></SpeedAction></LongitudinalAction></PrivateAction></Private>\n',
    });
    const uri3 = await client.open(fileUri(path.join(root, 'values.xosc')), dynamics);
    const shapes = labels(await client.request('textDocument/completion', client.at(uri3, at(dynamics, 'dynamicsShape="|"'))));
    assert.deepEqual(shapes.sort(), ['cubic', 'linear', 'sinusoidal', 'step', '$TargetSpeed'].sort());
    const value = labels(await client.request('textDocument/completion', client.at(uri3, at(dynamics, 'value="$|"'))));
    assert.deepEqual(value, ['$TargetSpeed']);
    const names3 = itemsOf(await client.request('textDocument/completion', client.at(uri3, at(dynamics, 'value="$" |/>'))));
    const sorted = [...names3].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? ''));
    assert.deepEqual(labels(sorted), ['dynamicsDimension']);
    assert.equal((sorted[0].textEdit as TextEdit).newText, 'dynamicsDimension="${1|distance,rate,time|}"');
  });

  it('hover names the type, the allowed values, whether required, and the version that introduced or deprecated it', async () => {
    const text = scenario('2', {
      actions:
        '        <Private entityRef="ego"><PrivateAction><ActivateControllerAction longitudinal="true"/></PrivateAction></Private>\n',
    });
    const uri = await client.open(fileUri(path.join(root, 'hover.xosc')), text);
    const at = (needle: string, shift = 1) => positionAt(text, text.indexOf(needle) + shift);
    const element = await client.request<Hover>('textDocument/hover', client.at(uri, at('<ActivateControllerAction')));
    const elementText = (element.contents as MarkupContent).value;
    assert.match(
      elementText,
      /\*\*`<ActivateControllerAction>`\*\* — type `ActivateControllerAction`, minOccurs 0, maxOccurs 1 in `<PrivateAction>`/,
    );
    assert.match(elementText, /\*\*deprecated\*\* since 1\.1/);
    const attribute = await client.request<Hover>('textDocument/hover', client.at(uri, at('longitudinal=')));
    assert.match((attribute.contents as MarkupContent).value, /ActivateControllerAction\.longitudinal\*\* — `Boolean`, optional/);
    assert.match((attribute.contents as MarkupContent).value, /xsd:boolean, a \\\$parameter, an \\\$\{expression\}/);
    const variables = await client.request<Hover>(
      'textDocument/hover',
      client.at(
        await client.open(fileUri(path.join(root, 'hover12.xosc')), scenario('2', { root: '  <VariableDeclarations/>\n' })),
        positionAt(
          scenario('2', { root: '  <VariableDeclarations/>\n' }),
          scenario('2', { root: '  <VariableDeclarations/>\n' }).indexOf('<VariableDeclarations') + 2,
        ),
      ),
    );
    assert.match((variables.contents as MarkupContent).value, /introduced in OpenSCENARIO 1\.2 \(this file: 1\.2\)/);
  });

  it('reports values, order, cardinality, missing and deprecated precisely, with quick fixes', async () => {
    const text = scenario('2', {
      actions:
        '        <Private entityRef="ego"><PrivateAction><ActivateControllerAction longitudinal="yes"/></PrivateAction></Private>\n' +
        '        <Private entityRef="ego"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionTarget><AbsoluteTargetSpeed value="$TargetSpeed"/></SpeedActionTarget><SpeedActionDynamics dynamicsShape="stepp" value="${$TargetSpeed * 2}" dynamicsDimension="time"/></SpeedAction></LongitudinalAction></PrivateAction></Private>\n' +
        '        <Private entityRef="ego"><PrivateAction><TeleportAction><Position><WorldPosition x="1" y="2"/></Position><Position/></TeleportAction></PrivateAction></Private>\n' +
        '        <Private><PrivateAction><LaneChangeActoin/></PrivateAction></Private>\n' +
        '        <UserDefinedAction><CustomCommandAction type="log">hello</CustomCommandAction></UserDefinedAction>\n',
    });
    const uri = await client.open(fileUri(path.join(root, 'broken.xosc')), text);
    const diagnostics = await schemaDiagnostics(uri, (list) => list.length > 0);
    const summary = diagnostics.map((diagnostic) => `${problemCodeOf(diagnostic)} ${textAt(text, diagnostic.range)}`).sort();
    assert.deepEqual(summary, [
      'schema-cardinality Position',
      'schema-deprecated ActivateControllerAction',
      'schema-missing-attribute Private',
      'schema-order UserDefinedAction',
      'schema-unknown-element LaneChangeActoin',
      'schema-value stepp',
      'schema-value yes',
    ]);
    const deprecated = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'schema-deprecated') as Diagnostic;
    assert.deepEqual(deprecated.tags, [DiagnosticTag.Deprecated]);
    const fixes = async (code: string, written?: string) => {
      const diagnostic = diagnostics.find(
        (candidate) => problemCodeOf(candidate) === code && (written === undefined || textAt(text, candidate.range) === written),
      ) as Diagnostic;
      return client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
    };
    const rename = (await fixes('schema-unknown-element'))[0];
    // A PrivateAction holds a LateralAction (which holds the LaneChangeAction): the closest valid name here.
    assert.equal(rename.title, 'Change to <LateralAction>');
    const renamed = applyEdits(text, rename.edit?.changes?.[uri] ?? []);
    assert.ok(renamed.includes('<PrivateAction><LateralAction/></PrivateAction>'));
    const value = await fixes('schema-value', 'stepp');
    assert.deepEqual(
      value.map((action) => action.title),
      ["Change to 'step'"],
    );
    assert.deepEqual(await fixes('schema-value', 'yes'), []);
    const missing = (await fixes('schema-missing-attribute'))[0];
    assert.equal(missing.title, "Add 'entityRef'");
    assert.ok(applyEdits(text, missing.edit?.changes?.[uri] ?? []).includes('<Private entityRef=""><PrivateAction><LaneChangeActoin/>'));
  });

  it('inserts missing required elements with a quick fix, and the result validates', async () => {
    const text = scenario('0').replace('    <StopTrigger/>\n', '');
    const uri = await client.open(fileUri(path.join(root, 'missing.xosc')), text);
    const diagnostics = await schemaDiagnostics(uri, (list) => list.length > 0);
    assert.equal(diagnostics.length, 1);
    assert.equal(messageOf(diagnostics[0]), '<Storyboard> lacks the required element <StopTrigger>');
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: diagnostics[0].range,
      context: { diagnostics },
    });
    const fixed = applyEdits(text, actions[0].edit?.changes?.[uri] ?? []);
    assert.equal(fixed, scenario('0'));
  });

  it('the quick fix for a missing element inserts a minimal valid skeleton: required attributes and children, indented', async () => {
    const full = scenario('0');
    const storyStart = full.indexOf('    <Story name="story">');
    const storyEnd = full.indexOf('    <StopTrigger/>');
    const cases = [
      {
        name: 'Init',
        text: full.replace('    <Init>\n      <Actions>\n      </Actions>\n    </Init>\n', ''),
        inserted: '    <Init>\n      <Actions/>\n    </Init>\n',
      },
      {
        name: 'Story',
        text: full.slice(0, storyStart) + full.slice(storyEnd),
        inserted:
          '    <Story name="">\n      <Act name="">\n        <ManeuverGroup maximumExecutionCount="0" name="">\n          <Actors selectTriggeringEntities="false"/>\n        </ManeuverGroup>\n        <StartTrigger/>\n      </Act>\n    </Story>\n',
      },
    ];
    for (const { name, text, inserted } of cases) {
      const uri = await client.open(fileUri(path.join(root, `skeleton_${name}.xosc`)), text);
      const diagnostics = await schemaDiagnostics(uri, (list) => list.length > 0);
      assert.equal(diagnostics.length, 1, name);
      assert.match(messageOf(diagnostics[0]), new RegExp(`^<Storyboard> lacks the required element <${name}>`));
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri },
        range: diagnostics[0].range,
        context: { diagnostics },
      });
      assert.equal(actions[0].title, `Insert <${name}>`);
      const fixed = applyEdits(text, actions[0].edit?.changes?.[uri] ?? []);
      assert.ok(fixed.includes(inserted), fixed);
      // Re-validated with the core validator: nothing is missing in what was inserted (the empty names are values to fill in).
      const findings = checkSchema(parseXml(fixed), { modular: true }).findings.map(
        (finding) => `${finding.code} <${finding.element.name}>`,
      );
      assert.deepEqual(findings, [], name);
      const after = await client.open(fileUri(path.join(root, `skeleton_${name}_fixed.xosc`)), fixed);
      assert.deepEqual(await schemaDiagnostics(after), [], name);
    }
    // A self-closing parent is opened, its skeleton child indented one level below it.
    const selfClosing = full.replace('    <Init>\n      <Actions>\n      </Actions>\n    </Init>\n', '    <Init/>\n');
    const uri = await client.open(fileUri(path.join(root, 'skeleton_self_closing.xosc')), selfClosing);
    const diagnostics = await schemaDiagnostics(uri, (list) => list.length > 0);
    assert.deepEqual(diagnostics.map(messageOf), ['<Init> lacks the required element <Actions>']);
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: diagnostics[0].range,
      context: { diagnostics },
    });
    const fixed = applyEdits(selfClosing, actions[0].edit?.changes?.[uri] ?? []);
    assert.ok(fixed.includes('    <Init>\n      <Actions/>\n    </Init>\n    <Story'), fixed);
  });

  it('the setting pins the version: a 1.0 file read as 1.2 accepts VariableDeclarations', async () => {
    const text = scenario('0', { root: '  <VariableDeclarations/>\n' });
    const uri = await client.open(fileUri(path.join(root, 'pinned.xosc')), text);
    await schemaDiagnostics(uri, (list) => list.length === 1);
    await client.settingsChanged({ schema: { version: '1.2' } });
    assert.deepEqual(await schemaDiagnostics(uri, (list) => list.length === 0), []);
    await client.settingsChanged({});
    await schemaDiagnostics(uri, (list) => list.length === 1);
  });

  it('the modular extension is accepted where SPEC puts it, and nowhere else', async () => {
    const text = scenario('0')
      .replace(
        '<Actors selectTriggeringEntities="false"/>',
        '<Actors selectTriggeringEntities="false"/>\n          <ScenarioReference scenarioFileName="other.xosc"><ManeuverGroupReference maneuverGroupName="g"><ParameterReference key="k" value="1"/></ManeuverGroupReference></ScenarioReference>',
      )
      .replace('<RoadNetwork/>', '<RoadNetwork parameterAttributes="x"/>');
    const uri = await client.open(fileUri(path.join(root, 'modular.xosc')), text);
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.length > 0);
    // Only the flattener's own findings (the referenced file is missing), no schema complaint.
    assert.ok(
      diagnostics.every((diagnostic) => !String(problemCodeOf(diagnostic)).startsWith('schema-')),
      diagnostics.map(messageOf).join('\n'),
    );
    const misplaced = scenario('0', { actions: '        <ScenarioReference scenarioFileName="x.xosc"/>\n' });
    const uri2 = await client.open(fileUri(path.join(root, 'misplaced.xosc')), misplaced);
    const codes = (await client.diagnosticsOf(uri2, (list) => list.length > 0)).map((diagnostic) => String(problemCodeOf(diagnostic)));
    assert.ok(codes.includes('reference-outside-group'), codes.join(', '));
    assert.ok(!codes.some((code) => code.startsWith('schema-')), codes.join(', '));
  });

  it('deprecated completion items carry the deprecated tag', async () => {
    const { text, position } = cursor(
      scenario('3', { actions: '        <Private entityRef="ego"><PrivateAction><|</PrivateAction></Private>\n' }),
    );
    const uri = await client.open(fileUri(path.join(root, 'deprecated.xosc')), text);
    const items = itemsOf(await client.request('textDocument/completion', client.at(uri, position)));
    const activate = items.find((item) => item.label === 'ActivateControllerAction');
    assert.deepEqual(activate?.tags, [CompletionItemTag.Deprecated]);
  });
});
