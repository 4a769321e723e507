import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Diagnostic } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { temporaryWorkspace } from '../support/workspace';
import { mainWithKeys, SIMPLE } from './fixtures/scenarios';
import { fileUri, TestClient } from './harness';

describe('language server: workspaces as users have them (JSON-RPC)', function () {
  const simpleText = SIMPLE;
  /** A main file in a sub-folder whose simple scenario lies elsewhere: found only through a search root or a scenario path. */
  const mainIn = (fileName: string) => mainWithKeys([]).replace('scenarioFileName="simple.xosc"', `scenarioFileName="${fileName}"`);
  let parent: string;
  let client: TestClient | undefined;

  before(function () {
    parent = temporaryWorkspace({
      'first/placeholder.xosc': simpleText,
      'second/lib.xosc': simpleText,
      'second/sub/main.xosc': mainIn('lib.xosc'),
      'second/libraries/own.xosc': simpleText,
      'second/other/uses-own.xosc': mainIn('own.xosc'),
    });
  });

  afterEach(async function () {
    await client?.stop();
    client = undefined;
  });

  after(function () {
    if (parent) fs.rmSync(parent, { recursive: true, force: true });
  });

  const codesOf = async (filePath: string, predicate?: (diagnostics: Diagnostic[]) => boolean) =>
    (await (client as TestClient).diagnosticsOf(await (client as TestClient).openFile(filePath), predicate)).map((diagnostic) =>
      problemCodeOf(diagnostic),
    );

  it('searches upward to the folder a file is in, not only to the first folder', async function () {
    client = await TestClient.start({ root: path.join(parent, 'first'), folders: [path.join(parent, 'second')] });
    await client.indexed();
    assert.deepEqual(await codesOf(path.join(parent, 'second', 'sub', 'main.xosc')), []);
  });

  it('reads the scenario path setting of each folder', async function () {
    client = await TestClient.start({
      root: path.join(parent, 'first'),
      folders: [path.join(parent, 'second')],
      settings: { scenarioPath: ['nowhere'] },
      folderSettings: { [path.join(parent, 'second')]: { scenarioPath: ['libraries'] } },
    });
    await client.indexed();
    assert.deepEqual(await codesOf(path.join(parent, 'second', 'other', 'uses-own.xosc')), []);
  });

  it('follows workspace folders being added', async function () {
    client = await TestClient.start({ root: path.join(parent, 'first') });
    await client.indexed();
    const uri = fileUri(path.join(parent, 'second', 'sub', 'main.xosc'));
    assert.deepEqual(await codesOf(path.join(parent, 'second', 'sub', 'main.xosc')), ['missing-file']);
    await client.connection.sendNotification('workspace/didChangeWorkspaceFolders', {
      event: { added: [{ uri: fileUri(path.join(parent, 'second')), name: 'second' }], removed: [] },
    });
    await client.until(
      () => (client as TestClient).diagnostics.get(uri)?.diagnostics.length === 0 || undefined,
      'the file to resolve in its new folder',
    );
  });

  it('checks an untitled document', async function () {
    client = await TestClient.start({ root: path.join(parent, 'second') });
    await client.indexed();
    const uri = await client.open(
      'untitled:Untitled-1',
      mainIn('lib.xosc').replace(
        'maneuverGroupName="Brake">',
        'maneuverGroupName="Brake">\n<ParameterReference key="nosuchkey" value="1"/>',
      ),
    );
    const diagnostics = await client.diagnosticsOf(uri);
    assert.deepEqual(
      diagnostics.map((diagnostic) => problemCodeOf(diagnostic)),
      ['unknown-key'],
    );
  });
});
