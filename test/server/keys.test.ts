import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CodeAction, CompletionItem, Diagnostic, Hover, Location, MarkupContent, TextEdit } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { cursor, positionAfter } from '../support/cursor';
import { DOTTED, MAIN, MAIN_OVERRIDES, SIMPLE, SIMPLE_EXPRESSION } from './fixtures/scenarios';
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

/** The fixtures' simple scenario with a second Event of the same shape in Brake's Maneuver (a speed of 12 at 4 s). */
const TWO_EVENTS = (() => {
  const start = SIMPLE.indexOf('            <Event name="SlowDown"');
  const end = SIMPLE.indexOf('</Event>', start) + '</Event>\n'.length;
  const event = SIMPLE.slice(start, end);
  const again = event.replace('name="SlowDown"', 'name="SpeedUp"').replace('value="5"', 'value="12"').replace('value="2"', 'value="4"');
  return SIMPLE.slice(0, end) + again + SIMPLE.slice(end);
})();

describe('language server: keys of two Events of one shape (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': TWO_EVENTS, 'main.xosc': MAIN }, 'main.xosc');
  const speed = 'Action.PrivateAction.LongitudinalAction.SpeedAction.SpeedActionTarget.AbsoluteTargetSpeed.value';

  async function keysOffered(given: string[]): Promise<CompletionItem[]> {
    const uri = fileUri(path.join(server.root, 'typing.xosc'));
    const typed =
      cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
<ScenarioReference scenarioFileName="simple.xosc">
  <ManeuverGroupReference maneuverGroupName="Brake">
${given.map((key) => `    <ParameterReference key="${key}" value="1"/>\n`).join('')}    <ParameterReference key="|"`);
    await server.client.open(uri, typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
    await server.client.close(uri);
    return items;
  }

  it('offers each Event its own positioned key after the key that sets both', async function () {
    const items = await keysOffered([]);
    const sorted = [...items].sort((a, b) => String(a.sortText).localeCompare(String(b.sortText)));
    const labels = sorted.map((item) => item.label);
    const both = labels.indexOf('AbsoluteTargetSpeed.value');
    assert.ok(both >= 0, labels.join(', '));
    assert.deepEqual(labels.slice(both, both + 3), ['AbsoluteTargetSpeed.value', `Event[1].${speed}`, `Event[2].${speed}`]);
    const detailOf = (label: string) => sorted.find((item) => item.label === label)?.detail ?? '';
    assert.match(detailOf('AbsoluteTargetSpeed.value'), /^default 5 \/ 12 — simple\.xosc:\d+ \(sets 2 attributes\)$/);
    assert.match(detailOf(`Event[1].${speed}`), /^default 5 — simple\.xosc:\d+ \(this one alone of the 2 the plain key sets\)$/);
    assert.match(detailOf(`Event[2].${speed}`), /^default 12 — /);
    // The conditions of the two Events too, each with its own position.
    assert.ok(
      labels.includes('Event[2].StartTrigger.ConditionGroup.Condition.ByValueCondition.SimulationTimeCondition.value'),
      labels.join(', '),
    );
  });

  it('leaves out the Event a key already sets, and the key that would set both', async function () {
    const labels = (await keysOffered([`Event[2].${speed}`])).map((item) => item.label);
    assert.ok(labels.includes(`Event[1].${speed}`), labels.join(', '));
    assert.ok(!labels.includes(`Event[2].${speed}`), labels.join(', '));
    assert.ok(!labels.includes('AbsoluteTargetSpeed.value'), labels.join(', '));
  });

  it('a positioned key it offers sets that Event alone, with no problem reported', async function () {
    for (const [position, defaultValue] of [
      [1, '5'],
      [2, '12'],
    ] as const) {
      const uri = fileUri(path.join(server.root, `positioned${position}.xosc`));
      const text = MAIN_OVERRIDES.replace(
        /<ParameterReference key="value" value="8"\/>\s*<ParameterReference key="SimulationTimeCondition.value" value="9"\/>/,
        `<ParameterReference key="Event[${position}].${speed}" value="30"/>`,
      );
      assert.ok(text.includes(`Event[${position}]`));
      await server.client.open(uri, text);
      const diagnostics = await server.client.diagnosticsOf(uri);
      assert.deepEqual(
        diagnostics.map((diagnostic) => `${problemCodeOf(diagnostic)}: ${diagnostic.message}`),
        [],
      );
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(uri, positionAfter(text, 'key="Ev')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, new RegExp(`^key \`Event\\[${position}\\]\\.[^\`]*\` sets 1 attribute:\\n`));
      assert.ok(value.includes(`default \`${defaultValue}\``), value);
      await server.client.close(uri);
    }
  });
});
