import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CompletionItem, Diagnostic, DiagnosticSeverity, Hover, Location, MarkupContent, WorkspaceEdit } from 'vscode-languageserver/node';
import { firstDifference } from '../../server/src/core/equivalence';
import { main } from '../../server/src/cli';
import { FlattenToTextRequest } from '../../common/src/protocol';
import { fileUri, TestClient } from './harness';
import { problemCodeOf } from '../support/diagnostics';
import { positionAfter, positionAt } from '../support/cursor';
import { caseStudyDir, libraryDir, requireCorpus } from '../support/paths';

function rangeText(text: string, location: Location): string {
  const lines = text.split('\n');
  return lines[location.range.start.line].slice(location.range.start.character, location.range.end.character);
}

describe('language server on the case study (../shared/corpus)', function () {
  let client: TestClient;
  let mainUri: string;
  let mainText: string;

  before(async function () {
    requireCorpus(this);
    client = await TestClient.start({ root: caseStudyDir });
    await client.indexed();
    mainText = fs.readFileSync(path.join(caseStudyDir, 'main.xosc'), 'utf8');
    mainUri = await client.openFile(path.join(caseStudyDir, 'main.xosc'));
  });

  after(async function () {
    await client?.stop();
  });

  it('warns about the NAME.xosc fallback and the keys that simple_2.xosc lists as whole keys', async function () {
    const diagnostics = await client.diagnosticsOf(mainUri);
    assert.deepEqual(
      diagnostics.map((diagnostic) => `${diagnostic.range.start.line + 1}:${problemCodeOf(diagnostic)}`),
      ['339:xosc-fallback', '492:unknown-key', '518:unknown-key'],
    );
    assert.deepEqual(
      diagnostics.map((diagnostic) => diagnostic.severity),
      [DiagnosticSeverity.Warning, DiagnosticSeverity.Error, DiagnosticSeverity.Error],
    );
    const related = diagnostics[1].relatedInformation?.[0];
    assert.equal(related?.location.uri, fileUri(path.join(caseStudyDir, 'simple_2.xosc')));
    assert.equal(
      rangeText(fs.readFileSync(path.join(caseStudyDir, 'simple_2.xosc'), 'utf8'), related.location),
      'AbsoluteTargetSpeed.value',
    );
  });

  it('completes keys for a group of simple_2.xosc, which lists the dotted AbsoluteTargetSpeed.value (issue 7, item 3)', async function () {
    await client.diagnosticsOf(mainUri);
    const reference = mainText.indexOf('maneuverGroupName="VehicleArrivingToAccidentSite.ArrivingToAccidentSite"');
    const keyStart = mainText.indexOf('key="entityRef"', reference) + 'key="'.length;
    const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(mainUri, positionAt(mainText, keyStart)));
    const labels = items.map((item) => item.label);
    // The key under the cursor is replaced, so it is offered again; the group's other keys are given already.
    assert.ok(labels.includes('entityRef'), labels.join(', '));
    assert.ok(!labels.some((label) => label.includes('AbsoluteTargetSpeed')), 'no key reaches the dotted name');
  });

  it('gives each problem of main.xosc the severity the CLI check gives it (issue 7, item 2)', async function () {
    const printed: string[] = [];
    await main(['check', caseStudyDir, '--format', 'json'], { out: (text) => printed.push(text), err: () => undefined });
    const report = JSON.parse(printed.join('')) as { problems: { file: string; line: number; code: string; severity: string }[] };
    const severityName = ['', 'error', 'warning', 'information'];
    const fromCli = report.problems
      .filter((problem) => path.resolve(problem.file) === path.join(caseStudyDir, 'main.xosc'))
      .map((problem) => `${problem.line}:${problem.code}:${problem.severity}`);
    const diagnostics = await client.diagnosticsOf(mainUri);
    assert.deepEqual(
      diagnostics.map(
        (diagnostic) => `${diagnostic.range.start.line + 1}:${problemCodeOf(diagnostic)}:${severityName[diagnostic.severity ?? 0]}`,
      ),
      fromCli,
    );
  });

  it('shows the parameterAttributes entry of simple_2.xosc that names no attribute', async function () {
    const uri = await client.openFile(path.join(caseStudyDir, 'simple_2.xosc'));
    const diagnostics: Diagnostic[] = await client.diagnosticsOf(uri);
    const entry = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'unknown-parameter-attribute');
    assert.ok(entry);
    assert.equal(entry.range.start.line + 1, 129);
    await client.close(uri);
  });

  it('goes to definition through the nested package for a dotted group name', async function () {
    const locations = await client.request<Location[]>(
      'textDocument/definition',
      client.at(mainUri, positionAfter(mainText, 'maneuverGroupName="VehicleCollisionInit.Coll')),
    );
    assert.equal(locations.length, 1);
    assert.equal(locations[0].uri, fileUri(path.join(caseStudyDir, 'simple_1.xosc')));
    assert.equal(locations[0].range.start.line + 1, 117);
    assert.equal(rangeText(fs.readFileSync(path.join(caseStudyDir, 'simple_1.xosc'), 'utf8'), locations[0]), 'CollisionInit');
  });

  it('goes from a key to the attribute it overrides in simple_1.xosc', async function () {
    const locations = await client.request<Location[]>(
      'textDocument/definition',
      client.at(mainUri, positionAfter(mainText, 'key="AcquirePositionAction.Position.WorldPosition.x')),
    );
    assert.equal(locations.length, 1);
    const simple = fs.readFileSync(path.join(caseStudyDir, 'simple_1.xosc'), 'utf8');
    assert.match(rangeText(simple, locations[0]), /^x="-?[\d.]+"$/);
    assert.match(simple.split('\n')[locations[0].range.start.line], /<WorldPosition parameterAttributes="x,y,z,h"/);
  });

  it('goes from scenarioFileName to the unpacked package', async function () {
    const [location] = await client.request<Location[]>(
      'textDocument/definition',
      client.at(mainUri, positionAfter(mainText, 'scenarioFileName="modular_1.m')),
    );
    assert.equal(location.uri, fileUri(path.join(caseStudyDir, 'modular_1', 'main.xosc')));
  });

  it('completes only the key not yet given in a group reference', async function () {
    const items = await client.request<CompletionItem[]>(
      'textDocument/completion',
      client.at(mainUri, positionAfter(mainText, 'key="', 1)),
    );
    const sorted = items.sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? '')).map((item) => item.label);
    assert.equal(sorted[0], 'delay');
    assert.ok(sorted.every((label) => label.endsWith('delay')));
  });

  it('hovers a key with the value taking effect', async function () {
    const hover = await client.request<Hover>(
      'textDocument/hover',
      client.at(mainUri, positionAfter(mainText, 'key="AbsoluteTargetSpeed.va', 2)),
    );
    assert.match(
      (hover.contents as MarkupContent).value,
      /default `6\.8` declared at `simple_1\.xosc:130`; takes effect: `10` \(this key\)/,
    );
  });

  it('completes keys on a line being typed in the middle of the file (not well-formed)', async function () {
    const anchor = mainText.indexOf('<ParameterReference key="StandStillCondition.duration"');
    // The line giving StandStillCondition.duration is replaced by one being typed: an unclosed value.
    const typed = `${mainText.slice(0, anchor)}<ParameterReference key="${mainText.slice(mainText.indexOf('\n', anchor))}`;
    const uri = fileUri(path.join(caseStudyDir, 'typed-main.xosc'));
    await client.open(uri, typed);
    const items = await client.request<CompletionItem[]>(
      'textDocument/completion',
      client.at(uri, positionAt(typed, anchor + '<ParameterReference key="'.length)),
    );
    const labels = items.sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? '')).map((item) => item.label);
    assert.equal(labels[0], 'duration', 'the key no longer given is offered first, in its shortest form');
    assert.ok(
      labels.every((label) => label.endsWith('duration')),
      `only that key: ${labels}`,
    );
    await client.close(uri);
  });

  it('renames a group of simple_1.xosc in the package main and in the dotted names of the outer main', async function () {
    const simplePath = path.join(caseStudyDir, 'simple_1.xosc');
    const uri = await client.openFile(simplePath);
    const edit = await client.request<WorkspaceEdit>('textDocument/rename', {
      ...client.at(uri, positionAfter(fs.readFileSync(simplePath, 'utf8'), 'name="CollisionI')),
      newName: 'Crash',
    });
    const changes = edit.changes ?? {};
    const inner = changes[fileUri(path.join(caseStudyDir, 'modular_1', 'main.xosc'))] ?? [];
    assert.deepEqual(
      inner.map((change) => change.newText),
      ['Crash'],
    );
    const outer = changes[mainUri] ?? [];
    assert.equal(outer.length, 6);
    assert.ok(outer.every((change) => change.newText === 'VehicleCollisionInit.Crash'));
    assert.deepEqual(
      changes[uri].map((change) => change.newText),
      ['Crash'],
    );
    await client.close(uri);
  });

  it('updates references to an unpacked package when its folder is renamed', async function () {
    const edit = await client.request<WorkspaceEdit | null>('workspace/willRenameFiles', {
      files: [{ oldUri: fileUri(path.join(caseStudyDir, 'modular_2')), newUri: fileUri(path.join(caseStudyDir, 'leaving')) }],
    });
    const changes = edit?.changes?.[mainUri] ?? [];
    assert.ok(changes.length > 0);
    assert.ok(changes.every((change) => change.newText === 'leaving.mosc'));
    assert.equal(changes.length, mainText.split('scenarioFileName="modular_2.mosc"').length - 1);
  });

  it('finds every reference to a group of simple_1.xosc, in the package and through it', async function () {
    const simplePath = path.join(caseStudyDir, 'simple_1.xosc');
    const uri = await client.openFile(simplePath);
    const locations = await client.request<Location[]>('textDocument/references', {
      ...client.at(uri, positionAfter(fs.readFileSync(simplePath, 'utf8'), 'name="CollisionI')),
      context: { includeDeclaration: false },
    });
    const found = locations
      .map((location) => `${path.relative(caseStudyDir, new URL(location.uri).pathname)}:${location.range.start.line + 1}`)
      .sort();
    assert.deepEqual(found, [
      'main.xosc:310',
      'main.xosc:340',
      'main.xosc:370',
      'main.xosc:400',
      'main.xosc:430',
      'main.xosc:460',
      'modular_1/main.xosc:122',
    ]);
    await client.close(uri);
  });
});

