import * as assert from 'node:assert/strict';
import { UNKNOWN_CATALOG } from '../../../server/src/core/diagnostics/unknownCatalog';
import { ruleIdOf } from '../../../server/src/core/rules';

/** Where the document checks report it: test/server/parameters.test.ts and test/cli/realFileShapes.test.ts. */
describe('diagnostics: unknown-catalog', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(UNKNOWN_CATALOG.code, 'unknown-catalog');
    assert.equal(UNKNOWN_CATALOG.severity, 'error');
    assert.equal(ruleIdOf('unknown-catalog'), UNKNOWN_CATALOG.rule.qcRule ?? 'modular2simple:unknown-catalog');
  });
});
