import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';
import { CreateFile, TextDocumentEdit, TextEdit } from 'vscode-languageserver/node';
import { ExtractGroupRequest, FlattenToTextRequest } from '../../common/src/protocol';
import { firstDifference } from '../../server/src/core/equivalence';
import { buildModel } from '../../server/src/core/model';
import { parseXml } from '../../server/src/core/xml';
import { positionAt } from '../support/cursor';
import { requireCorpus, sharedDir } from '../support/paths';
import { applyEdits } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';
import { TestClient } from './harness';

const esminiShared = path.join(sharedDir, 'esmini');
const synchronize = path.join(sharedDir, 'corpus', 'openscenario', 'esmini', 'synchronize.xosc');

/**
 * Issue 28: a group whose catalog entry reads a parameter of its scenario without declaring it (esmini's
 * synchronize.xosc: HWManeuvers' Synchronize_NPC reads $AccRate, which esmini takes from the referencing scenario).
 * Extracted to a simple scenario, the group carries no `$AccRate` of its own; the simple scenario must declare it
 * all the same, or it does not flatten (nor load) on its own.
 */
describe('language server: Extract to a simple scenario declares what its catalog entries read from the scenario (JSON-RPC)', function () {
  this.timeout(120_000);
  let root: string;
  let client: TestClient;

  before(async function () {
    requireCorpus(this);
    // esmini's repository layout, which synchronize.xosc names: ../xosc/Catalogs and ../xodr beside its folder.
    root = temporaryWorkspace({ 'esmini/synchronize.xosc': fs.readFileSync(synchronize) }, 'm2s-extract-catalog-');
    fs.cpSync(path.join(esminiShared, 'Catalogs'), path.join(root, 'xosc', 'Catalogs'), { recursive: true });
    fs.mkdirSync(path.join(root, 'xodr'));
    fs.copyFileSync(path.join(esminiShared, 'xodr', 'e6mini.xodr'), path.join(root, 'xodr', 'e6mini.xodr'));
    client = await TestClient.start({ root, workspaceEdit: { documentChanges: true, resourceOperations: ['create'] } });
    await client.indexed();
  });
  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  async function flatten(uri: string): Promise<{ text: string | null; problems: string[] }> {
    const result = await client.send(FlattenToTextRequest, { uri, options: { force: false } });
    return { text: result.text, problems: result.problems.map((problem) => `${problem.severity} ${problem.message}`) };
  }

  it('Synchronize_NPC1_Sequence: the simple scenario declares AccRate as the source does, flattens on its own, and the main as before', async function () {
    const file = path.join(root, 'esmini', 'synchronize.xosc');
    const text = fs.readFileSync(file, 'utf8');
    const uri = await client.openFile(file);
    const before = await flatten(uri);
    assert.ok(before.text, `the source does not flatten: ${before.problems.join('; ')}`);
    const group = buildModel(parseXml(text)).groups.find((candidate) => candidate.name === 'Synchronize_NPC1_Sequence');
    assert.ok(group, 'synchronize.xosc has no group Synchronize_NPC1_Sequence');
    // The group itself names no $AccRate: only the catalog entry it references reads it.
    assert.doesNotMatch(text.slice(group.element.start, group.element.end), /AccRate/);

    const result = await client.send(ExtractGroupRequest, { uri, position: positionAt(text, group.element.start + 1) });
    let simpleFile = '';
    let main = text;
    for (const change of result.edit.documentChanges ?? []) {
      if (CreateFile.is(change)) simpleFile = fileURLToPath(change.uri);
      else if (TextDocumentEdit.is(change)) {
        const edits = change.edits.filter((item): item is TextEdit => 'newText' in item);
        if (change.textDocument.uri === uri) main = applyEdits(main, edits);
        else fs.writeFileSync(fileURLToPath(change.textDocument.uri), applyEdits('', edits));
      }
    }
    assert.ok(simpleFile && fs.existsSync(simpleFile), 'no simple scenario written');
    const simpleUri = await client.openFile(simpleFile);
    const alone = await flatten(simpleUri);
    assert.ok(alone.text, `the simple scenario does not flatten on its own: ${alone.problems.join('; ')}`);
    assert.deepEqual(
      alone.problems.filter((problem) => problem.startsWith('error')),
      [],
    );
    await client.close(simpleUri);
    assert.match(fs.readFileSync(simpleFile, 'utf8'), /<ParameterDeclaration name="AccRate" parameterType="double" value="3"\/>/);

    await client.change(uri, [{ text: main }]);
    const after = await flatten(uri);
    assert.ok(after.text, `the main does not flatten after the extract: ${after.problems.join('; ')}`);
    assert.equal(firstDifference(after.text, before.text), undefined, 'the main flattens differently after the extract');
    await client.close(uri);
  });
});