describe('language server settings (../shared/corpus)', function () {
  it('resolves names through the scenarioPath setting, and again when it changes', async function () {
    requireCorpus(this);
    const client = await TestClient.start({ root: libraryDir });
    await client.indexed();
    const uri = `mosc:${path.join(libraryDir, 'modular_hero_back', 'result.mosc')}/main.xosc`;
    await client.open(uri, fs.readFileSync(path.join(libraryDir, 'modular_hero_back', 'main.xosc'), 'utf8'));
    // Inside a .mosc there is no search of parent folders, so simple_1.xosc needs the setting.
    const before = await client.diagnosticsOf(uri);
    assert.ok(
      before.some((diagnostic) => problemCodeOf(diagnostic) === 'missing-file' && /simple_1\.xosc/.test(String(diagnostic.message))),
    );
    await client.settingsChanged({ scenarioPath: [libraryDir] });
    await client.diagnosticsOf(uri, (diagnostics) => !diagnostics.some((diagnostic) => diagnostic.severity === DiagnosticSeverity.Error));
    await client.stop();
  });
});

describe('language server on the library (../shared/corpus)', function () {
  let client: TestClient;

  before(async function () {
    requireCorpus(this);
    client = await TestClient.start({ root: libraryDir, settings: { scenarioPath: [libraryDir] } });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
  });

  it('serves the main.xosc inside result.mosc by its mosc: URI, without errors', async function () {
    const uri = `mosc:${path.join(libraryDir, 'modular_hero_back', 'result.mosc')}/main.xosc`;
    const text = fs.readFileSync(path.join(libraryDir, 'modular_hero_back', 'main.xosc'), 'utf8');
    await client.open(uri, text);
    const diagnostics = await client.diagnosticsOf(uri);
    assert.deepEqual(
      diagnostics.filter((diagnostic) => diagnostic.severity === DiagnosticSeverity.Error),
      [],
    );
    const [location] = await client.request<Location[]>(
      'textDocument/definition',
      client.at(uri, positionAfter(text, 'maneuverGroupName="ManeuverGroupV')),
    );
    assert.equal(location.uri, fileUri(path.join(libraryDir, 'simple_1.xosc')));
    await client.close(uri);
  });

  it("flattens every library scenario to the original tool's output", async function () {
    for (const name of fs.readdirSync(libraryDir).filter((entry) => entry.startsWith('modular_hero'))) {
      const result = await client.send(FlattenToTextRequest, { uri: `mosc:${path.join(libraryDir, name, 'result.mosc')}/main.xosc` });
      assert.ok(result.text, `${name}: ${JSON.stringify(result.problems)}`);
      assert.equal(firstDifference(result.text, fs.readFileSync(path.join(libraryDir, name, 'result.xosc'), 'utf8')), undefined, name);
    }
  });
});
