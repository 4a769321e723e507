import * as assert from 'node:assert/strict';
import { AMBIGUOUS_REFERENCE } from '../../../server/src/core/diagnostics/ambiguousReference';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/core/semantics.test.ts. */
describe('diagnostics: ambiguous-reference', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(AMBIGUOUS_REFERENCE.code, 'ambiguous-reference');
    assert.equal(AMBIGUOUS_REFERENCE.severity, 'warning');
    assert.equal(ruleIdOf('ambiguous-reference'), AMBIGUOUS_REFERENCE.rule.qcRule ?? 'modular2simple:ambiguous-reference');
  });
});
