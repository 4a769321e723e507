import * as assert from 'node:assert/strict';
import { TYPE_MISMATCH } from '../../../server/src/core/diagnostics/typeMismatch';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/server/parameterTypes.test.ts and test/core/values.test.ts. */
describe('diagnostics: type-mismatch', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(TYPE_MISMATCH.code, 'type-mismatch');
    assert.equal(TYPE_MISMATCH.severity, 'error');
    assert.equal(ruleIdOf('type-mismatch'), TYPE_MISMATCH.rule.qcRule ?? 'modular2simple:type-mismatch');
  });
});
