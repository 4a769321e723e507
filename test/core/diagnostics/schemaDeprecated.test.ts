import * as assert from 'node:assert/strict';
import { SCHEMA_DEPRECATED } from '../../../server/src/core/diagnostics/schemaDeprecated';
import { ruleIdOf } from '../../../server/src/core/rules';
import { fixContext, RANGE } from './support';

/** Where the schema check reports it: test/core/schema.test.ts (deprecations) and test/core/checkerParity.test.ts. */
describe('diagnostics: schema-deprecated', () => {
  it("is a warning, struck through, whose fix writes the standard's replacement", async () => {
    assert.equal(SCHEMA_DEPRECATED.severity, 'warning');
    assert.equal(SCHEMA_DEPRECATED.deprecated, true);
    assert.deepEqual(await SCHEMA_DEPRECATED.fixes!(fixContext({ suggestion: 'curvaturePrime' })), [
      { title: "Change to 'curvaturePrime'", edits: [{ place: 'document', range: RANGE, newText: 'curvaturePrime' }], preferred: true },
    ]);
    assert.deepEqual(await SCHEMA_DEPRECATED.fixes!(fixContext(undefined)), []);
    assert.equal(ruleIdOf('schema-deprecated'), 'modular2simple:schema-deprecated');
  });
});
