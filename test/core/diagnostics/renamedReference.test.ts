import * as assert from 'node:assert/strict';
import { RENAMED_REFERENCE } from '../../../server/src/core/diagnostics/renamedReference';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/core/semantics-flatten.test.ts. */
describe('diagnostics: renamed-reference', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(RENAMED_REFERENCE.code, 'renamed-reference');
    assert.equal(RENAMED_REFERENCE.severity, 'error');
    assert.equal(ruleIdOf('renamed-reference'), RENAMED_REFERENCE.rule.qcRule ?? 'modular2simple:renamed-reference');
    assert.equal(RENAMED_REFERENCE.isData!({ suggestion: 'G_2' }), true);
    assert.equal(RENAMED_REFERENCE.isData!('G_2'), false);
  });
});
