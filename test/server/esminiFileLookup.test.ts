/** Catalogs and road files found where esmini finds them, through the language server (issue 27). */
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Location } from 'vscode-languageserver/node';
import { positionAt } from '../support/cursor';
import { STRAIGHT_ROAD } from '../support/roads';
import { twoCatalogs } from '../support/twoCatalogs';
import { temporaryWorkspace } from '../support/workspace';
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
