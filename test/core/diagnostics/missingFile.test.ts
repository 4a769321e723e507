import * as assert from 'node:assert/strict';
import { leftOutOfPackageWording, MISSING_FILE, missingFileWording } from '../../../server/src/core/diagnostics/missingFile';
import { fixContext, RANGE } from './support';

describe('diagnostics: missing-file', () => {
  it('names where it looked, and the closest file there before any other hint', () => {
    assert.deepEqual(missingFileWording('a.xosc', ['/w', '/s'], 'b.xosc', 'set SCENARIO_PATH'), {
      severity: 'error',
      code: 'missing-file',
      message: "cannot find 'a.xosc'; searched /w, /s",
      hint: "did you mean 'b.xosc'?",
    });
    assert.equal(missingFileWording('a.xosc', ['/w'], undefined, 'set SCENARIO_PATH').hint, 'set SCENARIO_PATH');
    assert.deepEqual(leftOutOfPackageWording('a.xosc'), {
      severity: 'information',
      code: 'missing-file',
      message: "'a.xosc' was found through SCENARIO_PATH and is left out of the package",
      hint: 'pass --include-scenario-path to store it too',
    });
  });

  it('changes the name to the closest file, and offers nothing without one', async () => {
    assert.deepEqual(await MISSING_FILE.fixes!(fixContext({ suggestion: 'b.xosc' })), [
      { title: "Change to 'b.xosc'", edits: [{ place: 'document', range: RANGE, newText: 'b.xosc' }], preferred: true },
    ]);
    assert.deepEqual(await MISSING_FILE.fixes!(fixContext(undefined)), []);
  });
});
