import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { Diagnostic } from 'vscode-languageserver/node';
import { childRef, diskRef, refId, SourceRef } from '../../server/src/core/sources';
import { IndexedFile, WorkspaceIndex } from '../../server/src/workspaceIndex';
import { problemCodeOf } from '../support/diagnostics';
import { cycleFile, MAIN, mainWithKeys, SIMPLE, withDuplicateGroups } from './fixtures/scenarios';
import { useServer } from './harness';

/** An index entry of a scenario file on disk naming `names` in its ScenarioReferences (undefined: not scanned). */
function scanned(filePath: string, names: string[] | undefined, kind: IndexedFile['kind'] = 'xosc'): IndexedFile {
  return {
    path: filePath,
    kind,
    groups: [],
    modular: kind === 'mosc' || (names?.length ?? 0) > 0,
    catalogReferences: [],
    scenarioNames: names,
  };
}

const referrers = (entries: IndexedFile[], target: SourceRef) =>
  WorkspaceIndex.referrersOf(entries, target).map((ref) => refId(ref).replaceAll(path.sep, '/'));

/** The reverse index of scenario references (issue 25): a pull of one file's diagnostics analyses the main files that may reach it, no other. */
describe('language server: the workspace index knows which main files may reach a scenario', function () {
  describe('from the names the index scanned', function () {
    const root = path.resolve('/w');
    const at = (name: string) => path.join(root, name);

    it('follows a chain of main files and a package, leaving out what names other files', () => {
      const entries = [
        scanned(at('top.xosc'), ['middle.xosc']),
        scanned(at('middle.xosc'), ['sub/Target.xosc']),
        scanned(at('other.xosc'), ['unrelated.xosc']),
        scanned(at('pkg.mosc'), ['target.xosc'], 'mosc'),
        scanned(at('uses-pkg.xosc'), ['pkg.xosc']),
        scanned(at('plain.xosc'), []),
      ];
      assert.deepEqual(referrers(entries, diskRef(at('sub/target.xosc'))), [
        '/w/top.xosc',
        '/w/middle.xosc',
        '/w/pkg.mosc/main.xosc',
        '/w/uses-pkg.xosc',
      ]);
    });

    it('reaches a folder package through its main file, and a file inside a package through the package', () => {
      const entries = [
        scanned(at('folder/main.xosc'), ['a.xosc']),
        scanned(at('outer.xosc'), ['folder.mosc']),
        scanned(at('x.xosc'), ['b.xosc']),
      ];
      assert.deepEqual(referrers(entries, diskRef(at('folder/a.xosc'))), ['/w/folder/main.xosc', '/w/outer.xosc']);
      const packaged = [
        scanned(at('p.mosc'), ['inner.xosc'], 'mosc'),
        scanned(at('q.mosc'), ['other.xosc'], 'mosc'),
        scanned(at('m.xosc'), ['p.mosc']),
      ];
      assert.deepEqual(referrers(packaged, childRef(diskRef(at('p.mosc')), 'inner.xosc')), ['/w/p.mosc/main.xosc', '/w/m.xosc']);
    });

    it('keeps every main whose names it cannot read, and passes through a file it did not scan', () => {
      const entries = [
        scanned(at('parameter.xosc'), ['$File']),
        scanned(at('up.xosc'), ['../elsewhere/t.xosc']),
        scanned(at('absolute.xosc'), [path.join(root, 'somewhere', 't.xosc')]),
        scanned(at('nested.mosc'), undefined, 'mosc'),
        scanned(at('big.xosc'), undefined),
        scanned(at('through-big.xosc'), ['big.xosc']),
        scanned(at('unrelated.xosc'), ['u.xosc']),
      ];
      assert.deepEqual(referrers(entries, diskRef(at('t.xosc'))), [
        '/w/parameter.xosc',
        '/w/up.xosc',
        '/w/absolute.xosc',
        '/w/nested.mosc/main.xosc',
        '/w/through-big.xosc',
      ]);
    });
  });

  describe('a pull of an open file (JSON-RPC)', function () {
    const files: Record<string, string> = {
      'simple.xosc': withDuplicateGroups(),
      'main.xosc': MAIN,
      // A chain: top.xosc reaches simple.xosc only through middle.xosc.
      'middle.xosc': mainWithKeys(['<ParameterReference key="AbsoluteTargetSpeed.value" value="9"/>']),
      'top.xosc': cycleFile('Top', 'middle.xosc'),
    };
    for (let index = 0; index < 20; index++) {
      files[`unrelated/u${index}.xosc`] = SIMPLE;
      files[`unrelated/m${index}.xosc`] = mainWithKeys([]).replace('scenarioFileName="simple.xosc"', `scenarioFileName="u${index}.xosc"`);
    }
    const server = useServer(files, 'main.xosc', { pullDiagnostics: true });

    it("analyses only the main files that may reach it, reads none of the others' files, and walks no folder", async function () {
      const workspace = server.client.workspace;
      const analysed: string[] = [];
      const analyze = workspace.analyze.bind(workspace);
      workspace.analyze = (ref) => {
        analysed.push(path.relative(server.root, refId(ref)));
        return analyze(ref);
      };
      const read = new Set<string>();
      const readFile = workspace.files.readFile.bind(workspace.files);
      workspace.files.readFile = (filePath, maxBytes) => {
        read.add(path.relative(server.root, filePath));
        return readFile(filePath, maxBytes);
      };
      let walks = 0;
      const walk = workspace.index.walk.bind(workspace.index);
      workspace.index.walk = (folders) => {
        walks++;
        return walk(folders);
      };
      try {
        const uri = await server.client.openFile(path.join(server.root, 'simple.xosc'));
        const report = await server.client.request<{ items: Diagnostic[] }>('textDocument/diagnostic', { textDocument: { uri } });
        // The duplicate Brake is reported because main.xosc and middle.xosc refer to that name.
        assert.deepEqual(report.items.map((diagnostic) => problemCodeOf(diagnostic)).sort(), [
          'duplicate-group',
          'unknown-parameter-attribute',
        ]);
        assert.deepEqual([...new Set(analysed)].sort(), ['main.xosc', 'middle.xosc', 'simple.xosc', 'top.xosc']);
        assert.deepEqual(
          [...read].filter((file) => file.startsWith('unrelated')),
          [],
          'files read that reach no simple.xosc',
        );
        assert.equal(walks, 0, 'the index kept the list of files');
        await server.client.close(uri);
      } finally {
        workspace.analyze = analyze;
        workspace.files.readFile = readFile;
        workspace.index.walk = walk;
      }
    });
  });
});
