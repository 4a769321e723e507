import * as assert from 'node:assert/strict';
import { UNKNOWN_CATALOG_ENTRY } from '../../../server/src/core/diagnostics/unknownCatalogEntry';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/core/semantics-corpus.test.ts (test/support/openscenarioCorpus.ts). */
describe('diagnostics: unknown-catalog-entry', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNKNOWN_CATALOG_ENTRY.code, 'unknown-catalog-entry');
    assert.equal(UNKNOWN_CATALOG_ENTRY.severity, 'error');
    assert.equal(ruleIdOf('unknown-catalog-entry'), UNKNOWN_CATALOG_ENTRY.rule.qcRule ?? 'modular2simple:unknown-catalog-entry');
    assert.equal(UNKNOWN_CATALOG_ENTRY.isData!({ suggestion: 'car' }), true);
    assert.equal(UNKNOWN_CATALOG_ENTRY.isData!({ suggestion: null }), false);
  });
});
