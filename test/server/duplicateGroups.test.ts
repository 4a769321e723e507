import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { mainWithKeys, withDuplicateGroups } from './fixtures/scenarios';
import { useServer } from './harness';
import { problemCodeOf } from '../support/diagnostics';

describe('language server: duplicate group names (JSON-RPC)', function () {
  const duplicated = withDuplicateGroups();
  const server = useServer({ 'simple.xosc': duplicated, 'main.xosc': mainWithKeys([]) }, 'main.xosc');

  it('warns on the reference that is ambiguous', async function () {
    const diagnostics = await server.client.diagnosticsOf(server.openUri);
    assert.deepEqual(
      diagnostics.map((diagnostic) => problemCodeOf(diagnostic)),
      ['ambiguous-group'],
    );
  });

  it('does not warn on duplicate names in a file of its own', async function () {
    const uri = await server.client.openFile(path.join(server.root, 'simple.xosc'));
    const diagnostics = await server.client.diagnosticsOf(uri);
    assert.deepEqual(
      diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'duplicate-group'),
      [],
    );
    await server.client.close(uri);
  });
});
