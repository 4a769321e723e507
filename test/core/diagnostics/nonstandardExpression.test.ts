import * as assert from 'node:assert/strict';
import { NONSTANDARD_EXPRESSION } from '../../../server/src/core/diagnostics/nonstandardExpression';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/core/semantics-rules.test.ts and test/cli/qcBundle.test.ts (test/support/qcRuleFiles.ts). */
describe('diagnostics: nonstandard-expression', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(NONSTANDARD_EXPRESSION.code, 'nonstandard-expression');
    assert.equal(NONSTANDARD_EXPRESSION.severity, 'warning');
    assert.equal(ruleIdOf('nonstandard-expression'), NONSTANDARD_EXPRESSION.rule.qcRule ?? 'modular2simple:nonstandard-expression');
  });
});
