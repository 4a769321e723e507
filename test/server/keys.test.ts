import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CodeAction, CompletionItem, Diagnostic, Hover, Location, MarkupContent, TextEdit } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { cursor, positionAfter } from '../support/cursor';
import { DOTTED, MAIN, MAIN_OVERRIDES, SIMPLE_EXPRESSION } from './fixtures/scenarios';
import { fileUri, useServer } from './harness';

function lineOf(text: string, needle: string): number {
  return text.slice(0, text.indexOf(needle)).split('\n').length - 1;
}

describe('language server: what a key stands for (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': SIMPLE_EXPRESSION, 'main.xosc': MAIN_OVERRIDES }, 'main.xosc');

  describe('a key stands for exactly the attributes it sets', function () {
    it('goes from a bare key only to the attribute no more specific key takes', async function () {
      const locations = await server.client.request<Location[]>(
        'textDocument/definition',
        server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')),
      );
      assert.deepEqual(
        locations.map((location) => `${path.basename(location.uri)}:${location.range.start.line}`),
        [`simple.xosc:${lineOf(SIMPLE_EXPRESSION, '<AbsoluteTargetSpeed')}`],
      );
    });

    it('counts in the hover only the attributes the key sets, naming the one a more specific key takes', async function () {
      const hover = await server.client.request<Hover>(
        'textDocument/hover',
        server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')),
      );
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /^key `value` sets 1 attribute:\n/);
      assert.match(
        value,
        /AbsoluteTargetSpeed\.value`: default `\$\{2\*\$a\*\$b\}` declared at `simple\.xosc:\d+`; takes effect: `8` \(this key\)/,
      );
      assert.match(
        value,
        /Matched, but set by a more specific key:\n\n- `[^`]*SimulationTimeCondition\.value`: `9` from `SimulationTimeCondition\.value` on line \d+/,
      );
    });

    it('still goes from the specific key to its attribute', async function () {
      const locations = await server.client.request<Location[]>(
        'textDocument/definition',
        server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="SimulationTime')),
      );
      assert.deepEqual(
        locations.map((location) => location.range.start.line),
        [lineOf(SIMPLE_EXPRESSION, '<SimulationTimeCondition')],
      );
    });
  });

  describe('hovers show values literally', function () {
    it('shows a default of ${2*$a*$b} as code, not as emphasis', async function () {
      const hover = await server.client.request<Hover>(
        'textDocument/hover',
        server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')),
      );
      const value = (hover.contents as MarkupContent).value;
      assert.ok(value.includes('default `${2*$a*$b}`'), value);
      // Outside code spans no Markdown character of a value is left to be read as emphasis.
      const outsideCode = value.replace(/`[^`]*`/g, '');
      assert.ok(!/[*_]/.test(outsideCode), outsideCode);
    });

    it('escapes names in the group hover', async function () {
      const hover = await server.client.request<Hover>(
        'textDocument/hover',
        server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'maneuverGroupName="Br')),
      );
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /^ManeuverGroup \*\*Brake\*\* of `simple\.xosc`/);
      assert.ok(value.includes('- Event **Slow\\*Down\\***: SetSpeed (SpeedAction)'), value);
    });
  });
});

describe('language server: a simple scenario listing a dotted name in parameterAttributes (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': DOTTED, 'main.xosc': MAIN }, 'main.xosc');

  it('still completes the keys the group offers', async function () {
    const uri = fileUri(path.join(server.root, 'typing.xosc'));
    const typed =
      cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
<ScenarioReference scenarioFileName="simple.xosc">
  <ManeuverGroupReference maneuverGroupName="Brake">
    <ParameterReference key="|"`);
    await server.client.open(uri, typed.text);
    const items = await server.client.request<CompletionItem[]>(
      'textDocument/completion',
      server.client.at(uri, positionAfter(typed.text, 'key="')),
    );
    const labels = items.map((item) => item.label);
    // With the dotted name unreachable, the condition's value is the only 'value' left.
    assert.deepEqual([...labels].sort(), ['delay', 'missing', 'value']);
    assert.ok(!labels.some((label) => label.includes('AbsoluteTargetSpeed')), 'no key reaches the dotted name');
    await server.client.close(uri);
  });

  it('still offers the ScenarioReference snippet', async function () {
    const uri = fileUri(path.join(server.root, 'typing.xosc'));
    const typed = `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
<Sce`;
    await server.client.open(uri, typed);
    const items = await server.client.request<CompletionItem[]>(
      'textDocument/completion',
      server.client.at(uri, positionAfter(typed, '<Sce')),
    );
    const snippet = items.find((item) => item.label === 'ScenarioReference simple.xosc Brake');
    assert.ok(snippet, items.map((item) => item.label).join(', '));
    assert.match((snippet.textEdit as TextEdit).newText, /<ParameterReference key="delay" value="\$\{\d+:0\}"\/>/);
    await server.client.close(uri);
  });

  it('still adds the missing keys', async function () {
    const diagnostics = await server.client.diagnosticsOf(server.openUri);
    const diagnostic = diagnostics.find((candidate) => problemCodeOf(candidate) === 'unknown-key') as Diagnostic;
    assert.ok(diagnostic, JSON.stringify(diagnostics.map((candidate) => problemCodeOf(candidate))));
    const actions = await server.client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri: server.openUri },
      range: diagnostic.range,
      context: { diagnostics: [diagnostic] },
    });
    assert.ok(
      actions.some((action) => /missing key/.test(action.title)),
      actions.map((action) => action.title).join(', '),
    );
  });
});
