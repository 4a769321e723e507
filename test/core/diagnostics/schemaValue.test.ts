import * as assert from 'node:assert/strict';
import { SCHEMA_VALUE } from '../../../server/src/core/diagnostics/schemaValue';
import { ruleIdOf } from '../../../server/src/core/rules';
import { repairedValue } from '../../../server/src/core/schema/values';
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

  it("writes a value of the right type where the slip is one of form: a date without its time (ScenarioRunner's catalogs), a decimal comma, True", async () => {
    const dated = BASE.replace(/date="[^"]*"/, 'date="2020-02-17"');
    const problem = schemaProblemsOf(dated).find((candidate) => candidate.code === 'schema-value');
    assert.match(problem?.message ?? '', /'2020-02-17' is not a valid value of FileHeader\.date \(DateTime\)/);
    assert.equal(problem?.hint, "did you mean '2020-02-17T00:00:00'?");
    const fixed = await schemaFixed(dated, SCHEMA_VALUE);
    assert.equal(fixed?.title, "Change to '2020-02-17T00:00:00'");
    assert.deepEqual(
      schemaProblemsOf(fixed?.text ?? '').filter((candidate) => candidate.code === 'schema-value'),
      [],
    );
    const spaced = BASE.replace(/date="[^"]*"/, 'date="2020-02-17 10:30:00"');
    assert.equal((await schemaFixed(spaced, SCHEMA_VALUE))?.title, "Change to '2020-02-17T10:30:00'");
    const comma = BASE.replace(/maxSpeed="([^"]*)"/, 'maxSpeed="69,4"');
    assert.notEqual(comma, BASE);
    assert.equal((await schemaFixed(comma, SCHEMA_VALUE))?.title, "Change to '69.4'");
    // Nothing of the kind: no guess.
    const boolean = { alternatives: [{ builtin: 'boolean' as const }], parameter: true, expression: false };
    assert.equal(repairedValue(boolean, 'True'), 'true');
    assert.equal(repairedValue(boolean, 'yes'), undefined);
    const word = BASE.replace(/date="[^"]*"/, 'date="yesterday"');
    assert.equal(schemaProblemsOf(word).find((candidate) => candidate.code === 'schema-value')?.hint, undefined);
  });
});
