import * as assert from 'node:assert/strict';
import { SCHEMA_VALUE } from '../../../server/src/core/diagnostics/schemaValue';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { schemaFixed, schemaProblemsOf } from './support';

/** A scenario the schema check finds nothing else to report in but its empty Act. */
const BASE = roadScenario({ groups: [] });

describe('diagnostics: schema-value', () => {
  it('names the value, the type and what it allows, and changes it to the closest allowed value', async () => {
    const text = BASE.replace('vehicleCategory="car"', 'vehicleCategory="cra"');
    const problem = schemaProblemsOf(text).find((candidate) => candidate.code === 'schema-value');
    assert.equal(
      problem?.message,
      "'cra' is not a valid value of Vehicle.vehicleCategory (VehicleCategory): expected one of bicycle, bus, car, motorbike, semitrailer, trailer, train, tram, truck, van, a $parameter",
    );
    assert.deepEqual(await schemaFixed(text, SCHEMA_VALUE), { title: "Change to 'car'", text: BASE });
    assert.equal(ruleIdOf('schema-value'), 'asam.net:xosc:1.0.0:xml.valid_schema');
  });
});
