import * as assert from 'node:assert/strict';
import { SCHEMA_MISSING_ELEMENT } from '../../../server/src/core/diagnostics/schemaMissingElement';
import { roadScenario } from '../../support/fixtures';
import { schemaFixed, schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-missing-element', () => {
  it('names the element, and inserts a minimal skeleton of it where it goes', async () => {
    const text = BASE.replace('<StopTrigger/>', '');
    const problem = schemaProblemsOf(text).find((candidate) => candidate.code === 'schema-missing-element');
    assert.equal(problem?.message, '<Storyboard> lacks the required element <StopTrigger>');
    assert.deepEqual(problem?.data, { missing: ['StopTrigger'], parent: 'Storyboard' });
    const fixed = await schemaFixed(text, SCHEMA_MISSING_ELEMENT);
    assert.equal(fixed?.title, 'Insert <StopTrigger>');
    assert.deepEqual(
      schemaProblemsOf(fixed?.text ?? '').map((candidate) => candidate.message),
      schemaProblemsOf(BASE).map((candidate) => candidate.message),
    );
  });

  it('checks the data a client sends back', () => {
    assert.equal(SCHEMA_MISSING_ELEMENT.isData!({ missing: ['A'], parent: 'B', insertAt: '3' }), true);
    assert.equal(SCHEMA_MISSING_ELEMENT.isData!({ missing: ['A'] }), false);
  });
});
