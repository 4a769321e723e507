import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import {
  CodeAction,
  CodeLens,
  CompletionItem,
  Diagnostic,
  DiagnosticSeverity,
  DocumentSymbol,
  Hover,
  Location,
  MarkupContent,
  SymbolInformation,
  TextEdit,
  WorkspaceEdit,
} from 'vscode-languageserver/node';
import { FlattenToFileRequest, FlattenToTextRequest, PackRequest, StructureRequest } from '../../common/src/protocol';
import { CLEAN, cycleFile, MAIN, PACKAGE_MAIN, SIMPLE } from './fixtures/scenarios';
import { fileUri, TestClient } from './harness';
import { problemCodeOf } from '../support/diagnostics';
import { at, cursor } from '../support/cursor';
import { temporaryWorkspace } from '../support/workspace';
import { applyEdits, textAt } from '../support/textEdits';

async function packageBytes(): Promise<Uint8Array> {
  const zip = new JSZip();
  zip.file('main.xosc', PACKAGE_MAIN);
  zip.file('simple.xosc', SIMPLE);
  return zip.generateAsync({ type: 'uint8array' });
}

function messageOf(diagnostic: Diagnostic): string {
  return typeof diagnostic.message === 'string' ? diagnostic.message : diagnostic.message.value;
}

function codes(diagnostics: Diagnostic[]): string[] {
  return diagnostics.map((diagnostic) => String(problemCodeOf(diagnostic))).sort();
}

