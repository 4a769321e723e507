import * as assert from 'node:assert/strict';
import { distributionWording } from '../../../server/src/core/diagnostics/distribution';
import {
  UNKNOWN_DISTRIBUTION_PARAMETER,
  unknownDistributionParameterWording,
} from '../../../server/src/core/diagnostics/unknownDistributionParameter';
import { fixContext, RANGE } from './support';

describe('diagnostics: distribution and unknown-distribution-parameter', () => {
  it("says the engine's problem, placed in the ScenarioFile where it lies there", () => {
    assert.deepEqual(distributionWording('warning', 'step wider than range'), {
      severity: 'warning',
      code: 'distribution',
      message: 'step wider than range',
    });
    assert.equal(distributionWording('error', 'bad', { file: 's.xosc', line: 4 }).message, 'in the ScenarioFile (s.xosc:4): bad');
  });

  it('adds the closest declared name to an undeclared parameterName, and fixes it', async () => {
    assert.equal(unknownDistributionParameterWording('error', 'not declared', 'Speed').message, "not declared; did you mean 'Speed'?");
    assert.equal(unknownDistributionParameterWording('error', 'not declared', undefined).message, 'not declared');
    assert.deepEqual(await UNKNOWN_DISTRIBUTION_PARAMETER.fixes!(fixContext({ suggestion: 'Speed' })), [
      { title: "Change to 'Speed'", edits: [{ place: 'document', range: RANGE, newText: 'Speed' }], preferred: true },
    ]);
  });
});
