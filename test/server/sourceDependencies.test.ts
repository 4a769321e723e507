import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { diskRef } from '../../server/src/core/sources';
import { DEFAULT_SETTINGS } from '../../server/src/settings';
import { SourceDependencies } from '../../server/src/sourceDependencies';
import { Workspace } from '../../server/src/workspace';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

const sorted = (ids: Iterable<string>) => [...ids].sort();

describe('server: the reverse index of source dependencies', () => {
  it('a change makes stale the file, every source depending on it (transitively listed) and no other', () => {
    const dependencies = new SourceDependencies();
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/a.xosc', '/w/b.xosc']);
    dependencies.set('/w/a.xosc', ['/w/a.xosc', '/w/b.xosc']);
    dependencies.set('/w/b.xosc', ['/w/b.xosc']);
    dependencies.set('/w/other.xosc', ['/w/other.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/b.xosc'])), ['/w/a.xosc', '/w/b.xosc', '/w/main.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/a.xosc'])), ['/w/a.xosc', '/w/main.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/unread.xosc'])), ['/w/unread.xosc']);
  });

  it('a dependency a source no longer has, or a source forgotten, makes it stale no more; one it gained does', () => {
    const dependencies = new SourceDependencies();
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/a.xosc']);
    // Read again after an edit that took the reference to a.xosc out and put one to b.xosc in.
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/b.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/a.xosc'])), ['/w/a.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/b.xosc'])), ['/w/b.xosc', '/w/main.xosc']);
    dependencies.delete('/w/main.xosc');
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/b.xosc'])), ['/w/b.xosc']);
    assert.equal(dependencies.get('/w/main.xosc'), undefined);
  });

  it('a source forgotten and read again depends on what its new read found, whether or not it is what it found before', () => {
    const dependencies = new SourceDependencies();
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/a.xosc']);
    dependencies.delete('/w/main.xosc');
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/a.xosc'])), ['/w/a.xosc']);
    // Read again to the same files (a keystroke in a value): its links are taken as they were.
    dependencies.readStarted('/w/main.xosc');
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/a.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/a.xosc'])), ['/w/a.xosc', '/w/main.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/b.xosc'])), ['/w/b.xosc']);
    // Forgotten, then read again to other files: the file it no longer reads makes it stale no more.
    dependencies.delete('/w/main.xosc');
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/b.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/a.xosc'])), ['/w/a.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/b.xosc'])), ['/w/b.xosc', '/w/main.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/main.xosc'])), ['/w/main.xosc']);
  });

  it('a folder or package changed makes stale the sources depending on a file below it, and only below it', () => {
    const dependencies = new SourceDependencies();
    dependencies.set('/w/main.xosc', ['/w/main.xosc', '/w/lib.mosc/simple.xosc']);
    dependencies.set('/w/cat/vehicles.xosc', ['/w/cat/vehicles.xosc']);
    dependencies.set('/w/catalogs.xosc', ['/w/catalogs.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/lib.mosc'])), ['/w/lib.mosc', '/w/lib.mosc/simple.xosc', '/w/main.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/cat'])), ['/w/cat', '/w/cat/vehicles.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w'])), [
      '/w',
      '/w/cat/vehicles.xosc',
      '/w/catalogs.xosc',
      '/w/lib.mosc/simple.xosc',
      '/w/main.xosc',
    ]);
    // A source forgotten is stale no more: the package's path and the file below it are named, no source.
    dependencies.delete('/w/main.xosc');
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/lib.mosc'])), ['/w/lib.mosc', '/w/lib.mosc/simple.xosc']);
  });

  it('a source still being read is stale after any change, until its dependencies are known', () => {
    const dependencies = new SourceDependencies();
    dependencies.readStarted('/w/main.xosc');
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/unrelated.xosc'])), ['/w/main.xosc', '/w/unrelated.xosc']);
    dependencies.set('/w/main.xosc', ['/w/main.xosc']);
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/unrelated.xosc'])), ['/w/unrelated.xosc']);
    dependencies.readStarted('/w/a.xosc');
    dependencies.readFailed('/w/a.xosc');
    assert.deepEqual(sorted(dependencies.staleAfter(['/w/unrelated.xosc'])), ['/w/unrelated.xosc']);
  });

  it("the server's analysis follows a dependency an edit added, and keeps its source over a change of one the edit removed", async () => {
    const files: Record<string, string> = {
      's1.xosc': scenario(simpleGroup('S1')),
      's2.xosc': scenario(simpleGroup('S2')),
    };
    const mainOf = (file: string, group: string) => scenario(outerGroup('Car', 'car', [{ file, groups: [{ name: group }] }]));
    files['main.xosc'] = mainOf('s1.xosc', 'S1');
    const root = temporaryWorkspace(files);
    const workspace = new Workspace();
    workspace.configure([root], DEFAULT_SETTINGS);
    const main = diskRef(path.join(root, 'main.xosc'));
    const uri = `file://${main.disk}`;
    workspace.documents.add(uri, TextDocument.create(uri, 'xml', 1, files['main.xosc']), Promise.resolve(main));
    workspace.open(uri, main);
    const groupProblems = async () =>
      (await workspace.analyze(main)).problems.filter((problem) => /\bS[12]\b/.test(problem.message)).map((problem) => problem.message);
    assert.deepEqual(await groupProblems(), []);
    // The edit moves the reference from s1.xosc to s2.xosc.
    workspace.documents.setText(uri, TextDocument.create(uri, 'xml', 2, mainOf('s2.xosc', 'S2')));
    workspace.update(main);
    assert.deepEqual(await groupProblems(), []);
    const readAfterEdit = await workspace.source(main);
    // s1.xosc, no longer read, loses its group: the main file's source stays as it was read.
    fs.writeFileSync(path.join(root, 's1.xosc'), scenario(simpleGroup('Other1')));
    workspace.fileChanged(path.join(root, 's1.xosc'), false);
    assert.equal(await workspace.source(main), readAfterEdit, 'the main file was read again for a file it no longer reads');
    assert.deepEqual(await groupProblems(), []);
    // s2.xosc, read since the edit, loses its group: the main file is read again and reports it.
    fs.writeFileSync(path.join(root, 's2.xosc'), scenario(simpleGroup('Other2')));
    workspace.fileChanged(path.join(root, 's2.xosc'), false);
    assert.notEqual(await workspace.source(main), readAfterEdit);
    assert.equal((await groupProblems()).length, 1, 'the missing group S2 is reported');
  });
});