describe('language server on its own fixtures (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;
  let mainUri: string;
  let simpleUri: string;

  before(async function () {
    root = temporaryWorkspace({
      'simple.xosc': SIMPLE,
      'main.xosc': MAIN,
      'clean.xosc': CLEAN,
      'cycleA.xosc': cycleFile('A', 'cycleB.xosc'),
      'cycleB.xosc': cycleFile('B', 'cycleA.xosc'),
      'pkg.mosc': await packageBytes(),
    });
    client = await TestClient.start({ root });
    await client.indexed();
    mainUri = await client.openFile(path.join(root, 'main.xosc'));
    simpleUri = fileUri(path.join(root, 'simple.xosc'));
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  describe('diagnostics', function () {
    it('reports every problem of the main file with its code, severity and precise range', async function () {
      const diagnostics = await client.diagnosticsOf(mainUri);
      assert.deepEqual(codes(diagnostics), ['missing-file', 'no-default', 'unknown-group', 'unknown-key', 'xosc-fallback']);
      const unknownKey = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'unknown-key') as Diagnostic;
      assert.equal(unknownKey.severity, DiagnosticSeverity.Error, 'an unknown key is an error, as for the CLI');
      assert.equal(textAt(MAIN, unknownKey.range), 'dela');
      assert.match(messageOf(unknownKey), /did you mean 'delay'/);
      const unknownGroup = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'unknown-group') as Diagnostic;
      assert.equal(textAt(MAIN, unknownGroup.range), 'Brak');
      assert.match(messageOf(unknownGroup), /it has: Brake, Wait/);
      const missing = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'missing-file') as Diagnostic;
      assert.equal(missing.severity, DiagnosticSeverity.Error);
      assert.equal(textAt(MAIN, missing.range), 'nowhere.xosc');
      const fallback = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'xosc-fallback') as Diagnostic;
      assert.equal(fallback.severity, DiagnosticSeverity.Warning);
      assert.equal(textAt(MAIN, fallback.range), 'pkg.xosc');
    });

    it('relates a key without default to the listed name in the simple scenario', async function () {
      const diagnostics = await client.diagnosticsOf(mainUri);
      const noDefault = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'no-default') as Diagnostic;
      assert.equal(noDefault.severity, DiagnosticSeverity.Error);
      assert.equal(textAt(MAIN, noDefault.range), 'missing');
      const related = noDefault.relatedInformation?.[0];
      assert.ok(related, 'has a related location');
      assert.equal(related.location.uri, simpleUri);
      assert.equal(textAt(SIMPLE, related.location.range), 'missing');
    });

    it('reports a parameterAttributes entry that names no attribute in the simple scenario', async function () {
      await client.openFile(path.join(root, 'simple.xosc'));
      const diagnostics = await client.diagnosticsOf(simpleUri);
      assert.deepEqual(codes(diagnostics), ['unknown-parameter-attribute']);
      assert.deepEqual(diagnostics[0].range.start, at(SIMPLE, 'parameterAttributes="delay, |missing"'));
      await client.close(simpleUri);
    });

    it('reports a cycle with every file of it', async function () {
      const uri = await client.openFile(path.join(root, 'cycleA.xosc'));
      const diagnostics = await client.diagnosticsOf(uri);
      assert.deepEqual(codes(diagnostics), ['cycle']);
      const [cycle] = diagnostics;
      assert.match(messageOf(cycle), /cycleA\.xosc -> .*cycleB\.xosc -> .*cycleA\.xosc/);
      assert.equal(textAt(cycleFile('A', 'cycleB.xosc'), cycle.range), 'cycleB.xosc');
      const steps = cycle.relatedInformation?.map(
        (item) => `${path.basename(item.location.uri)}:${item.location.range.start.line}:${item.message}`,
      );
      assert.deepEqual(steps, ['cycleA.xosc:2:cycleA.xosc references cycleB.xosc', 'cycleB.xosc:2:cycleB.xosc references cycleA.xosc']);
      await client.close(uri);
    });

    it('the second file of a cycle points each step at its reference, not at 1:1, and names the files as the first does', async function () {
      const first = await client.openFile(path.join(root, 'cycleA.xosc'));
      await client.diagnosticsOf(first);
      const second = await client.openFile(path.join(root, 'cycleB.xosc'));
      const [cycle] = await client.diagnosticsOf(second);
      assert.equal(problemCodeOf(cycle), 'cycle');
      assert.equal(textAt(cycleFile('B', 'cycleA.xosc'), cycle.range), 'cycleA.xosc');
      assert.match(messageOf(cycle), /^reference cycle: cycleA\.xosc -> cycleB\.xosc -> cycleA\.xosc/);
      const steps = cycle.relatedInformation?.map(
        (item) =>
          `${path.basename(item.location.uri)}:${textAt(cycleFile(path.basename(item.location.uri) === 'cycleA.xosc' ? 'A' : 'B', path.basename(item.location.uri) === 'cycleA.xosc' ? 'cycleB.xosc' : 'cycleA.xosc'), item.location.range)}`,
      );
      assert.deepEqual(steps, ['cycleA.xosc:cycleB.xosc', 'cycleB.xosc:cycleA.xosc']);
      await client.close(second);
      await client.close(first);
    });

    it('reports malformed XML with a position, and recovers when it is fixed', async function () {
      const uri = fileUri(path.join(root, 'broken.xosc'));
      await client.open(uri, '<OpenSCENARIO>\n  <Storyboard>\n    <Story name="x">\n</OpenSCENARIO>\n');
      const broken = await client.diagnosticsOf(uri);
      assert.ok(broken.some((diagnostic) => problemCodeOf(diagnostic) === 'xml' && diagnostic.severity === DiagnosticSeverity.Error));
      await client.change(uri, [{ text: '<OpenSCENARIO>\n  <Storyboard/>\n</OpenSCENARIO>\n' }]);
      assert.deepEqual(await client.diagnosticsOf(uri), []);
      await client.close(uri);
    });

    it('re-diagnoses an open main file when a simple scenario it uses is edited (unsaved)', async function () {
      await client.open(simpleUri, SIMPLE);
      const start = at(SIMPLE, '<ManeuverGroup name="|Brake"');
      await client.change(simpleUri, [
        { range: { start, end: { line: start.line, character: start.character + 'Brake'.length } }, text: 'Braking' },
      ]);
      const diagnostics = await client.diagnosticsOf(
        mainUri,
        (list) => list.filter((diagnostic) => problemCodeOf(diagnostic) === 'unknown-group').length === 2,
      );
      assert.ok(diagnostics.some((diagnostic) => /has no ManeuverGroup named 'Brake'; it has: Braking, Wait/.test(messageOf(diagnostic))));
      await client.close(simpleUri);
      await client.diagnosticsOf(
        mainUri,
        (list) => list.filter((diagnostic) => problemCodeOf(diagnostic) === 'unknown-group').length === 1,
      );
    });

    it('follows file changes on disk (didChangeWatchedFiles)', async function () {
      const nowhere = path.join(root, 'nowhere.xosc');
      fs.writeFileSync(nowhere, SIMPLE.replace('name="Brake"', 'name="Any"'));
      await client.connection.sendNotification('workspace/didChangeWatchedFiles', { changes: [{ uri: fileUri(nowhere), type: 1 }] });
      await client.diagnosticsOf(mainUri, (list) => !list.some((diagnostic) => problemCodeOf(diagnostic) === 'missing-file'));
      fs.rmSync(nowhere);
      await client.connection.sendNotification('workspace/didChangeWatchedFiles', { changes: [{ uri: fileUri(nowhere), type: 3 }] });
      await client.diagnosticsOf(mainUri, (list) => list.some((diagnostic) => problemCodeOf(diagnostic) === 'missing-file'));
    });
  });

  describe('definition', function () {
    const definition = (markedSnippet: string, after?: string) =>
      client.request<Location[]>('textDocument/definition', client.at(mainUri, at(MAIN, markedSnippet, after)));

    it('goes from scenarioFileName to the file', async function () {
      const [location] = await definition('scenarioFileName="sim|ple.xosc"', 'name="Outer"');
      assert.equal(location.uri, simpleUri);
    });

    it('goes from scenarioFileName into a package, as the mosc: URI of its main.xosc', async function () {
      const [location] = await definition('scenarioFileName="|pkg.xosc"');
      assert.equal(location.uri, `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`);
    });

    it('goes from maneuverGroupName to the group', async function () {
      const locations = await definition('maneuverGroupName="Br|ake"');
      assert.equal(locations.length, 1);
      assert.equal(locations[0].uri, simpleUri);
      assert.equal(textAt(SIMPLE, locations[0].range), 'Brake');
      assert.deepEqual(locations[0].range.start, at(SIMPLE, '<ManeuverGroup name="|Brake"'));
    });

    it('goes from a key to the attribute it overrides', async function () {
      const locations = await definition('key="AbsoluteTargetSpeed.val|ue"');
      assert.equal(locations.length, 1);
      assert.equal(locations[0].uri, simpleUri);
      assert.equal(textAt(SIMPLE, locations[0].range), 'value="5"');
    });

    it('goes from a dotted group name into the package, as a mosc: URI', async function () {
      const locations = await definition('maneuverGroupName="Inner.Br|ake"');
      assert.equal(locations.length, 1);
      assert.equal(locations[0].uri, `mosc:${path.join(root, 'pkg.mosc')}/simple.xosc`);
      assert.equal(textAt(SIMPLE, locations[0].range), 'Brake');
    });

    it('goes from entityRef to its ScenarioObject', async function () {
      const [location] = await definition('entityRef="ca|r"', 'name="Fourth"');
      assert.equal(location.uri, mainUri);
      assert.equal(textAt(MAIN, location.range), 'car');
      assert.equal(location.range.start.line, 4);
    });

    it('serves a file inside a package opened by its mosc: URI', async function () {
      const uri = `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`;
      await client.open(uri, PACKAGE_MAIN);
      assert.deepEqual(await client.diagnosticsOf(uri), []);
      const text = PACKAGE_MAIN;
      const position = at(text, 'maneuverGroupName="Br|ake"');
      const [location] = await client.request<Location[]>('textDocument/definition', client.at(uri, position));
      assert.equal(location.uri, `mosc:${path.join(root, 'pkg.mosc')}/simple.xosc`);
      const symbols = await client.request<DocumentSymbol[]>('textDocument/documentSymbol', { textDocument: { uri } });
      assert.deepEqual(
        symbols.map((symbol) => symbol.name),
        ['ego', 'Storyboard'],
      );
      await client.close(uri);
    });
  });

  describe('completion', function () {
    const labels = (items: CompletionItem[]) => items.map((item) => item.label);

    it('offers the file names that resolve, packages and siblings', async function () {
      const uri = fileUri(path.join(root, 'typing.xosc'));
      const typed =
        cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="|`);
      await client.open(uri, typed.text);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, typed.position));
      // The built-in library's modules follow the workspace's files (issue 28).
      const [files, modules] = [
        labels(items).filter((label) => !label.startsWith('library:')),
        labels(items).filter((label) => label.startsWith('library:')),
      ];
      await client.close(uri);
      assert.deepEqual(files, ['clean.xosc', 'cycleA.xosc', 'cycleB.xosc', 'main.xosc', 'pkg.mosc', 'simple.xosc']);
      assert.ok(modules.includes('library:cut-in'), labels(items).join(', '));
    });

    it('offers the entries of its own package to a file inside a .mosc', async function () {
      const uri = `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`;
      const typed = PACKAGE_MAIN.replace('scenarioFileName="simple.xosc"', 'scenarioFileName=""');
      await client.open(uri, typed);
      const position = at(typed, 'scenarioFileName="|"');
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, position));
      await client.close(uri);
      assert.deepEqual(
        items.filter((item) => !item.label.startsWith('library:')).map((item) => `${item.label} (${item.detail})`),
        ['simple.xosc (pkg.mosc)'],
      );
    });

    it('offers the default value of the attribute a key reaches', async function () {
      const position = at(MAIN, 'key="AbsoluteTargetSpeed.value" value="|7"');
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(mainUri, position));
      assert.deepEqual(
        items.map((item) => `${item.label}: ${item.detail}`),
        ['5: default of AbsoluteTargetSpeed.value'],
      );
      assert.equal(textAt(MAIN, (items[0].textEdit as TextEdit).range), '7');
    });

    it('offers the entities of the file for entityRef', async function () {
      const items = await client.request<CompletionItem[]>(
        'textDocument/completion',
        client.at(mainUri, at(MAIN, 'entityRef="ca|r"', 'name="Fourth"')),
      );
      assert.deepEqual(
        items.map((item) => item.label),
        ['hero', 'car'],
      );
      assert.equal(textAt(MAIN, (items[0].textEdit as TextEdit).range), 'car');
    });

    it('offers the groups of the referenced file while the document is not well-formed', async function () {
      const uri = fileUri(path.join(root, 'typing.xosc'));
      const typed =
        cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="pkg.mosc">
    <ManeuverGroupReference maneuverGroupName="|`);
      await client.open(uri, typed.text);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, typed.position));
      assert.deepEqual(labels(items), ['Inner.Brake']);
      await client.close(uri);
    });

    it('offers the keys not yet given, shortest unambiguous form first, with default and origin', async function () {
      const uri = fileUri(path.join(root, 'typing.xosc'));
      const typed =
        cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="simple.xosc">
    <ManeuverGroupReference maneuverGroupName="Brake">
      <ParameterReference key="delay" value="1"/>
      <ParameterReference key="|"`);
      await client.open(uri, typed.text);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, typed.position));
      const sorted = [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? ''));
      assert.deepEqual(labels(sorted).slice(0, 3), ['AbsoluteTargetSpeed.value', 'missing', 'SimulationTimeCondition.value']);
      assert.ok(!labels(items).includes('delay'), 'a key already given is left out');
      assert.ok(!labels(items).includes('value'), 'an ambiguous key is never offered');
      const first = sorted[0];
      assert.match(first.detail ?? '', /^default 5 — simple\.xosc:20$/);
      assert.match(sorted[1].detail ?? '', /^default \(none\)/);
      await client.close(uri);
    });

    it("offers the element's own attributes inside parameterAttributes, aware of the comma list", async function () {
      const uri = fileUri(path.join(root, 'simple2.xosc'));
      const typed = cursor(`<OpenSCENARIO><Storyboard>
  <WorldPosition parameterAttributes="x, |" x="1" y="2" z="0" h="3.14"/>
</Storyboard></OpenSCENARIO>`);
      await client.open(uri, typed.text);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, typed.position));
      assert.deepEqual(labels(items), ['y', 'z', 'h']);
      assert.equal(items[0].detail, 'default 2');
      await client.close(uri);
    });

    it('offers a snippet writing a whole ScenarioReference with every key at its default', async function () {
      const uri = fileUri(path.join(root, 'typing.xosc'));
      const typed =
        cursor(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <Sce|`);
      await client.open(uri, typed.text);
      const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, typed.position));
      const snippet = items.find((item) => item.label === 'ScenarioReference simple.xosc Brake');
      assert.ok(snippet, `snippet among ${labels(items).join(', ')}`);
      const newText = (snippet.textEdit as TextEdit).newText;
      assert.match(newText, /^<ScenarioReference scenarioFileName="simple\.xosc">\n/);
      assert.match(newText, /<ParameterReference key="AbsoluteTargetSpeed\.value" value="\$\{1:5\}"\/>/);
      assert.match(newText, /<ParameterReference key="delay" value="\$\{2:0\}"\/>/);
      assert.match(newText, /<ParameterReference key="SimulationTimeCondition\.value" value="\$\{4:2\}"\/>/);
      assert.ok(!newText.includes('key="missing"'), 'an attribute without default gets no key');
      assert.ok(items.some((item) => item.label === 'ScenarioReference pkg.mosc Inner.Brake'));
      await client.close(uri);
    });
  });

  describe('hover', function () {
    it("shows a key's default, the value that takes effect and where each comes from", async function () {
      const hover = await client.request<Hover>('textDocument/hover', client.at(mainUri, at(MAIN, 'key="AbsoluteTargetSpeed.val|ue"')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /default `5` declared at `simple\.xosc:20`/);
      assert.match(value, /takes effect: `7` \(this key\)/);
      assert.equal(textAt(MAIN, hover.range as Location['range']), 'AbsoluteTargetSpeed.value');
    });

    it('shows where a scenarioFileName resolves and the groups it offers', async function () {
      const hover = await client.request<Hover>('textDocument/hover', client.at(mainUri, at(MAIN, 'scenarioFileName="|pkg.xosc"')));
      const value = (hover.contents as MarkupContent).value;
      // Where the name was found, without repeating the name the attribute already shows.
      assert.match(value, /^found at `pkg\.mosc\/main\.xosc`/);
      assert.ok(!value.includes('pkg.xosc'), value);
      assert.match(value, /ManeuverGroups:\n- Inner\\\.Brake$/);
    });

    it('shows what a referenced group does, one line per maneuver and event', async function () {
      const hover = await client.request<Hover>('textDocument/hover', client.at(mainUri, at(MAIN, 'maneuverGroupName="Br|ake"')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /- Maneuver \*\*BrakeManeuver\*\*/);
      assert.match(value, /- Event \*\*SlowDown\*\*: SetSpeed \(SpeedAction\) when SimulationTimeCondition/);
    });
  });

  describe('references and rename', function () {
    it('finds every reference to a group from its declaration', async function () {
      const uri = await client.openFile(path.join(root, 'simple.xosc'));
      const locations = await client.request<Location[]>('textDocument/references', {
        ...client.at(uri, at(SIMPLE, '<ManeuverGroup name="|Brake"')),
        context: { includeDeclaration: false },
      });
      const found = locations.map((location) => `${path.basename(location.uri)}:${location.range.start.line}`).sort();
      assert.deepEqual(found, ['clean.xosc:13', 'main.xosc:14']);
      await client.close(uri);
    });

    it('finds every key that overrides an attribute listed in parameterAttributes', async function () {
      const uri = await client.openFile(path.join(root, 'simple.xosc'));
      const position = at(SIMPLE, 'parameterAttributes="v|alue" value="5"');
      const locations = await client.request<Location[]>('textDocument/references', {
        ...client.at(uri, position),
        context: { includeDeclaration: false },
      });
      const found = locations
        .map((location) => `${path.basename(location.uri)}:${textAt(fs.readFileSync(new URL(location.uri), 'utf8'), location.range)}`)
        .sort();
      assert.deepEqual(found, ['clean.xosc:AbsoluteTargetSpeed.value', 'main.xosc:AbsoluteTargetSpeed.value']);
      // The same from the attribute that holds the default.
      const fromAttribute = await client.request<Location[]>('textDocument/references', {
        ...client.at(uri, at(SIMPLE, 'parameterAttributes="value" va|lue="5"')),
        context: { includeDeclaration: true },
      });
      assert.equal(fromAttribute.length, 3);
      assert.equal(textAt(SIMPLE, fromAttribute[0].range), 'value');
      await client.close(uri);
    });

    it('renames a group and every maneuverGroupName that uses it', async function () {
      const uri = await client.openFile(path.join(root, 'simple.xosc'));
      const position = at(SIMPLE, '<ManeuverGroup name="Br|ake"');
      const prepared = await client.request<{ range: Location['range']; placeholder: string }>(
        'textDocument/prepareRename',
        client.at(uri, position),
      );
      assert.equal(prepared.placeholder, 'Brake');
      const edit = await client.request<WorkspaceEdit>('textDocument/rename', { ...client.at(uri, position), newName: 'Stop' });
      const changes = edit.changes ?? {};
      assert.deepEqual(
        Object.keys(changes)
          .map((key) => path.basename(key))
          .sort(),
        ['clean.xosc', 'main.xosc', 'simple.xosc'],
      );
      assert.match(applyEdits(SIMPLE, changes[uri]), /<ManeuverGroup name="Stop"/);
      assert.match(applyEdits(MAIN, changes[mainUri]), /maneuverGroupName="Stop">/);
      await client.close(uri);
    });

    it('updates scenarioFileName values when a file is renamed', async function () {
      const edit = await client.request<WorkspaceEdit>('workspace/willRenameFiles', {
        files: [{ oldUri: simpleUri, newUri: fileUri(path.join(root, 'braking.xosc')) }],
      });
      const changes = edit.changes ?? {};
      assert.deepEqual(
        Object.keys(changes)
          .map((key) => path.basename(key))
          .sort(),
        ['clean.xosc', 'main.xosc'],
      );
      const renamed = applyEdits(MAIN, changes[mainUri]);
      assert.equal((renamed.match(/scenarioFileName="braking\.xosc"/g) ?? []).length, 2);
      assert.ok(!renamed.includes('"simple.xosc"'));
    });
  });

  describe('quick fixes', function () {
    async function actionsFor(code: string): Promise<CodeAction[]> {
      const diagnostics = await client.diagnosticsOf(mainUri);
      const diagnostic = diagnostics.find((candidate) => problemCodeOf(candidate) === code) as Diagnostic;
      return client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri: mainUri },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
    }

    it('replaces an unknown key by the closest valid one', async function () {
      const [action] = (await actionsFor('unknown-key')).filter((candidate) => candidate.diagnostics);
      assert.equal(action.title, "Change key to 'delay'");
      assert.match(applyEdits(MAIN, action.edit?.changes?.[mainUri] ?? []), /<ParameterReference key="delay" value="1"\/>/);
    });

    it('changes NAME.xosc to NAME.mosc', async function () {
      const [action] = (await actionsFor('xosc-fallback')).filter((candidate) => candidate.diagnostics);
      assert.match(applyEdits(MAIN, action.edit?.changes?.[mainUri] ?? []), /scenarioFileName="pkg\.mosc"/);
    });

    it('adds a default attribute in the simple scenario for a key without default', async function () {
      const [action] = (await actionsFor('no-default')).filter((candidate) => candidate.diagnostics);
      const edited = applyEdits(SIMPLE, action.edit?.changes?.[simpleUri] ?? []);
      assert.match(edited, /<Condition parameterAttributes="delay, missing" missing="3" name="Go"/);
    });

    it('adds the missing keys with their defaults', async function () {
      const actions = await actionsFor('unknown-key');
      const add = actions.find((candidate) => /missing key/.test(candidate.title));
      assert.ok(add, `among ${actions.map((candidate) => candidate.title)}`);
      assert.equal(add.title, 'Add 2 missing keys with their defaults');
      const edited = applyEdits(MAIN, add.edit?.changes?.[mainUri] ?? []);
      assert.match(
        edited,
        /<ParameterReference key="missing" value="3"\/>\n {14}<ParameterReference key="delay" value="0"\/>\n {14}<ParameterReference key="SimulationTimeCondition\.value" value="2"\/>\n {12}<\/ManeuverGroupReference>/,
      );
    });

    it('offers the missing keys on a valid key line only where a diagnostic asks, else as a rewrite on the group reference tag', async function () {
      const actionsAt = (markedSnippet: string, only?: string[]) => {
        const position = at(MAIN, markedSnippet);
        return client.request<CodeAction[]>('textDocument/codeAction', {
          textDocument: { uri: mainUri },
          range: { start: position, end: position },
          context: { diagnostics: [], ...(only ? { only } : {}) },
        });
      };
      const missingKeys = (actions: CodeAction[]) => actions.filter((candidate) => /missing key/.test(candidate.title));
      assert.deepEqual(
        missingKeys(await actionsAt('key="AbsoluteTargetSpeed.value" value="|7"')),
        [],
        'no lightbulb on a valid ParameterReference',
      );
      const [rewrite] = missingKeys(await actionsAt('maneuverGroupName="Br|ake"'));
      assert.ok(rewrite, 'the rewrite on the ManeuverGroupReference tag');
      assert.equal(rewrite.kind, 'refactor.rewrite');
      assert.equal(rewrite.diagnostics, undefined);
      assert.equal(missingKeys(await actionsAt('maneuverGroupName="Br|ake"', ['quickfix'])).length, 0, 'not among quick fixes');
      assert.equal(missingKeys(await actionsAt('maneuverGroupName="Br|ake"', ['refactor'])).length, 1);
      const [fix] = missingKeys(await actionsFor('unknown-key'));
      assert.equal(fix.kind, 'quickfix');
    });

    it('offers to list the closest attribute or to add a default in the simple scenario', async function () {
      const uri = await client.openFile(path.join(root, 'simple.xosc'));
      const [diagnostic] = await client.diagnosticsOf(uri);
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
      const add = actions.find((candidate) => candidate.title === "Add a default value for 'missing'");
      assert.ok(add);
      assert.match(applyEdits(SIMPLE, add.edit?.changes?.[uri] ?? []), /parameterAttributes="delay, missing" missing=""/);
      await client.close(uri);
    });
  });

  describe('symbols and lenses', function () {
    it('outlines Storyboard, Story, Act, ManeuverGroup and references', async function () {
      const symbols = await client.request<DocumentSymbol[]>('textDocument/documentSymbol', { textDocument: { uri: mainUri } });
      const storyboard = symbols.find((symbol) => symbol.name === 'Storyboard') as DocumentSymbol;
      const story = storyboard.children?.[0] as DocumentSymbol;
      assert.equal(story.name, 'Main');
      const act = story.children?.[0] as DocumentSymbol;
      assert.deepEqual(
        act.children?.map((group) => group.name),
        ['Outer', 'Second', 'Third', 'Fourth'],
      );
      const reference = act.children?.[0].children?.find((child) => child.detail === 'ScenarioReference') as DocumentSymbol;
      assert.equal(reference.name, 'simple.xosc');
      assert.equal(reference.children?.[0].name, 'Brake');
    });

    it('finds groups across the workspace', async function () {
      const symbols = await client.request<SymbolInformation[]>('workspace/symbol', { query: 'brk' });
      const found = symbols.map((symbol) => `${symbol.containerName}:${symbol.name}`).sort();
      assert.deepEqual(found, ['pkg.mosc/simple.xosc:Brake', 'simple.xosc:Brake']);
      const inPackage = symbols.find((symbol) => symbol.containerName === 'pkg.mosc/simple.xosc') as SymbolInformation;
      assert.equal(inPackage.location.uri, `mosc:${path.join(root, 'pkg.mosc')}/simple.xosc`);
      assert.equal(textAt(SIMPLE, inPackage.location.range).split('\n')[0], '<ManeuverGroup name="Brake" maximumExecutionCount="1">');
    });

    it('puts override counts and the flatten preview on each ScenarioReference', async function () {
      const lenses = await client.request<CodeLens[]>('textDocument/codeLens', { textDocument: { uri: mainUri } });
      assert.equal(lenses.length, 8);
      assert.equal(lenses[0].command?.title, '3 keys override 1 attribute');
      assert.equal(lenses[1].command?.command, 'modular2simple.openPreview');
      // The reference's line, so that the preview opens at the groups it imports.
      assert.deepEqual(lenses[1].command?.arguments, [mainUri, { line: lenses[1].range.start.line }]);
      assert.equal(lenses[1].range.start.line, MAIN.slice(0, MAIN.indexOf('<ScenarioReference')).split('\n').length - 1);
    });
  });

  describe('custom requests', function () {
    it('flattens to text for the preview', async function () {
      const result = await client.send(FlattenToTextRequest, { uri: fileUri(path.join(root, 'clean.xosc')) });
      assert.deepEqual(
        result.problems.map((problem) => problem.severity),
        ['warning'],
        'only the warning of simple.xosc',
      );
      assert.ok(result.text);
      assert.match(result.text, /<ManeuverGroup name="Outer\.Brake"/);
      assert.match(result.text, /<AbsoluteTargetSpeed value="9"\/>/);
      assert.ok(!result.text.includes('parameterAttributes'));
    });

    it('returns no text but the problems when flattening fails', async function () {
      const result = await client.send(FlattenToTextRequest, { uri: mainUri });
      assert.equal(result.text, null);
      assert.ok(result.problems.some((problem) => problem.severity === 'error' && /nowhere\.xosc/.test(problem.message)));
    });

    it('flattens to a file atomically and refuses to overwrite an input', async function () {
      const output = path.join(root, 'out', 'flat.xosc');
      fs.mkdirSync(path.dirname(output), { recursive: true });
      const written = await client.send(FlattenToFileRequest, { uri: fileUri(path.join(root, 'clean.xosc')), outputPath: output });
      assert.equal(written.written, output);
      assert.match(fs.readFileSync(output, 'utf8'), /Outer\.Brake/);
      assert.deepEqual(fs.readdirSync(path.dirname(output)), ['flat.xosc']);
      const before = fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8');
      const refused = await client.send(FlattenToFileRequest, {
        uri: fileUri(path.join(root, 'clean.xosc')),
        outputPath: path.join(root, 'simple.xosc'),
      });
      assert.equal(refused.written, null);
      assert.ok(refused.problems.some((problem) => /refusing to overwrite simple\.xosc/.test(problem.message)));
      assert.equal(fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8'), before);
    });

    it('packs an unpacked folder into a .mosc that the server then reads', async function () {
      const folder = path.join(root, 'unpacked');
      fs.mkdirSync(folder, { recursive: true });
      fs.writeFileSync(path.join(folder, 'main.xosc'), PACKAGE_MAIN);
      const output = path.join(root, 'out', 'unpacked.mosc');
      const result = await client.send(PackRequest, { inputs: [fileUri(folder)], outputPath: output });
      assert.equal(result.written, output, JSON.stringify(result.problems));
      const zip = await JSZip.loadAsync(fs.readFileSync(output));
      assert.deepEqual(Object.keys(zip.files).sort(), ['main.xosc', 'simple.xosc']);
      const flattened = await client.send(FlattenToTextRequest, { uri: `mosc:${output}/main.xosc` });
      assert.match(flattened.text ?? '', /<ManeuverGroup name="Inner\.Brake"/);
      const refused = await client.send(PackRequest, {
        inputs: [fileUri(path.join(root, 'simple.xosc')), fileUri(path.join(folder, 'main.xosc'))],
        outputPath: path.join(root, 'simple.xosc'),
      });
      assert.equal(refused.written, null);
      fs.rmSync(folder, { recursive: true });
    });

    it('returns the reference graph', async function () {
      const tree = await client.send(StructureRequest, { uri: mainUri });
      assert.ok(tree);
      assert.equal(tree.kind, 'main');
      assert.deepEqual(
        tree.children.map((child) => `${child.kind}:${child.label}`),
        ['reference:Outer → simple.xosc', 'reference:Second → pkg.xosc', 'missing:nowhere.xosc', 'reference:Fourth → simple.xosc'],
      );
      const second = tree.children[1];
      assert.equal(second.children[0].kind, 'package');
      assert.equal(second.children[0].children[0].label, 'Inner → simple.xosc');
      assert.equal(second.children[1].label, 'Inner.Brake');
      assert.match(second.children[1].detail ?? '', /^\d+ attributes? overridden$/);
      assert.equal(second.children[1].uri, `mosc:${path.join(root, 'pkg.mosc')}/simple.xosc`);
    });

    it('reads a package, or an unpacked folder, as its main.xosc', async function () {
      const tree = await client.send(StructureRequest, { uri: fileUri(path.join(root, 'pkg.mosc')) });
      assert.ok(tree);
      assert.equal(tree.uri, `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`);
      assert.deepEqual(
        tree.children.map((child) => child.label),
        ['Inner → simple.xosc'],
      );
      const flattened = await client.send(FlattenToTextRequest, { uri: fileUri(path.join(root, 'pkg.mosc')) });
      assert.match(flattened.text ?? '', /<ManeuverGroup name="Inner\.Brake"/);
    });

    it('answers an unknown request with an error, not a crash', async function () {
      await assert.rejects(client.request(StructureRequest.method + '.nope', { uri: mainUri }), /Unhandled method/);
      const tree = await client.send(StructureRequest, { uri: mainUri });
      assert.equal(tree?.kind, 'main');
    });
  });
});

