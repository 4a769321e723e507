import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';
import { CodeAction, CreateFile, FileChangeType, TextDocumentEdit, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { ExtractGroupRequest, FlattenToTextRequest } from '../../common/src/protocol';
import { firstDifference } from '../../server/src/core/equivalence';
import { buildModel } from '../../server/src/core/model';
import { parseXml } from '../../server/src/core/xml';
import { caseStudyDir, libraryDir, requireCorpus, sharedDir } from '../support/paths';
import { positionAt } from '../support/cursor';
import { requireEsmini, runEsmini } from '../support/esmini';
import { esminiXodrDir } from '../support/esminiBinaries';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';
import { applyEdits } from '../support/textEdits';

const esminiCorpus = path.join(sharedDir, 'corpus', 'openscenario', 'esmini');
const CAN_CREATE = { documentChanges: true, resourceOperations: ['create' as const] };

/**
 * The files a WorkspaceEdit creates and the new texts of those it edits, applied to the disk (and to the open
 * documents through didChange); the files written on disk are reported as an editor's file watcher does.
 */
async function applyWorkspaceEdit(client: TestClient, edit: WorkspaceEdit, open: Map<string, string>): Promise<string[]> {
  const created: string[] = [];
  const changed: string[] = [];
  for (const change of edit.documentChanges ?? []) {
    if (CreateFile.is(change)) {
      const file = fileURLToPath(change.uri);
      assert.ok(!fs.existsSync(file), `the edit creates ${file}, which exists`);
      fs.writeFileSync(file, '');
      created.push(file);
      continue;
    }
    assert.ok(TextDocumentEdit.is(change));
    const uri = change.textDocument.uri;
    const before = open.get(uri) ?? fs.readFileSync(fileURLToPath(uri), 'utf8');
    const after = applyEdits(
      before,
      change.edits.filter((item): item is TextEdit => 'newText' in item),
    );
    if (open.has(uri)) {
      open.set(uri, after);
      await client.change(uri, [{ text: after }]);
    } else {
      const file = fileURLToPath(uri);
      fs.writeFileSync(file, after);
      if (!created.includes(file)) changed.push(file);
    }
  }
  for (const [uri, edits] of Object.entries(edit.changes ?? {})) {
    const after = applyEdits(open.get(uri) as string, edits);
    open.set(uri, after);
    await client.change(uri, [{ text: after }]);
  }
  await fileEvents(client, created, FileChangeType.Created);
  await fileEvents(client, changed, FileChangeType.Changed);
  return created;
}

/** What an editor's file watcher reports of files written on disk (the server keeps the bytes it read until told). */
async function fileEvents(client: TestClient, files: string[], type: FileChangeType): Promise<void> {
  if (files.length > 0)
    await client.connection.sendNotification('workspace/didChangeWatchedFiles', {
      changes: files.map((file) => ({ uri: fileUri(file), type })),
    });
}

async function flattened(client: TestClient, uri: string, force = false): Promise<string> {
  const result = await client.send(FlattenToTextRequest, { uri, options: { force } });
  assert.ok(result.text !== null, `${uri} does not flatten: ${result.problems.map((problem) => problem.message).join('; ')}`);
  return result.text;
}

/** Whether the file's only errors are CatalogLocations directories found nowhere (esmini's samples name ../xosc/Catalogs, esmini's repository layout): then it is compared flattened with force, as modularize compares such inputs. */
async function lacksOnlyCatalogs(client: TestClient, uri: string): Promise<boolean> {
  const result = await client.send(FlattenToTextRequest, { uri, options: { force: false } });
  const errors = result.problems.filter((problem) => problem.severity === 'error');
  return result.text === null && errors.length > 0 && errors.every((problem) => problem.code === 'catalog-directory');
}

async function refactorings(client: TestClient, uri: string, text: string, offset: number, only: string[]): Promise<CodeAction[]> {
  const position = positionAt(text, offset);
  return client.request<CodeAction[]>('textDocument/codeAction', {
    textDocument: { uri },
    range: { start: position, end: position },
    context: { diagnostics: [], only },
  });
}

describe('refactorings over JSON-RPC on the corpus (issue 19)', function () {
  this.timeout(300_000);
  let root: string;
  let client: TestClient;
  before(async function () {
    requireCorpus(this);
    root = temporaryWorkspace({}, 'm2s-refactor-');
    fs.cpSync(esminiCorpus, path.join(root, 'esmini'), { recursive: true });
    fs.cpSync(libraryDir, path.join(root, 'library'), { recursive: true });
    fs.cpSync(caseStudyDir, path.join(root, 'case-study'), { recursive: true });
    client = await TestClient.start({ root, workspaceEdit: CAN_CREATE });
    await client.indexed();
  });
  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('extracts every ManeuverGroup of the esmini scenarios to a simple scenario, and each main flattens as before', async function () {
    const files = fs.readdirSync(path.join(root, 'esmini')).filter((name) => name.endsWith('.xosc'));
    let extracted = 0;
    const scenarios = new Set<string>();
    const refused: string[] = [];
    for (const name of files) {
      const file = path.join(root, 'esmini', name);
      const text = fs.readFileSync(file, 'utf8');
      const model = buildModel(parseXml(text));
      if (model.groups.length === 0 || model.references.length > 0) continue;
      const uri = await client.openFile(file);
      const force = await lacksOnlyCatalogs(client, uri);
      const before = await flattened(client, uri, force);
      for (const group of model.groups) {
        const actions = await refactorings(client, uri, text, group.element.start + 3, ['refactor.extract']);
        const action = actions.find((candidate) => candidate.kind === 'refactor.extract.simpleScenario');
        if (!action) continue;
        if (action.disabled) {
          refused.push(`${name} '${group.name}': ${action.disabled.reason}`);
          continue;
        }
        assert.ok(action.edit, `${name}: the action has no edit: ${JSON.stringify(action)}`);
        const open = new Map([[uri, text]]);
        const created = await applyWorkspaceEdit(client, action.edit, open);
        assert.equal(created.length, 1, `${name}: one simple scenario is created`);
        assert.match(fs.readFileSync(created[0], 'utf8'), /<Storyboard>/);
        assert.match(open.get(uri) as string, /<ScenarioReference scenarioFileName="[^"]+\.xosc">/);
        const after = await flattened(client, uri, force);
        assert.equal(
          firstDifference(after, before),
          undefined,
          `${name}: group '${group.name}' extracted to ${path.basename(created[0])} flattens differently`,
        );
        // The simple scenario stands on its own: it flattens (it is a plain scenario) with no error (forced as its source, whose catalogs are absent).
        const simpleUri = await client.openFile(created[0]);
        await flattened(client, simpleUri, force);
        await client.close(simpleUri);
        // Back to the scenario as it was, for its next group.
        await client.change(uri, [{ text }]);
        for (const createdFile of created) fs.rmSync(createdFile);
        await client.connection.sendNotification('workspace/didChangeWatchedFiles', {
          changes: created.map((createdFile) => ({ uri: fileUri(createdFile), type: FileChangeType.Deleted })),
        });
        extracted++;
        scenarios.add(name);
      }
      await client.close(uri);
    }
    assert.ok(scenarios.size >= 50 && extracted >= 90, `only ${extracted} groups of ${scenarios.size} esmini scenarios extracted`);
    console.log(
      `      ${extracted} groups of ${scenarios.size} esmini scenarios extracted, each flattened output equivalent; refused: ${refused.length ? refused.join('; ') : 'none'}`,
    );
  });

  it('extracts with the attributes chosen through the extractGroup request, and refuses a client that cannot create files', async function () {
    const file = path.join(root, 'esmini', 'lane_change.xosc');
    const text = fs.readFileSync(file, 'utf8');
    const uri = await client.openFile(file);
    const open = new Map([[uri, text]]);
    const force = await lacksOnlyCatalogs(client, uri);
    const before = await flattened(client, uri, force);
    const group = buildModel(parseXml(text)).groups[0];
    const position = positionAt(text, group.element.start + 1);
    const result = await client.send(ExtractGroupRequest, { uri, position, attributes: [] });
    // No attribute chosen: only the group's name, which the outer name alone cannot give, is listed.
    assert.deepEqual(result.parameters, ['ManeuverGroup.name']);
    await applyWorkspaceEdit(client, result.edit, open);
    assert.equal(firstDifference(await flattened(client, uri, force), before), undefined);
    await client.close(uri);

    const other = await TestClient.start({ root, workspaceEdit: { documentChanges: false } });
    try {
      const otherUri = await other.openFile(path.join(root, 'esmini', 'cut-in.xosc'));
      const cutIn = fs.readFileSync(path.join(root, 'esmini', 'cut-in.xosc'), 'utf8');
      const offset = buildModel(parseXml(cutIn)).groups[0].element.start + 2;
      const actions = await refactorings(other, otherUri, cutIn, offset, ['refactor']);
      const action = actions.find((candidate) => candidate.kind === 'refactor.extract.simpleScenario');
      assert.match(action?.disabled?.reason ?? '', /cannot apply edits that create files/);
      await assert.rejects(
        other.send(ExtractGroupRequest, { uri: otherUri, position: positionAt(cutIn, offset) }),
        /cannot apply edits that create files/,
      );
    } finally {
      await other.stop();
    }
  });

  it('answers bad extractGroup requests with an error that says why, and offers nothing on a broken document', async function () {
    const file = path.join(root, 'esmini', 'cut-in.xosc');
    const text = fs.readFileSync(file, 'utf8');
    const uri = await client.openFile(file);
    await assert.rejects(
      client.send(ExtractGroupRequest, { uri, position: { line: 0, character: 0 } }),
      /no ManeuverGroup start tag at the position/,
    );
    await assert.rejects(
      client.send(ExtractGroupRequest, { uri, position: { line: 0, character: 0 }, attributes: [3] as unknown as string[] }),
      /attributes must be a list of choice ids/,
    );
    await assert.rejects(
      client.send(ExtractGroupRequest, { uri: 'file:///nowhere/x.xosc', position: { line: 0, character: 0 } }),
      /is not an open scenario/,
    );
    // Cut off in the middle of a group: nothing to move, and no failure.
    const broken = text.slice(0, text.indexOf('<Maneuver ') + 10);
    await client.change(uri, [{ text: broken }]);
    const groupAt = broken.indexOf('<ManeuverGroup') + 3;
    assert.deepEqual(await refactorings(client, uri, broken, groupAt, ['refactor']), []);
    await assert.rejects(client.send(ExtractGroupRequest, { uri, position: positionAt(broken, groupAt) }), /not well-formed/);
    await client.close(uri);
  });

  it('inlines each ScenarioReference group of the library mains, and the mains flatten as before', async function () {
    const mains = fs.readdirSync(path.join(root, 'library')).filter((name) => name.startsWith('modular_hero_'));
    assert.equal(mains.length, 31);
    for (const folder of mains) {
      const file = path.join(root, 'library', folder, 'main.xosc');
      const uri = await client.openFile(file);
      const open = new Map([[uri, fs.readFileSync(file, 'utf8')]]);
      const before = await flattened(client, uri);
      for (;;) {
        const text = open.get(uri) as string;
        const group = buildModel(parseXml(text)).groups.find((candidate) => candidate.references.length > 0);
        if (!group) break;
        const actions = await refactorings(client, uri, text, group.element.start + 1, ['refactor.inline']);
        assert.equal(actions.length, 1, `${folder}: one inline action on '${group.name}'`);
        assert.ok(actions[0].edit, `${folder}: ${JSON.stringify(actions[0])}`);
        await applyWorkspaceEdit(client, actions[0].edit, open);
        assert.equal(
          firstDifference(await flattened(client, uri), before),
          undefined,
          `${folder}: inlining '${group.name}' changed the flattened scenario`,
        );
      }
      // Everything inlined, the main is the paper's flattened result.
      assert.equal(
        firstDifference(open.get(uri) as string, fs.readFileSync(path.join(root, 'library', folder, 'result.xosc'), 'utf8')),
        undefined,
      );
      await client.close(uri);
    }
  });

  it("inlines the case study's groups, which import nested packages, and the main flattens (forced: its keys have errors) as before", async function () {
    const file = path.join(root, 'case-study', 'main.xosc');
    const uri = await client.openFile(file);
    const open = new Map([[uri, fs.readFileSync(file, 'utf8')]]);
    const before = await flattened(client, uri, true);
    let inlined = 0;
    for (;;) {
      const text = open.get(uri) as string;
      const group = buildModel(parseXml(text)).groups.find((candidate) => candidate.references.length > 0);
      if (!group) break;
      const actions = await refactorings(client, uri, text, group.element.start + 1, ['refactor.inline']);
      assert.ok(actions[0]?.edit, `'${group.name}': ${JSON.stringify(actions)}`);
      await applyWorkspaceEdit(client, actions[0].edit, open);
      assert.equal(
        firstDifference(await flattened(client, uri, true), before),
        undefined,
        `inlining '${group.name}' changed the flattened scenario`,
      );
      inlined++;
    }
    assert.ok(inlined >= 2, `${inlined} groups inlined`);
    await client.close(uri);
  });

  it('makes attributes of a simple scenario overridable, and the mains that use it flatten as before', async function () {
    const simpleFile = path.join(root, 'library', 'simple_1.xosc');
    const mainUri = await client.openFile(path.join(root, 'library', 'modular_hero_back', 'main.xosc'));
    const before = await flattened(client, mainUri);
    const uri = await client.openFile(simpleFile);
    const open = new Map([[uri, fs.readFileSync(simpleFile, 'utf8')]]);
    const vehicleGroup = (text: string) => text.indexOf('<ManeuverGroup name="ManeuverGroupVehicle"');
    const dynamics = (text: string) => text.indexOf('<SpeedActionDynamics', vehicleGroup(text));
    for (const attribute of ['dynamicsShape', 'value']) {
      const text = open.get(uri) as string;
      const at = text.indexOf(`${attribute}="`, dynamics(text)) + 2;
      const actions = await refactorings(client, uri, text, at, ['refactor.rewrite']);
      const action = actions.find((candidate) => candidate.kind === 'refactor.rewrite.makeOverridable');
      assert.equal(action?.title, `Make 'SpeedActionDynamics.${attribute}' overridable`);
      assert.ok(action?.edit);
      await applyWorkspaceEdit(client, action.edit, open);
    }
    const written = open.get(uri) as string;
    assert.match(written.slice(dynamics(written)), /^<SpeedActionDynamics parameterAttributes="dynamicsShape,value" dynamicsShape="step"/);
    // Once listed, it is not offered again; the group's name and its actor never are.
    const listed = await refactorings(client, uri, written, written.indexOf('dynamicsShape="', dynamics(written)) + 2, [
      'refactor.rewrite',
    ]);
    assert.equal(listed.filter((candidate) => candidate.kind === 'refactor.rewrite.makeOverridable').length, 0);
    const name = await refactorings(client, uri, written, vehicleGroup(written) + 20, ['refactor.rewrite']);
    assert.equal(name.filter((candidate) => candidate.kind === 'refactor.rewrite.makeOverridable').length, 0);
    assert.equal(firstDifference(await flattened(client, mainUri), before), undefined);
    await client.close(uri);
    await client.close(mainUri);
  });
});

describe('Extract to catalog over JSON-RPC: esmini runs the scenario identically (issue 19)', function () {
  this.timeout(300_000);
  let root: string;
  let client: TestClient;
  before(async function () {
    requireCorpus(this);
    requireEsmini(this);
    // The scenarios name ../xodr and ../xosc/Catalogs: the corpus goes in as xosc/ beside xodr/.
    root = temporaryWorkspace({}, 'm2s-catalog-');
    fs.cpSync(esminiCorpus, path.join(root, 'xosc'), { recursive: true });
    fs.symlinkSync(esminiXodrDir, path.join(root, 'xodr'));
    client = await TestClient.start({ root, workspaceEdit: CAN_CREATE });
    await client.indexed();
  });
  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  const cases: { file: string; element: string; title: RegExp; edit?: [string, string]; expect: RegExp[] }[] = [
    // The catalog there has a different car_white: a new catalog file beside it (the name stays).
    {
      file: 'straight_500m.xosc',
      element: '<Vehicle name="car_white"',
      title: /VehicleCatalog_2\/car_white in VehicleCatalog_2\.xosc/,
      expect: [/<CatalogReference catalogName="VehicleCatalog_2" entryName="car_white"\/>/],
    },
    // No ManeuverCatalog location: a new Catalogs/ManeuverCatalog.xosc and its location.
    {
      file: 'cut-in.xosc',
      element: '<Maneuver ',
      title: /ManeuverCatalog\/\w+ in ManeuverCatalog\.xosc/,
      expect: [
        /<ManeuverCatalog>\s*<Directory path="Catalogs"\/>\s*<\/ManeuverCatalog>/,
        /<CatalogReference catalogName="ManeuverCatalog" entryName="CutInManeuver">/,
      ],
    },
    // Both catalog files there are the catalog ControllerCatalog, which has an ACCController of its own: a new catalog, under
    // its name (esmini's controller type). A scenario parameter the controller uses is declared in the entry and passed in.
    {
      file: 'acc-test.xosc',
      element: '<Controller name="ACCController"',
      title: /ControllerCatalog_2\/ACCController in ControllerCatalog_2\.xosc/,
      expect: [/<ParameterAssignment parameterRef="EgoSpeed" value="\$EgoSpeed"\/>/],
    },
    // A pedestrian and a misc object, each into its kind's catalog.
    {
      file: 'straight_500m_pedestrian.xosc',
      element: '<Pedestrian name="Pedestrian1"',
      title: /Pedestrian1 in \w+\.xosc/,
      expect: [/<CatalogReference catalogName="\w+" entryName="Pedestrian1"\/>/],
    },
    {
      file: 'drop-bike.xosc',
      element: '<MiscObject name="box"',
      title: /box in \w+\.xosc/,
      expect: [/<CatalogReference catalogName="\w+" entryName="box"\/>/],
    },
    // The catalog's sloppyDriver, with its own Sloppiness parameter: reused, the value that differs assigned.
    {
      file: 'cut-in_sloppy.xosc',
      element: '<Controller name="sloppyDriver"',
      edit: [
        '<Property name="mode" value="additive"/>\n                    <Property name="sloppiness" value="0.6" />',
        '<Property name="sloppiness" value="0.6" />\n                    <Property name="mode" value="additive"/>',
      ],
      title: /ControllerCatalog\/sloppyDriver in ControllerCatalog\.xosc, an entry there already/,
      expect: [
        /<CatalogReference catalogName="ControllerCatalog" entryName="sloppyDriver">\s*<ParameterAssignments>\s*<ParameterAssignment parameterRef="Sloppiness" value="0.6"\/>\s*<\/ParameterAssignments>\s*<\/CatalogReference>/,
      ],
    },
  ];
  for (const { file: name, element, title, edit, expect } of cases) {
    it(`${name}: ${element.slice(1)}…`, async function () {
      const file = path.join(root, 'xosc', name);
      if (edit) {
        const original = fs.readFileSync(file, 'utf8');
        assert.ok(original.includes(edit[0]));
        fs.writeFileSync(file, original.replace(edit[0], edit[1]));
        await fileEvents(client, [file], FileChangeType.Changed);
      }
      const text = fs.readFileSync(file, 'utf8');
      const before = await runEsmini(file, 20);
      assert.ok(before.length > 10, `${name}: ${before.length} steps`);
      const uri = await client.openFile(file);
      const open = new Map([[uri, text]]);
      const actions = await refactorings(client, uri, text, text.indexOf(element) + 2, ['refactor.extract']);
      const action = actions.find((candidate) => candidate.kind === 'refactor.extract.catalog');
      assert.ok(action?.edit, `${name}: ${JSON.stringify(actions)}`);
      assert.match(action.title, title);
      await applyWorkspaceEdit(client, action.edit, open);
      const after = open.get(uri) as string;
      for (const pattern of expect) assert.match(after, pattern);
      assert.ok(!after.includes(element), `${name}: the element moved out`);
      // Saved, then closed: the watcher reports the save.
      fs.writeFileSync(file, after);
      await fileEvents(client, [file], FileChangeType.Changed);
      await client.close(uri);
      // The scenario checks clean (the catalog entry resolves) and esmini runs it exactly as before.
      const check = await client.send(FlattenToTextRequest, { uri });
      assert.ok(check.text !== null, check.problems.map((problem) => problem.message).join('; '));
      assert.deepEqual(await runEsmini(file, 20), before, `${name}: esmini runs it differently`);
    });
  }
});
