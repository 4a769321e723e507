import * as assert from 'node:assert/strict';
import { SCHEMA_ORDER } from '../../../server/src/core/diagnostics/schemaOrder';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-order', () => {
  it('names the element out of order and what must come before it', () => {
    const text = BASE.replace('<CatalogLocations/>', '').replace('<RoadNetwork>', '<RoadNetwork></RoadNetwork><CatalogLocations/><X>');
    const problem = schemaProblemsOf(text).find((candidate) => candidate.code === 'schema-order');
    assert.equal(problem?.message, '<RoadNetwork> is out of order in <OpenSCENARIO>: <CatalogLocations> must come before it');
    assert.equal(problem?.severity, SCHEMA_ORDER.severity);
    assert.equal(ruleIdOf('schema-order'), 'asam.net:xosc:1.0.0:xml.valid_schema');
  });
});
