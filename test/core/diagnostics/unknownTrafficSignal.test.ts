import * as fs from 'node:fs';
import * as path from 'node:path';
import * as assert from 'node:assert/strict';
import { UNKNOWN_TRAFFIC_SIGNAL, unknownTrafficSignalWording } from '../../../server/src/core/diagnostics/unknownTrafficSignal';
import { ruleIdOf } from '../../../server/src/core/rules';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';
import { analyzeDocument, semanticProblems } from '../../../server/src/core/semantics';
import { CatalogLoader } from '../../../server/src/core/semantics/catalogs';
import { childRef, diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { parseXml } from '../../../server/src/core/xml';
import { packageOf } from '../../support/fixtures';
import { temporaryWorkspace } from '../../support/workspace';

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

  const action = (name: string) =>
    `<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="${name}" state="off;off;on"/></TrafficSignalAction></InfrastructureAction></GlobalAction>`;

  it('is what the document checks report on a signal the road file lacks', async () => {
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

  it("reads the road the scenario's .mosc holds, as a run loads it (issue 27; before, such a road was never read)", async () => {
    const signalsIn = async (name: string) => {
      const text = groupScenario(action(name));
      const root = temporaryWorkspace({ 'pkg.mosc': await packageOf({ 'main.xosc': text, 'road.xodr': ROAD }) });
      try {
        const semantics = await analyzeDocument(
          childRef(diskRef(path.join(root, 'pkg.mosc')), 'main.xosc'),
          parseXml(text),
          new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
          false,
        );
        return { root, found: semanticProblems(semantics).filter((problem) => problem.code === 'unknown-traffic-signal') };
      } finally {
        fs.rmSync(root, { recursive: true, force: true });
      }
    };
    const unknown = await signalsIn('999');
    assert.deepEqual(unknown.found.map(wordingOf), [
      unknownTrafficSignalWording('999', `${path.join(unknown.root, 'pkg.mosc')}/road.xodr`),
    ]);
    assert.deepEqual((await signalsIn('101')).found, []);
  });
});
