import * as assert from 'node:assert/strict';
import {
  duplicateInputWording,
  entryClashWording,
  INVALID_REFERENCE,
  mainCountWording,
  notPackableWording,
  outsidePackageWording,
} from '../../../server/src/core/diagnostics/invalidReference';
import { mainOf } from '../../support/fixtures';
import { analysisProblemsOf } from './support';

describe('diagnostics: invalid-reference', () => {
  it("words pack's inputs that make no package", () => {
    assert.deepEqual(notPackableWording('notes.txt'), {
      severity: 'error',
      code: 'invalid-reference',
      message: "'notes.txt' is neither a .xosc scenario nor a .mosc package",
      hint: 'pack only .xosc and .mosc files; with --self-contained, pack stores the road files, catalogs and other files the scenarios name inside the package',
    });
    assert.equal(
      duplicateInputWording('a.xosc', 'x/a.xosc').message,
      "two inputs are named 'a.xosc' (the other is x/a.xosc); names must be unique in a package",
    );
    assert.equal(mainCountWording(0).message, 'a package needs exactly one input named main.xosc; none was given');
    assert.equal(mainCountWording(2).message, 'a package needs exactly one main.xosc; 2 were given');
    assert.equal(mainCountWording(2).hint, 'name the modular main file main.xosc');
    assert.equal(
      entryClashWording('r.xodr', '/a/r.xodr', '/b/r.xodr').message,
      "two different files would be stored as 'r.xodr': /a/r.xodr and /b/r.xodr",
    );
    assert.equal(outsidePackageWording('../x.xosc').message, "'../x.xosc' points outside the package");
    assert.equal(INVALID_REFERENCE.severity, 'error');
  });

  it('is what an analysis reports on a scenarioFileName SPEC 2 does not allow', async () => {
    const problems = await analysisProblemsOf({ 'main.xosc': mainOf('simple.txt') });
    assert.deepEqual(
      problems.filter((problem) => problem.code === 'invalid-reference').map((problem) => problem.severity),
      ['error'],
      problems.map((problem) => `${problem.code}: ${problem.message}`).join('\n'),
    );
  });
});
