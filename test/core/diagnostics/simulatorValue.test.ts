import * as assert from 'node:assert/strict';
import { SIMULATOR_VALUE } from '../../../server/src/core/diagnostics/simulatorValue';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/core/values.test.ts (esmini's readings of expressions). */
describe('diagnostics: simulator-value', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(SIMULATOR_VALUE.code, 'simulator-value');
    assert.equal(SIMULATOR_VALUE.severity, 'warning');
    assert.equal(ruleIdOf('simulator-value'), SIMULATOR_VALUE.rule.qcRule ?? 'modular2simple:simulator-value');
  });
});
