import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CompletionItem } from 'vscode-languageserver/node';
import { cursor } from '../support/cursor';
import { MAIN_OVERRIDES, PACKAGE_MAIN, SIMPLE, SIMPLE_EXPRESSION } from './fixtures/scenarios';
import { fileUri, useServer } from './harness';

describe('language server: completion offers what fits, once (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': SIMPLE_EXPRESSION, 'main.xosc': MAIN_OVERRIDES }, 'main.xosc');

  const labelsAt = async (marked: string) => {
    const typed = cursor(marked);
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
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

describe('language server: completion right after opening, through an unpacked package (JSON-RPC)', function () {
  // The package's groups come from its flattened model, which only exists once rendered.
  const server = useServer({ 'inner/main.xosc': PACKAGE_MAIN, 'inner/simple.xosc': SIMPLE, 'other.xosc': SIMPLE }, 'other.xosc');

  it('offers the keys of a group of the package at the first request', async function () {
    const typed = cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="inner.mosc">
    <ManeuverGroupReference maneuverGroupName="Inner.Brake">
      <ParameterReference key="|"`);
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
    assert.ok(items.some((item) => item.label === 'AbsoluteTargetSpeed.value'), items.map((item) => item.label).join(', '));
  });
});
