import * as assert from 'node:assert/strict';
import { UNKNOWN_TRAFFIC_SIGNAL, unknownTrafficSignalWording } from '../../../server/src/core/diagnostics/unknownTrafficSignal';
import { ruleIdOf } from '../../../server/src/core/rules';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: unknown-traffic-signal', () => {
  it('names the signal and the road file, with the QC rule', () => {
    assert.deepEqual(unknownTrafficSignalWording('999', 'road.xodr'), {
      severity: 'error',
      code: 'unknown-traffic-signal',
      message:
        "traffic signal '999' is neither a signal of the road network road.xodr nor one a TrafficSignalController of the scenario sets",
      hint: 'name the id of a <signal> of the OpenDRIVE file',
    });
    assert.equal(UNKNOWN_TRAFFIC_SIGNAL.severity, 'error');
    assert.equal(ruleIdOf('unknown-traffic-signal'), UNKNOWN_TRAFFIC_SIGNAL.rule.qcRule);
  });

  it('is what the document checks report on a signal the road file lacks', async () => {
    const action = (name: string) =>
      `<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="${name}" state="off;off;on"/></TrafficSignalAction></InfrastructureAction></GlobalAction>`;
    const found = (await semanticProblemsOf(groupScenario(action('999')), { 'road.xodr': ROAD })).filter(
      (problem) => problem.code === 'unknown-traffic-signal',
    );
    // The road file is named by its path, which lies in the test's own folder.
    const roadFile = /road network (.*road\.xodr) nor/.exec(found[0]?.message ?? '')?.[1] ?? 'no road file named';
    assert.deepEqual(found.map(wordingOf), [unknownTrafficSignalWording('999', roadFile)]);
    const known = await semanticProblemsOf(groupScenario(action('101')), { 'road.xodr': ROAD });
    assert.deepEqual(
      known.filter((problem) => problem.code === 'unknown-traffic-signal'),
      [],
    );
  });
});
