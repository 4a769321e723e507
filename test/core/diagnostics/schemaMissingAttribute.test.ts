import * as assert from 'node:assert/strict';
import { SCHEMA_MISSING_ATTRIBUTE } from '../../../server/src/core/diagnostics/schemaMissingAttribute';
import { roadScenario } from '../../support/fixtures';
import { schemaFixed, schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-missing-attribute', () => {
  it('names the attributes, and adds each after the last attribute with a placeholder of its type', async () => {
    const text = BASE.replace(' maxSpeed="50"', '');
    const problem = schemaProblemsOf(text).find((candidate) => candidate.code === 'schema-missing-attribute');
    assert.equal(problem?.message, "<Performance> lacks the required attribute 'maxSpeed'");
    assert.deepEqual(problem?.data, { missing: ['maxSpeed'] });
    const fixed = await schemaFixed(text, SCHEMA_MISSING_ATTRIBUTE);
    assert.equal(fixed?.title, "Add 'maxSpeed'");
    assert.match(fixed?.text ?? '', /<Performance maxAcceleration="5" maxDeceleration="5" maxSpeed="[^"]+"\/>/);
    assert.deepEqual(
      schemaProblemsOf(fixed?.text ?? '').filter((candidate) => candidate.code === 'schema-missing-attribute'),
      [],
    );
  });

  it('checks the data a client sends back', () => {
    assert.equal(SCHEMA_MISSING_ATTRIBUTE.isData!({ missing: ['a'] }), true);
    assert.equal(SCHEMA_MISSING_ATTRIBUTE.isData!({ missing: 'a' }), false);
  });
});
