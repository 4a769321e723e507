import * as assert from 'node:assert/strict';
import { SCHEMA_UNKNOWN_ATTRIBUTE } from '../../../server/src/core/diagnostics/schemaUnknownAttribute';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { schemaFixed, schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-unknown-attribute', () => {
  it('names the attribute, and changes it to the closest one the element has', async () => {
    const text = BASE.replace('maxSpeed=', 'maxSped=');
    const problem = schemaProblemsOf(text).find((candidate) => candidate.code === 'schema-unknown-attribute');
    assert.equal(problem?.message, "<Performance> has no attribute 'maxSped' in OpenSCENARIO 1.2");
    assert.deepEqual(await schemaFixed(text, SCHEMA_UNKNOWN_ATTRIBUTE), { title: "Change to 'maxSpeed'", text: BASE });
    assert.equal(SCHEMA_UNKNOWN_ATTRIBUTE.severity, 'error');
    assert.equal(ruleIdOf('schema-unknown-attribute'), 'asam.net:xosc:1.0.0:xml.valid_schema');
  });
});
