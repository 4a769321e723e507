import * as assert from 'node:assert/strict';
import {
  NON_POSITIVE_PHASE_DURATION,
  nonPositivePhaseDurationWording,
} from '../../../server/src/core/diagnostics/nonPositivePhaseDuration';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: non-positive-phase-duration', () => {
  it('is an error below zero and a warning at zero, naming both readings', () => {
    assert.deepEqual(nonPositivePhaseDurationWording(-1), {
      severity: 'error',
      code: 'non-positive-phase-duration',
      message: 'the duration of a Phase must be positive; it is -1 s',
    });
    assert.deepEqual(nonPositivePhaseDurationWording(0), {
      severity: 'warning',
      code: 'non-positive-phase-duration',
      message: "a Phase of duration 0 is within the standard's range [0..inf[, but ASAM's Quality Checker requires a positive duration",
    });
    assert.equal(NON_POSITIVE_PHASE_DURATION.severity, 'error');
  });

  it('is what the document checks report on a Phase of duration 0', async () => {
    const signals = `<TrafficSignals><TrafficSignalController name="Ctrl"><Phase name="go" duration="0"><TrafficSignalState trafficSignalId="101" state="on"/></Phase></TrafficSignalController></TrafficSignals>`;
    const action = '<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>';
    const problems = await semanticProblemsOf(groupScenario(action, { trafficSignals: signals }), { 'road.xodr': ROAD });
    assert.deepEqual(problems.filter((problem) => problem.code === 'non-positive-phase-duration').map(wordingOf), [
      nonPositivePhaseDurationWording(0),
    ]);
  });
});
