import * as assert from 'node:assert/strict';
import { DUPLICATE_CATALOG_ENTRY } from '../../../server/src/core/diagnostics/duplicateCatalogEntry';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/cli/qcBundle.test.ts (test/support/qcRuleFiles.ts). */
describe('diagnostics: duplicate-catalog-entry', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(DUPLICATE_CATALOG_ENTRY.code, 'duplicate-catalog-entry');
    assert.equal(DUPLICATE_CATALOG_ENTRY.severity, 'warning');
    assert.equal(ruleIdOf('duplicate-catalog-entry'), DUPLICATE_CATALOG_ENTRY.rule.qcRule ?? 'modular2simple:duplicate-catalog-entry');
  });
});
