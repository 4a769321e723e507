import * as assert from 'node:assert/strict';
import { DUPLICATE_NAME } from '../../../server/src/core/diagnostics/duplicateName';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/server/ruleLinks.test.ts and test/cli/qcBundle.test.ts (test/support/qcRuleFiles.ts). */
describe('diagnostics: duplicate-name', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(DUPLICATE_NAME.code, 'duplicate-name');
    assert.equal(DUPLICATE_NAME.severity, 'warning');
    assert.equal(ruleIdOf('duplicate-name'), DUPLICATE_NAME.rule.qcRule ?? 'modular2simple:duplicate-name');
  });
});
