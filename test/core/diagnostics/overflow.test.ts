import * as assert from 'node:assert/strict';
import { OVERFLOW } from '../../../server/src/core/diagnostics/overflow';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/core/values.test.ts. */
describe('diagnostics: overflow', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(OVERFLOW.code, 'overflow');
    assert.equal(OVERFLOW.severity, 'error');
    assert.equal(ruleIdOf('overflow'), OVERFLOW.rule.qcRule ?? 'modular2simple:overflow');
  });
});
