/** Catalogs and road files found where esmini finds them, through the language server (issue 27). */
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Diagnostic, Location } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { importedCatalogController } from '../support/fixtures';
import { positionAt } from '../support/cursor';
import { STRAIGHT_ROAD } from '../support/roads';
import { twoCatalogs } from '../support/twoCatalogs';
import { temporaryWorkspace } from '../support/workspace';
import { foldersToWatch } from '../../server/src/features/outsideFolderWatchers';
import { fileUri, TestClient } from './harness';

describe('language server: two catalog files of one name, as esmini reads them (issue 27)', function () {
  this.timeout(60_000);
  let client: TestClient;
  let root: string;

  before(async () => {
    root = temporaryWorkspace(twoCatalogs('car_blue', 'VehicleCatalog.xosc', ['car_red']));
    client = await TestClient.start({ root });
  });

  after(async () => {
    await client?.stop();
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('reports the entry only the second file has, names that file, and goes to the first file for an entry both have', async () => {
    const file = path.join(root, 'scenario.xosc');
    const text = fs.readFileSync(file, 'utf8');
    const uri = await client.openFile(file);
    const diagnostics = await client.diagnosticsOf(uri, (list) =>
      list.some((each) => typeof each.message === 'string' && each.message.includes('car_red')),
    );
    const missing = diagnostics.filter((each) => (each.data as { code?: string } | undefined)?.code === 'unknown-catalog-entry');
    assert.equal(missing.length, 1, JSON.stringify(diagnostics));
    assert.deepEqual(missing[0].range.start, positionAt(text, text.indexOf('"car_red"') + 1));
    const second = path.join(root, 'second', 'VehicleCatalog.xosc');
    assert.deepEqual(
      missing[0].relatedInformation?.map((related) => related.location.uri),
      [fileUri(second)],
    );
    const at = text.indexOf('entryName="car_blue"') + 'entryName="car_'.length;
    const locations = await client.request<Location[]>('textDocument/definition', client.at(uri, positionAt(text, at)));
    const first = path.join(root, 'first', 'VehicleCatalog.xosc');
    assert.deepEqual(
      locations.map((location) => location.uri),
      [fileUri(first)],
    );
    const firstText = fs.readFileSync(first, 'utf8');
    assert.equal(
      firstText.split('\n')[locations[0].range.start.line].slice(locations[0].range.start.character, locations[0].range.end.character),
      'car_blue',
    );
  });
});

describe('language server: a road file appearing on disk (issue 27)', function () {
  this.timeout(60_000);

  it('watches road files, and drops the road-file warning once the road is created beside the scenario', async () => {
    const files = twoCatalogs('car_blue');
    const root = temporaryWorkspace(files);
    const client = await TestClient.start({ root });
    try {
      const uri = await client.openFile(path.join(root, 'scenario.xosc'));
      const code = (each: { data?: unknown }) => (each.data as { code?: string } | undefined)?.code;
      await client.diagnosticsOf(uri, (list) => list.some((each) => code(each) === 'road-file'));
      await client.indexed();
      const watched = client.registrations
        .filter((registration) => registration.method === 'workspace/didChangeWatchedFiles')
        .flatMap((registration) => (registration.registerOptions as { watchers: { globPattern: string }[] }).watchers)
        .map((watcher) => watcher.globPattern);
      assert.ok(watched.includes('**/*.xodr'), watched.join(', '));
      fs.writeFileSync(path.join(root, 'straight.xodr'), STRAIGHT_ROAD);
      await client.connection.sendNotification('workspace/didChangeWatchedFiles', {
        changes: [{ uri: fileUri(path.join(root, 'straight.xodr')), type: 1 }],
      });
      await client.diagnosticsOf(uri, (list) => !list.some((each) => code(each) === 'road-file'));
    } finally {
      await client.stop();
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});

describe('language server: a catalog Directory outside the workspace is watched (issue 27)', function () {
  this.timeout(60_000);

  it('registers a watcher for the folder, drops the catalog error once a catalog appears there, and lets the watcher go on close', async () => {
    const files = twoCatalogs('car_blue');
    // The workspace is project/; its scenario's VehicleCatalog lies in ../shared-catalogs, which nothing else watches.
    const parent = temporaryWorkspace({
      'project/scenario.xosc': files['scenario.xosc'].replace(
        /<CatalogLocations>.*<\/CatalogLocations>/,
        '<CatalogLocations><VehicleCatalog><Directory path="../shared-catalogs"/></VehicleCatalog></CatalogLocations>',
      ),
      'project/straight.xodr': STRAIGHT_ROAD,
      'shared-catalogs/README.txt': 'catalogs shared by several projects\n',
    });
    const root = path.join(parent, 'project');
    const outside = path.join(parent, 'shared-catalogs');
    const client = await TestClient.start({ root });
    try {
      const uri = await client.openFile(path.join(root, 'scenario.xosc'));
      const code = (each: { data?: unknown }) => (each.data as { code?: string } | undefined)?.code;
      const before = await client.diagnosticsOf(uri, (list) => list.some((each) => code(each) === 'unknown-catalog'));
      assert.ok(
        before.some((each) => code(each) === 'unknown-catalog'),
        JSON.stringify(before.map((each) => each.message)),
      );
      const watchersOf = (registration: { registerOptions?: unknown }) =>
        (registration.registerOptions as { watchers: { globPattern: string | { baseUri: string; pattern: string } }[] }).watchers;
      const outsideRegistration = await client.until(
        () =>
          client.registrations.find(
            (registration) =>
              registration.method === 'workspace/didChangeWatchedFiles' &&
              watchersOf(registration).some((watcher) => typeof watcher.globPattern !== 'string'),
          ),
        'a watcher for the folder outside the workspace',
      );
      assert.deepEqual(
        watchersOf(outsideRegistration).map((watcher) => watcher.globPattern),
        [{ baseUri: fileUri(outside), pattern: '*.{xosc,mosc,xodr}' }],
        'only the folder outside the workspace, not the project folder the workspace registration covers',
      );

      const catalog = twoCatalogs('car_blue')['second/VehicleCatalog.xosc'];
      fs.writeFileSync(path.join(outside, 'VehicleCatalog.xosc'), catalog);
      await client.connection.sendNotification('workspace/didChangeWatchedFiles', {
        changes: [{ uri: fileUri(path.join(outside, 'VehicleCatalog.xosc')), type: 1 }],
      });
      const after = await client.diagnosticsOf(uri, (list) => !list.some((each) => /^unknown-catalog/.test(code(each) ?? '')));
      assert.ok(!after.some((each) => /^unknown-catalog/.test(code(each) ?? '')), JSON.stringify(after.map((each) => each.message)));

      await client.connection.sendNotification('textDocument/didClose', { textDocument: { uri } });
      await client.until(() => client.unregistrations.includes(outsideRegistration.id), 'the watcher let go once no open file reads there');
    } finally {
      await client.stop();
    }
  });
});

describe('the folders outside the workspace that get watchers', () => {
  it('are those no watched root holds, each once, sorted and bounded', () => {
    const roots = ['/work/project', '/shared/scenarios'];
    const read = ['/work/project/catalogs', '/work/project', '/opt/catalogs', '/shared/scenarios/deep/er', '/opt/catalogs', '/a/roads'];
    assert.deepEqual(foldersToWatch(read, roots), ['/a/roads', '/opt/catalogs']);
    assert.deepEqual(foldersToWatch(read, roots, 1), ['/a/roads']);
    // A sibling whose name starts like a root is not inside it.
    assert.deepEqual(foldersToWatch(['/work/project-old'], roots), ['/work/project-old']);
  });
});

describe("language server: an imported group's controller File that lies only beside its file (issue 27)", function () {
  this.timeout(60_000);

  it('is warned of live at the CatalogReference, with a watcher for the path, and the warning goes once the file lies beside the main', async () => {
    const root = temporaryWorkspace({ 'straight.xodr': STRAIGHT_ROAD });
    const { module } = importedCatalogController(root, path.join(root, 'straight.xodr'), 'modules');
    fs.mkdirSync(path.join(root, 'modules', 'inputs'));
    fs.writeFileSync(path.join(root, 'modules', 'inputs', 'acc.cfg'), '');
    const client = await TestClient.start({ root, pullDiagnostics: true });
    try {
      await client.indexed();
      await client.openFile(path.join(root, 'main.xosc'));
      const moduleUri = await client.openFile(module);
      const warningsOf = async () =>
        (await client.request<{ items: Diagnostic[] }>('textDocument/diagnostic', { textDocument: { uri: moduleUri } })).items.filter(
          (each) => problemCodeOf(each) === 'file-path',
        );
      const before = await warningsOf();
      const message = String(before[0]?.message);
      assert.equal(before.length, 1, JSON.stringify(before));
      assert.ok(
        message.startsWith(
          `catalog entry 'acc' names its controller File 'inputs/acc.cfg', which esmini looks up from the working folder, then from the folder of ` +
            `the scenario that uses the entry: from the folder of ${path.join(root, 'main.xosc')}, which imports this group, it names ` +
            `${path.join(root, 'inputs', 'acc.cfg')}, which does not exist; the file lies beside this file (${path.join(root, 'modules', 'inputs', 'acc.cfg')})`,
        ),
        message,
      );
      const line = fs
        .readFileSync(module, 'utf8')
        .split('\n')
        .findIndex((text) => text.includes('entryName="acc"'));
      assert.equal(before[0].range.start.line, line);
      const patterns = (registration: { registerOptions?: unknown }) =>
        (registration.registerOptions as { watchers: { globPattern: string | { baseUri: string; pattern: string } }[] }).watchers.map(
          (watcher) => watcher.globPattern,
        );
      await client.until(
        () =>
          client.registrations.find(
            (registration) =>
              registration.method === 'workspace/didChangeWatchedFiles' &&
              patterns(registration).some(
                (pattern) => typeof pattern !== 'string' && pattern.baseUri === fileUri(root) && pattern.pattern === 'inputs/acc.cfg',
              ),
          ),
        "a watcher for the path esmini reads the File from, which the workspace's registration of scenarios does not cover",
      );

      fs.mkdirSync(path.join(root, 'inputs'));
      fs.writeFileSync(path.join(root, 'inputs', 'acc.cfg'), '');
      await client.connection.sendNotification('workspace/didChangeWatchedFiles', {
        changes: [{ uri: fileUri(path.join(root, 'inputs', 'acc.cfg')), type: 1 }],
      });
      // The notification is handled on its own turn: pulled until the analysis after it answers.
      const deadline = Date.now() + 20_000;
      let after = await warningsOf();
      while (after.length > 0 && Date.now() < deadline) {
        await new Promise((resolve) => setTimeout(resolve, 50));
        after = await warningsOf();
      }
      assert.deepEqual(after, [], 'no warning once the File lies beside the main');
    } finally {
      await client.stop();
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});
