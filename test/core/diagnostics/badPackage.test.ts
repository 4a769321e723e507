import * as assert from 'node:assert/strict';
import { BAD_PACKAGE, badPackageWording, unreadablePackageWording } from '../../../server/src/core/diagnostics/badPackage';
import { mainOf } from '../../support/fixtures';
import { analysisProblemsOf } from './support';

describe('diagnostics: bad-package', () => {
  it("names the reference and gives the reader's reason and hint", () => {
    assert.deepEqual(unreadablePackageWording('lib.mosc', 'not a ZIP archive', 'rebuild the package with `modular2simple pack`'), {
      severity: 'error',
      code: 'bad-package',
      message: "cannot look up 'lib.mosc': not a ZIP archive",
      hint: 'rebuild the package with `modular2simple pack`',
    });
    assert.deepEqual(badPackageWording('broken'), { severity: 'error', code: 'bad-package', message: 'broken', hint: undefined });
    assert.equal(BAD_PACKAGE.severity, 'error');
  });

  it('is what an analysis reports on a reference to a package that is no ZIP archive', async () => {
    const problems = await analysisProblemsOf({ 'main.xosc': mainOf('lib.mosc'), 'lib.mosc': 'not a zip' });
    const found = problems.filter((problem) => problem.code === 'bad-package');
    assert.equal(found.length, 1, problems.map((problem) => `${problem.code}: ${problem.message}`).join('\n'));
    assert.match(found[0].message, /lib\.mosc is not a readable ZIP archive/);
    assert.equal(found[0].severity, BAD_PACKAGE.severity);
  });
});
