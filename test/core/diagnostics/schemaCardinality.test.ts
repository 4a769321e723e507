import * as assert from 'node:assert/strict';
import { SCHEMA_CARDINALITY } from '../../../server/src/core/diagnostics/schemaCardinality';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-cardinality', () => {
  it('names the element that occurs too often and how often it may', () => {
    const problem = schemaProblemsOf(BASE.replace('<StopTrigger/>', '<StopTrigger/><StopTrigger/>')).find(
      (candidate) => candidate.code === 'schema-cardinality',
    );
    assert.equal(problem?.message, 'too many <StopTrigger> in <Storyboard>: at most 1');
    assert.equal(problem?.severity, SCHEMA_CARDINALITY.severity);
    assert.equal(ruleIdOf('schema-cardinality'), 'asam.net:xosc:1.0.0:xml.valid_schema');
  });
});
