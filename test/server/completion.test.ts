import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CompletionItem, TextEdit } from 'vscode-languageserver/node';
import { SCHEMA_VERSIONS } from '../../server/src/core/schema/model';
import { schemaFindingWords } from '../../server/src/core/diagnostics/schemaFindings';
import { checkSchema } from '../../server/src/core/schema/validate';
import { parseXml } from '../../server/src/core/xml';
import { cursor } from '../support/cursor';
import { scenario, simpleGroup } from '../support/fixtures';
import { SERVER_WAIT_MS } from '../support/wait';
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
  const inGroup = (
    content: string,
  ) => `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
${content}`;

  it('offers each overridable attribute once, in its shortest unambiguous key', async function () {
    const labels = await labelsAt(
      inGroup(`<ScenarioReference scenarioFileName="simple.xosc">
  <ManeuverGroupReference maneuverGroupName="Brake">
    <ParameterReference key="|"`),
    );
    assert.deepEqual(labels, ['AbsoluteTargetSpeed.value', 'delay', 'missing', 'SimulationTimeCondition.value']);
  });

  it('offers ScenarioReference snippets inside a ManeuverGroup, simple scenarios first', async function () {
    const labels = await labelsAt(inGroup('<|'));
    // The built-in library's modules come after the workspace's own files.
    const own = labels.filter((label) => !label.startsWith('ScenarioReference library:'));
    assert.deepEqual(own, [
      'ScenarioReference simple.xosc Brake',
      'ScenarioReference simple.xosc Wait',
      'ScenarioReference main.xosc Outer.Brake',
    ]);
    assert.deepEqual(labels.slice(0, own.length), own);
    assert.ok(labels.includes('ScenarioReference library:cut-in CutIn'), labels.join('\n'));
  });

  it('offers no ScenarioReference snippet outside a ManeuverGroup', async function () {
    assert.deepEqual(await labelsAt('<OpenSCENARIO><Storyboard><Init><Actions>\n  <|'), []);
    assert.deepEqual(await labelsAt(inGroup('<Maneuver name="M">\n  <|')), []);
    const afterManeuver = await labelsAt(inGroup('<Maneuver name="M"></Maneuver>\n  <|'));
    assert.deepEqual(afterManeuver.filter((label) => !label.startsWith('ScenarioReference library:')).length, 3);
  });

  it('offers ParameterReference inside a ManeuverGroupReference: an empty one, then each key not given yet with its default', async function () {
    const typed = cursor(
      inGroup(`<ScenarioReference scenarioFileName="simple.xosc">
  <ManeuverGroupReference maneuverGroupName="Brake">
    <ParameterReference key="delay" value="1"/>
    <|`),
    );
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
    await server.client.close(uri);
    const sorted = [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? ''));
    assert.deepEqual(
      sorted.map((item) => item.label),
      [
        'ParameterReference',
        'ParameterReference AbsoluteTargetSpeed.value',
        'ParameterReference missing',
        'ParameterReference SimulationTimeCondition.value',
      ],
    );
    assert.equal((sorted[0].textEdit as TextEdit).newText, '<ParameterReference key="$1" value="$2"/>$0');
    assert.equal(sorted[0].filterText, '<ParameterReference');
    assert.equal(
      (sorted[1].textEdit as TextEdit).newText,
      '<ParameterReference key="AbsoluteTargetSpeed.value" value="${1:\\${2*\\$a*\\$b\\}}"/>$0',
    );
  });

  it('offers parameterAttributes as an attribute name on the elements of a ManeuverGroup, once', async function () {
    const inside = await labelsAt(
      inGroup(
        '<Maneuver name="M"><Event name="E" priority="overwrite"><Action name="A"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionTarget><AbsoluteTargetSpeed value="5" |/>',
      ),
    );
    assert.ok(inside.includes('parameterAttributes'), inside.join(', '));
    const written = await labelsAt(inGroup('<Maneuver name="M"><Event parameterAttributes="priority" name="E" |'));
    assert.ok(!written.includes('parameterAttributes'), written.join(', '));
    const outside = await labelsAt('<OpenSCENARIO><Storyboard><Init><Actions><Private entityRef="ego" |');
    assert.ok(!outside.includes('parameterAttributes'), outside.join(', '));
    const onReference = await labelsAt(inGroup('<ScenarioReference |'));
    assert.ok(!onReference.includes('parameterAttributes'), onReference.join(', '));
  });
});