describe('language server: edits inside packages (JSON-RPC)', function () {
  let root: string;

  before(async function () {
    root = temporaryWorkspace({ 'main.xosc': MAIN, 'simple.xosc': SIMPLE, 'pkg.mosc': await packageBytes() });
  });

  after(function () {
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  async function renameInsidePackage(options: Record<string, unknown> | undefined) {
    const client = await TestClient.start({ root, initializationOptions: options });
    try {
      await client.indexed();
      const uri = `mosc:${path.join(root, 'pkg.mosc')}/simple.xosc`;
      await client.open(uri, SIMPLE);
      const position = at(SIMPLE, '<ManeuverGroup name="Br|ake"');
      return await client.request<WorkspaceEdit>('textDocument/rename', { ...client.at(uri, position), newName: 'Halt' }).then(
        (edit) => ({ edit, uri }),
        (error: Error) => ({ error, uri }),
      );
    } finally {
      await client.stop();
    }
  }

  it('renames a group inside a .mosc, with its uses there, when the client writes into packages', async function () {
    const result = await renameInsidePackage({ packageFileSystem: true });
    assert.ok('edit' in result, 'error' in result ? result.error.message : '');
    const changes = result.edit.changes ?? {};
    assert.match(applyEdits(SIMPLE, changes[result.uri]), /<ManeuverGroup name="Halt"/);
    const packageMain = `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`;
    assert.ok(changes[packageMain]?.length, `the package's own main.xosc is updated too: ${Object.keys(changes).join(', ')}`);
    assert.match(applyEdits(PACKAGE_MAIN, changes[packageMain]), /maneuverGroupName="Halt"/);
  });

  it('refuses that rename for a client that cannot write into packages', async function () {
    const result = await renameInsidePackage(undefined);
    assert.ok('error' in result);
    assert.match(result.error.message, /cannot write into packages/);
  });
});
