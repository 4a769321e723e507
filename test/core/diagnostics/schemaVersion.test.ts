import * as assert from 'node:assert/strict';
import { SCHEMA_VERSION } from '../../../server/src/core/diagnostics/schemaVersion';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-version', () => {
  it('says which schema a version the project has none of is checked against, as information', () => {
    const problem = schemaProblemsOf(BASE.replace('revMinor="2"', 'revMinor="9"')).find((candidate) => candidate.code === 'schema-version');
    assert.equal(problem?.message, 'no schema for OpenSCENARIO 1.9: checked against the OpenSCENARIO 1.3 schema');
    assert.equal(problem?.severity, SCHEMA_VERSION.severity);
    assert.equal(ruleIdOf('schema-version'), 'modular2simple:schema-version');
  });
});