describe('language server: completion right after opening, through an unpacked package (JSON-RPC)', function () {
  // The package's groups come from its flattened model, which only exists once rendered.
  const server = useServer({ 'inner/main.xosc': PACKAGE_MAIN, 'inner/simple.xosc': SIMPLE, 'other.xosc': SIMPLE }, 'other.xosc');

  it('offers the keys of a group of the package at the first request', async function () {
    const typed =
      cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="inner.mosc">
    <ManeuverGroupReference maneuverGroupName="Inner.Brake">
      <ParameterReference key="|"`);
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
    assert.ok(
      items.some((item) => item.label === 'AbsoluteTargetSpeed.value'),
      items.map((item) => item.label).join(', '),
    );
  });
});

/** The text a snippet inserts when each tab stop keeps its default (a choice its first value). */
function expandSnippet(snippet: string): string {
  return snippet
    .replace(/\$\{\d+\|([^,|]*)[^}]*\}/g, '$1')
    .replace(/\$\{\d+:((?:\\.|[^}\\])*)\}/g, '$1')
    .replace(/\$\{\d+\}|\$\d+/g, '')
    .replace(/\\([$}\\])/g, '$1');
}

describe('language server: completion in an empty file, with schema support on (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': SIMPLE }, 'simple.xosc', { schema: true });

  it('offers a whole scenario skeleton in an empty file, of the version the setting chooses (latest when auto)', async function () {
    const skeletonAt = async (marked: string) => {
      const typed = cursor(marked);
      const uri = await server.client.open(fileUri(path.join(server.root, 'empty.xosc')), typed.text);
      const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
      await server.client.close(uri);
      return items.find((item) => /^OpenSCENARIO \d\.\d scenario$/.test(item.label));
    };
    for (const marked of ['|', '<|', '<?xml version="1.0" encoding="UTF-8"?>\n|', '<!-- a new scenario -->\n<Open|']) {
      const skeleton = await skeletonAt(marked);
      assert.ok(skeleton, JSON.stringify(marked));
      assert.equal(skeleton.label, 'OpenSCENARIO 1.3 scenario');
      const inserted = (skeleton.textEdit as TextEdit).newText;
      assert.equal(inserted.startsWith('<?xml'), !marked.includes('<?xml'), marked);
      assert.match(inserted, /<FileHeader [^>]*revMajor="1" revMinor="3"/);
      assert.match(inserted, /date="\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d"/);
      for (const element of [
        '<OpenSCENARIO>',
        '<CatalogLocations/>',
        '<RoadNetwork/>',
        '<Entities/>',
        '<Storyboard>',
        '<Init>',
        '</OpenSCENARIO>',
      ])
        assert.ok(inserted.includes(element), `${element} in ${inserted}`);
    }
    const started = cursor('<OpenSCENARIO>\n  <|');
    const uri = await server.client.open(fileUri(path.join(server.root, 'started.xosc')), started.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, started.position));
    await server.client.close(uri);
    assert.ok(!items.some((item) => item.label.endsWith(' scenario')), 'no skeleton inside a scenario');
    await server.client.settingsChanged({ schema: { version: '1.0' } });
    let pinned: CompletionItem | undefined;
    const deadline = Date.now() + SERVER_WAIT_MS;
    while ((pinned = await skeletonAt('|'))?.label !== 'OpenSCENARIO 1.0 scenario' && Date.now() < deadline)
      await new Promise((resolve) => setTimeout(resolve, 50));
    assert.equal(pinned?.label, 'OpenSCENARIO 1.0 scenario');
    assert.match((pinned.textEdit as TextEdit).newText, /revMajor="1" revMinor="0"/);
    await server.client.settingsChanged({});
  });

  it('the skeleton of each version, inserted as the editor expands it, has no schema problem and is complete (1.0 to 1.3)', async function () {
    for (const version of SCHEMA_VERSIONS) {
      await server.client.settingsChanged({ schema: { version } });
      const skeletonOffered = async () => {
        const typed = cursor('|');
        const uri = await server.client.open(fileUri(path.join(server.root, 'empty.xosc')), typed.text);
        const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
        await server.client.close(uri);
        return items.find((item) => item.label === `OpenSCENARIO ${version} scenario`);
      };
      // The setting reaches the server asynchronously.
      let skeleton = await skeletonOffered();
      for (const deadline = Date.now() + SERVER_WAIT_MS; !skeleton && Date.now() < deadline; skeleton = await skeletonOffered())
        await new Promise((resolve) => setTimeout(resolve, 50));
      assert.ok(skeleton, version);
      const inserted = expandSnippet((skeleton.textEdit as TextEdit).newText);
      for (const element of [
        '<FileHeader ',
        '<ParameterDeclarations/>',
        '<CatalogLocations/>',
        '<RoadNetwork/>',
        '<Entities/>',
        '<Init>',
        '<StopTrigger/>',
      ])
        assert.ok(inserted.includes(element), `${version}: ${element} in\n${inserted}`);
      const date = /date="([^"]+)"/.exec(inserted)?.[1] ?? '';
      assert.ok(Math.abs(Date.parse(`${date}Z`) - Date.now()) < 60_000, `${version}: today's date, not ${date}`);
      const findings = checkSchema(parseXml(inserted), { modular: true }).findings;
      assert.deepEqual(
        findings.map((finding) => `${finding.code} ${schemaFindingWords(finding).message}`),
        [],
        `${version}:\n${inserted}`,
      );
    }
    await server.client.settingsChanged({});
  });
});

