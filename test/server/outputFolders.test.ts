import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { writeFileAtomicMakingFolders } from '../../common/src/atomic';
import { listFiles, temporaryWorkspace } from '../support/workspace';

/** Data whose writing fails after its first chunk, as a full disk would. */
async function* failingData(): AsyncIterable<Uint8Array> {
  yield Buffer.from('<OpenSCENARIO>');
  throw new Error('no space left on the device');
}

describe('server: an output written into folders that do not exist yet (the save dialog offered to create them)', () => {
  it('makes the folders and writes the file', async () => {
    const root = temporaryWorkspace();
    const output = path.join(root, 'a', 'b', 'out.xosc');
    await writeFileAtomicMakingFolders(output, '<OpenSCENARIO/>');
    assert.equal(fs.readFileSync(output, 'utf8'), '<OpenSCENARIO/>');
    assert.deepEqual(listFiles(root), [path.join('a', 'b', 'out.xosc')]);
  });

  it('removes the folders it made when the file cannot be written, and keeps a folder that was there', async () => {
    const root = temporaryWorkspace({ 'kept/other.xosc': 'x' });
    await assert.rejects(
      writeFileAtomicMakingFolders(path.join(root, 'kept', 'new', 'deeper', 'out.xosc'), failingData()),
      /no space left/,
    );
    assert.deepEqual(fs.readdirSync(root), ['kept']);
    assert.deepEqual(listFiles(root), [path.join('kept', 'other.xosc')]);
  });
});
