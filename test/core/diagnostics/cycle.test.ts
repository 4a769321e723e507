import * as assert from 'node:assert/strict';
import { cycleWording, packageCycleWording } from '../../../server/src/core/diagnostics/cycle';

describe('diagnostics: cycle', () => {
  it('names the files of a reference cycle, and the folders of a package cycle', () => {
    assert.deepEqual(cycleWording(['a.xosc', 'b.xosc', 'a.xosc']), {
      severity: 'error',
      code: 'cycle',
      message: 'reference cycle: a.xosc -> b.xosc -> a.xosc',
      hint: 'remove one reference of the cycle',
    });
    assert.equal(packageCycleWording(['x', 'y', 'x']).message, 'package cycle: x -> y -> x');
  });
});
