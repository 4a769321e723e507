import * as assert from 'node:assert/strict';
import { UNKNOWN_ASSIGNED_PARAMETER } from '../../../server/src/core/diagnostics/unknownAssignedParameter';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/server/parameters.test.ts. */
describe('diagnostics: unknown-assigned-parameter', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNKNOWN_ASSIGNED_PARAMETER.code, 'unknown-assigned-parameter');
    assert.equal(UNKNOWN_ASSIGNED_PARAMETER.severity, 'error');
    assert.equal(
      ruleIdOf('unknown-assigned-parameter'),
      UNKNOWN_ASSIGNED_PARAMETER.rule.qcRule ?? 'modular2simple:unknown-assigned-parameter',
    );
    assert.equal(UNKNOWN_ASSIGNED_PARAMETER.isData!({ suggestion: 'Mass' }), true);
    assert.equal(UNKNOWN_ASSIGNED_PARAMETER.isData!({}), false);
  });
});