describe('language server: a ScenarioReference for a group already used in the Act (JSON-RPC)', function () {
  // The imported group's actor is car; one key names that actor, one names ego.
  const simple = scenario(
    simpleGroup(
      'CutIn',
      `              <TriggeringEntities><EntityRef parameterAttributes="entityRef" entityRef="car"/></TriggeringEntities>\n`,
    ),
    ['ego', 'car'],
  );
  const server = useServer({ 'simple.xosc': simple }, 'simple.xosc');
  const firstGroup = `<ManeuverGroup name="Cut" maximumExecutionCount="1"><Actors><EntityRef entityRef="car"/></Actors>
  <ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="CutIn"/></ScenarioReference>
</ManeuverGroup>`;
  const itemAt = async (marked: string) => {
    const typed = cursor(marked);
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, typed.position));
    await server.client.close(uri);
    const item = items.find((candidate) => candidate.label === 'ScenarioReference simple.xosc CutIn');
    assert.ok(item, items.map((candidate) => candidate.label).join('\n'));
    return { item, text: typed.text, inserted: expandSnippet((item.textEdit as TextEdit).newText) };
  };

  it("proposes a name unique in the Act for the group, and the group's own actor for keys that name the imported group's actor", async function () {
    const { item, text, inserted } = await itemAt(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A">${firstGroup}
<ManeuverGroup name="Cut" maximumExecutionCount="1"><Actors><EntityRef entityRef="truck"/></Actors>
  <|`);
    assert.match(inserted, /<ParameterReference key="TriggeringEntities\.EntityRef\.entityRef" value="truck"\/>/);
    assert.match(inserted, /<ParameterReference key="Condition\.EntityRef\.entityRef" value="ego"\/>/);
    assert.match(inserted, /<ParameterReference key="value" value="10"\/>/);
    const [rename] = item.additionalTextEdits ?? [];
    assert.equal(rename?.newText, 'Cut2');
    const second = text.lastIndexOf('name="Cut"') + 'name="'.length;
    assert.deepEqual(rename.range.start, { line: 3, character: second - text.lastIndexOf('\n', second) - 1 });
    assert.equal(rename.range.end.character - rename.range.start.character, 'Cut'.length);
    assert.match(item.detail ?? '', /keys naming its actor car name truck; renames this ManeuverGroup Cut2 \(Cut is taken in its Act\)/);
  });

  it('leaves a name of its own and the defaults of a group whose actor is the imported one', async function () {
    const { item, inserted } = await itemAt(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A">${firstGroup}
<ManeuverGroup name="Other" maximumExecutionCount="1"><Actors><EntityRef entityRef="car"/></Actors>
  <|`);
    assert.equal(item.additionalTextEdits, undefined);
    assert.match(inserted, /key="TriggeringEntities\.EntityRef\.entityRef" value="car"/);
    // Names are unique per Act: a group of another Act may have the same name.
    const { item: elsewhere } = await itemAt(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A">${firstGroup}</Act><Act name="B">
<ManeuverGroup name="Cut" maximumExecutionCount="1"><Actors><EntityRef entityRef="truck"/></Actors>
  <|`);
    assert.equal(elsewhere.additionalTextEdits, undefined);
  });
});
