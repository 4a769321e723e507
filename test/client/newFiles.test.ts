import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { writeNewFiles } from '../../client/src/naming';
import { temporaryFolder } from '../support/temporaryDirectory';
import { listFiles } from '../support/workspace';

/** What New Modular Scenario and New Scenario from Template write with: new files only, all or none. */
describe('client: writing new files (New Modular Scenario, New Scenario from Template)', () => {
  it('writes every file, making the folders they need', async () => {
    const folder = temporaryFolder();
    const files = [
      { path: path.join(folder, 'main.xosc'), text: '<main/>' },
      { path: path.join(folder, 'roads', 'deep', 'road.xodr'), text: '<road/>' },
    ];
    assert.deepEqual(await writeNewFiles(files), [files[0].path, files[1].path]);
    assert.equal(fs.readFileSync(files[0].path, 'utf8'), '<main/>');
    assert.equal(fs.readFileSync(files[1].path, 'utf8'), '<road/>');
  });

  it('never replaces a file: the one that exists keeps its text, nothing else is written, the error names it', async () => {
    const folder = temporaryFolder();
    fs.writeFileSync(path.join(folder, 'main.xosc'), 'mine');
    await assert.rejects(writeNewFiles([{ path: path.join(folder, 'main.xosc'), text: 'new' }]), (error: Error) => {
      assert.equal(error.message, `${path.join(folder, 'main.xosc')} exists already and is left as it was`);
      return true;
    });
    assert.equal(fs.readFileSync(path.join(folder, 'main.xosc'), 'utf8'), 'mine');
    assert.deepEqual(listFiles(folder), ['main.xosc']);
  });

  it('when the second file exists, removes the first again and the folders it made: the disk is as it was', async () => {
    const folder = temporaryFolder();
    fs.mkdirSync(path.join(folder, 'roads'));
    fs.writeFileSync(path.join(folder, 'roads', 'road.xodr'), 'theirs');
    const files = [
      { path: path.join(folder, 'new', 'sub', 'main.xosc'), text: '<main/>' },
      { path: path.join(folder, 'roads', 'road.xodr'), text: '<road/>' },
      { path: path.join(folder, 'later.xosc'), text: '<later/>' },
    ];
    await assert.rejects(writeNewFiles(files), (error: Error) => {
      assert.match(error.message, new RegExp(`^${escaped(files[1].path)} exists already and is left as it was`));
      assert.match(error.message, new RegExp(`removed again: ${escaped(files[0].path)}$`));
      return true;
    });
    assert.equal(fs.readFileSync(files[1].path, 'utf8'), 'theirs');
    assert.deepEqual(fs.readdirSync(folder).sort(), ['roads']);
    assert.deepEqual(listFiles(folder), ['roads/road.xodr']);
  });

  it('a folder that cannot be made (a file stands in its place): the error names the file, what was written goes', async () => {
    const folder = temporaryFolder();
    fs.writeFileSync(path.join(folder, 'roads'), 'a file');
    const files = [
      { path: path.join(folder, 'main.xosc'), text: '<main/>' },
      { path: path.join(folder, 'roads', 'road.xodr'), text: '<road/>' },
    ];
    await assert.rejects(writeNewFiles(files), (error: Error) => {
      assert.match(error.message, new RegExp(`^could not write ${escaped(files[1].path)}: `));
      return true;
    });
    assert.deepEqual(listFiles(folder), ['roads']);
  });
});

function escaped(text: string): string {
  return text.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
}
