import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CompletionItem, Hover, Location, MarkupContent } from 'vscode-languageserver/node';
import { mainWithKeys, PACKAGE_MAIN, SIMPLE } from './fixtures/scenarios';
import { fileUri, markers, positionAfter, positionAt, useServer } from './harness';

/** The fixtures' simple scenario with a speed default that is full of Markdown characters. */
const SIMPLE_EXPRESSION = markers(SIMPLE)
  .text.replace('parameterAttributes="value" value="5"', 'parameterAttributes="value" value="${2*$a*$b}"')
  .replace('<Event name="SlowDown"', '<Event name="Slow*Down*"');

/** Overrides of group Brake: a bare `value` (both value attributes) and a more specific key for one of them. */
const MAIN_OVERRIDES = mainWithKeys(['<ParameterReference key="value" value="8"/>', '<ParameterReference key="SimulationTimeCondition.value" value="*9*"/>']);

function lineOf(text: string, needle: string): number {
  return text.slice(0, text.indexOf(needle)).split('\n').length - 1;
}

describe('language server: issue 7 server items (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': SIMPLE_EXPRESSION, 'main.xosc': MAIN_OVERRIDES }, 'main.xosc');

  describe('item 4: a key stands for exactly the attributes it sets', function () {
    it('goes from a bare key only to the attribute no more specific key takes', async function () {
      const locations = await server.client.request<Location[]>('textDocument/definition', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')));
      assert.deepEqual(
        locations.map((location) => `${path.basename(location.uri)}:${location.range.start.line}`),
        [`simple.xosc:${lineOf(SIMPLE_EXPRESSION, '<AbsoluteTargetSpeed')}`],
      );
    });

    it('counts in the hover only the attributes the key sets, naming the one a more specific key takes', async function () {
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /^key `value` sets 1 attribute:\n/);
      assert.match(value, /AbsoluteTargetSpeed\.value`: default `\$\{2\*\$a\*\$b\}` declared at `simple\.xosc:\d+`; takes effect: `8` \(this key\)/);
      assert.match(value, /Matched, but set by a more specific key:\n\n- `[^`]*SimulationTimeCondition\.value`: `\*9\*` from `SimulationTimeCondition\.value` on line 16/);
    });

    it('still goes from the specific key to its attribute', async function () {
      const locations = await server.client.request<Location[]>('textDocument/definition', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="SimulationTime')));
      assert.deepEqual(locations.map((location) => location.range.start.line), [lineOf(SIMPLE_EXPRESSION, '<SimulationTimeCondition')]);
    });
  });

  describe('item 5: hovers show values literally', function () {
    it('shows a default of ${2*$a*$b} as code, not as emphasis', async function () {
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')));
      const value = (hover.contents as MarkupContent).value;
      assert.ok(value.includes('default `${2*$a*$b}`'), value);
      // Outside code spans no Markdown character of a value is left to be read as emphasis.
      const outsideCode = value.replace(/`[^`]*`/g, '');
      assert.ok(!/[*_]/.test(outsideCode), outsideCode);
    });

    it('escapes names in the group hover', async function () {
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'maneuverGroupName="Br')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /^ManeuverGroup \*\*Brake\*\* of `simple\.xosc`/);
      assert.ok(value.includes('- Event **Slow\\*Down\\***: SetSpeed (SpeedAction)'), value);
    });
  });

  describe('item 6: completion offers what fits, once', function () {
    const labelsAt = async (marked: string) => {
      const typed = markers(marked);
      const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
      const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, positionAt(typed.text, typed.offsets[0])));
      await server.client.close(uri);
      return [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? '')).map((item) => item.label);
    };
    const inGroup = (content: string) => `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  ${content}`;

    it('offers each overridable attribute once, in its shortest unambiguous key', async function () {
      const labels = await labelsAt(inGroup(`<ScenarioReference scenarioFileName="simple.xosc">
    <ManeuverGroupReference maneuverGroupName="Brake">
      <ParameterReference key="|"`));
      assert.deepEqual(labels, ['AbsoluteTargetSpeed.value', 'delay', 'missing', 'SimulationTimeCondition.value']);
    });

    it('offers ScenarioReference snippets inside a ManeuverGroup, simple scenarios first', async function () {
      const labels = await labelsAt(inGroup('<|'));
      assert.deepEqual(labels, ['ScenarioReference simple.xosc Brake', 'ScenarioReference simple.xosc Wait', 'ScenarioReference main.xosc Outer.Brake']);
    });

    it('offers no ScenarioReference snippet outside a ManeuverGroup', async function () {
      assert.deepEqual(await labelsAt('<OpenSCENARIO><Storyboard><Init><Actions>\n  <|'), []);
      assert.deepEqual(await labelsAt(inGroup('<Maneuver name="M">\n  <|')), []);
      assert.deepEqual(await labelsAt(inGroup('<Maneuver name="M"></Maneuver>\n  <|')).then((labels) => labels.length), 3);
    });
  });
});

describe('language server: completion right after opening, through an unpacked package (JSON-RPC)', function () {
  // The package's groups come from its flattened model, which only exists once rendered.
  const server = useServer({ 'inner/main.xosc': PACKAGE_MAIN, 'inner/simple.xosc': markers(SIMPLE).text, 'other.xosc': markers(SIMPLE).text }, 'other.xosc');

  it('offers the keys of a group of the package at the first request', async function () {
    const typed = markers(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="inner.mosc">
    <ManeuverGroupReference maneuverGroupName="Inner.Brake">
      <ParameterReference key="|"`);
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, positionAt(typed.text, typed.offsets[0])));
    assert.ok(items.some((item) => item.label === 'AbsoluteTargetSpeed.value'), items.map((item) => item.label).join(', '));
  });
});

describe('language server: duplicate group names (issue 7, item 8; JSON-RPC)', function () {
  const simpleText = markers(SIMPLE).text;
  const waitStart = simpleText.indexOf('        <ManeuverGroup name="Wait"');
  const waitEnd = simpleText.indexOf('</ManeuverGroup>', waitStart) + '</ManeuverGroup>\n'.length;
  const wait = simpleText.slice(waitStart, waitEnd);
  // Wait twice (nothing refers to it) and Brake twice (main.xosc refers to it).
  const duplicated = simpleText.slice(0, waitEnd) + wait + wait.replace('name="Wait"', 'name="Brake"') + simpleText.slice(waitEnd);
  const server = useServer({ 'simple.xosc': duplicated, 'main.xosc': mainWithKeys([]) }, 'main.xosc');

  it('warns on the reference that is ambiguous', async function () {
    const diagnostics = await server.client.diagnosticsOf(server.openUri);
    assert.deepEqual(diagnostics.map((diagnostic) => diagnostic.code), ['ambiguous-group']);
  });

  it('does not warn on duplicate names in a file of its own', async function () {
    const uri = await server.client.openFile(path.join(server.root, 'simple.xosc'));
    const diagnostics = await server.client.diagnosticsOf(uri);
    assert.deepEqual(diagnostics.filter((diagnostic) => diagnostic.code === 'duplicate-group'), []);
    await server.client.close(uri);
  });
});
