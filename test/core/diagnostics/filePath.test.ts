import * as assert from 'node:assert/strict';
import {
  FILE_PATH,
  importedControllerFileWording,
  packagedPathOnStandardOutputWording,
  reachesOutsidePackageWording,
  unrebasedPathWording,
} from '../../../server/src/core/diagnostics/filePath';

/** Where pack and flatten report these: test/core/rebase.test.ts, test/cli/outputPaths.test.ts, test/server/outputPaths.test.ts. */
describe('diagnostics: file-path', () => {
  it('says what a package reaches outside itself, and how to carry it or why it is left', () => {
    const road = { kind: 'file', disk: '/w/road.xodr', written: 'road.xodr', viaParameter: false } as const;
    assert.deepEqual(reachesOutsidePackageWording({ ...road, rewritten: '../road.xodr' }), {
      severity: 'warning',
      code: 'file-path',
      message:
        "the package reaches the file /w/road.xodr outside itself (written '../road.xodr', relative to the package's folder); the package does not run without it",
      hint: 'pack with --self-contained to store it inside the package',
    });
    assert.deepEqual(reachesOutsidePackageWording({ ...road, kind: 'directory', written: '$Roads', viaParameter: true }), {
      severity: 'warning',
      code: 'file-path',
      message: 'the package reaches the folder /w/road.xodr outside itself; the package does not run without it',
      hint: "'$Roads' names a parameter, so it is left as written: --self-contained stores the file only where the parameter's value names it inside the package (no '..', not absolute); otherwise write the path itself",
    });
  });

  it('says what a flattened output cannot name from where it is written', () => {
    assert.deepEqual(packagedPathOnStandardOutputWording('road.xodr', 'roads/road.xodr'), {
      severity: 'warning',
      code: 'file-path',
      message: "'road.xodr' names roads/road.xodr inside the package, which standard output cannot carry; it is left as written",
      hint: "flatten to a file: the package's files are then written beside it",
    });
    assert.equal(
      unrebasedPathWording('a finding').hint,
      'declare the parameter with an absolute path, or write the output beside this file',
    );
    assert.equal(FILE_PATH.severity, 'warning');
  });

  it("says where esmini looks for an imported group's controller File that lies only beside the group's file, and what to do", () => {
    assert.deepEqual(
      importedControllerFileWording('acc', "'inputs/acc.cfg'", '/w/main.xosc', '/w/inputs/acc.cfg', '/w/modules/inputs/acc.cfg'),
      {
        severity: 'warning',
        code: 'file-path',
        message:
          "catalog entry 'acc' names its controller File 'inputs/acc.cfg', which esmini looks up from the working folder, then from the folder of " +
          'the scenario that uses the entry: from the folder of /w/main.xosc, which imports this group, it names /w/inputs/acc.cfg, which does ' +
          "not exist; the file lies beside this file (/w/modules/inputs/acc.cfg), so the flattened scenario runs without the controller's File",
        hint: "copy /w/modules/inputs/acc.cfg to /w/inputs/acc.cfg, or write the File's path absolute in the catalog entry",
      },
    );
  });
});
