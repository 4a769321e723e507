import * as assert from 'node:assert/strict';
import { UNDECLARED_CATALOG_PARAMETER } from '../../../server/src/core/diagnostics/undeclaredCatalogParameter';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/cli/qcBundle.test.ts (test/support/qcRuleFiles.ts). */
describe('diagnostics: undeclared-catalog-parameter', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNDECLARED_CATALOG_PARAMETER.code, 'undeclared-catalog-parameter');
    assert.equal(UNDECLARED_CATALOG_PARAMETER.severity, 'error');
    assert.equal(
      ruleIdOf('undeclared-catalog-parameter'),
      UNDECLARED_CATALOG_PARAMETER.rule.qcRule ?? 'modular2simple:undeclared-catalog-parameter',
    );
    assert.equal(UNDECLARED_CATALOG_PARAMETER.isData!({ parameter: 'P' }), true);
    assert.equal(UNDECLARED_CATALOG_PARAMETER.isData!({}), false);
  });
});
