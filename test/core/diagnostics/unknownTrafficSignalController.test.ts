import * as assert from 'node:assert/strict';
import {
  UNKNOWN_TRAFFIC_SIGNAL_CONTROLLER,
  unknownTrafficSignalControllerWording,
} from '../../../server/src/core/diagnostics/unknownTrafficSignalController';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: unknown-traffic-signal-controller', () => {
  it("names the reference and the scenario's controllers, or says it declares none", () => {
    assert.deepEqual(unknownTrafficSignalControllerWording('Nope', ['A', 'B']), {
      severity: 'error',
      code: 'unknown-traffic-signal-controller',
      message: "'Nope' is not a TrafficSignalController of this scenario's RoadNetwork (it has 'A', 'B')",
    });
    assert.equal(
      unknownTrafficSignalControllerWording('Nope', []).message,
      "'Nope' is not a TrafficSignalController of this scenario's RoadNetwork (it declares none)",
    );
    assert.equal(UNKNOWN_TRAFFIC_SIGNAL_CONTROLLER.severity, 'error');
  });

  it('is what the document checks report on a controller reference the scenario does not declare', async () => {
    const signals = `<TrafficSignals><TrafficSignalController name="Ctrl"><Phase name="go" duration="10"><TrafficSignalState trafficSignalId="101" state="on"/></Phase></TrafficSignalController></TrafficSignals>`;
    const action = `<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalControllerAction trafficSignalControllerRef="Other" phase="go"/></TrafficSignalAction></InfrastructureAction></GlobalAction>`;
    const problems = await semanticProblemsOf(groupScenario(action, { trafficSignals: signals }), { 'road.xodr': ROAD });
    assert.deepEqual(problems.filter((problem) => problem.code === 'unknown-traffic-signal-controller').map(wordingOf), [
      unknownTrafficSignalControllerWording('Other', ['Ctrl']),
    ]);
  });
});
