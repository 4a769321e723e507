import * as assert from 'node:assert/strict';
import { SCHEMA_UNKNOWN_ELEMENT } from '../../../server/src/core/diagnostics/schemaUnknownElement';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { schemaFixed, schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-unknown-element', () => {
  it('names the element and the closest one the schema allows, and renames the start and end tags to it', async () => {
    const text = BASE.replace('<Entities>', '<Entitys>').replace('</Entities>', '</Entitys>');
    const problem = schemaProblemsOf(text).find((candidate) => candidate.code === 'schema-unknown-element');
    assert.equal(problem?.message, '<OpenSCENARIO> has no child <Entitys> in OpenSCENARIO 1.2');
    assert.deepEqual(problem?.data, { suggestion: 'Entities' });
    assert.deepEqual(await schemaFixed(text, SCHEMA_UNKNOWN_ELEMENT), { title: 'Change to <Entities>', text: BASE });
    assert.equal(ruleIdOf('schema-unknown-element'), 'asam.net:xosc:1.0.0:xml.valid_schema');
  });

  it('checks the data a client sends back, and offers nothing without a suggestion', async () => {
    assert.equal(SCHEMA_UNKNOWN_ELEMENT.isData!({ suggestion: 'Entities' }), true);
    assert.equal(SCHEMA_UNKNOWN_ELEMENT.isData!({ suggestion: 1 }), false);
    const text = BASE.replace('<Entities>', '<X/><Entities>');
    assert.equal(await schemaFixed(text, SCHEMA_UNKNOWN_ELEMENT), undefined);
  });
});
