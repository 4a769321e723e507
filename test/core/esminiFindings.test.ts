/** esmini's findings of a run, taken from the run's own analysis (issue 27). */
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { esminiFindingsOfAnalysis } from '../../server/src/core/flatten/esminiFindings';
import { Problem } from '../../server/src/core/problems';
import { diskRef, refId, ScenarioStore, SourceRef } from '../../server/src/core/sources';
import { removeRunFolder, runScenario } from '../../server/src/esmini/run';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { libraryDir, repoRoot, requireCorpus, sharedDir } from '../support/paths';
import { listFiles, temporaryWorkspace } from '../support/workspace';
import { groupScenario, ROAD } from './diagnostics/networkSupport';
import { temporaryFolder } from '../support/temporaryDirectory';

/** Each finding as file, place and message, sorted: the two ways must agree finding for finding. */
function keys(problems: readonly Problem[]): string[] {
  return problems
    .filter((problem) => problem.code === 'simulator')
    .map(
      (problem) =>
        `${refId(problem.source)}:${problem.range.start.line}:${problem.range.start.character}:${problem.severity}:${problem.message}`,
    )
    .sort();
}

describe("core: esmini's findings from an analysis made for another simulator", function () {
  this.timeout(300_000);

  it('are those an analysis of the main for esmini gives, on every scenario and package of the shared corpus', async function () {
    requireCorpus(this);
    const corpus = path.join(sharedDir, 'corpus');
    const mains = listFiles(corpus)
      .filter((file) => /\.(xosc|mosc)$/i.test(file))
      .map((file) => path.join(corpus, file));
    assert.ok(mains.length > 200, `${mains.length} files`);
    let findings = 0;
    for (const file of mains) {
      // The paper's library finds its simple scenarios as the original tool did, through SCENARIO_PATH.
      const store = new ScenarioStore({ scenarioPath: file.startsWith(libraryDir) ? [libraryDir] : [], root: corpus });
      const main: SourceRef = file.endsWith('.mosc') ? { disk: file, entries: ['main.xosc'] } : diskRef(file);
      const standard = await new Flattener(store).analyze(main);
      const esmini = await new Flattener(store, 'esmini').analyze(main);
      const expected = keys(esmini.problems);
      assert.deepEqual(keys(esminiFindingsOfAnalysis(standard.source)), expected, file);
      findings += expected.length;
    }
    assert.ok(findings > 200, `${findings} findings in all`);
  });
  it('are those an analysis for esmini gives of a group esmini refuses for its actors, in the file and imported from it', async () => {
    const entityCondition =
      '<StartTrigger><ConditionGroup><Condition name="Near" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities><EntityCondition><StandStillCondition duration="1"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger>\n      </Act>';
    const selecting = groupScenario('<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>', { actors: '' })
      .replace('selectTriggeringEntities="false">', 'selectTriggeringEntities="true">')
      .replace(/<StartTrigger\/>\n {6}<\/Act>/, entityCondition);
    const main = selecting.replace(
      /<ManeuverGroup name="G"[\s\S]*?<\/ManeuverGroup>/,
      '<ManeuverGroup name="Outer" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>' +
        '<ScenarioReference scenarioFileName="modules/simple.xosc"><ManeuverGroupReference maneuverGroupName="G"/></ScenarioReference></ManeuverGroup>',
    );
    assert.notEqual(main, selecting);
    const root = temporaryWorkspace({ 'road.xodr': ROAD, 'modules/road.xodr': ROAD, 'modules/simple.xosc': selecting, 'main.xosc': main });
    try {
      const store = new ScenarioStore({ root, scenarioPath: [] });
      for (const file of ['modules/simple.xosc', 'main.xosc']) {
        const ref = diskRef(path.join(root, file));
        const expected = keys((await new Flattener(store, 'esmini').analyze(ref)).problems);
        assert.equal(expected.length, 1, `${file}: ${expected.join('\n')}`);
        assert.deepEqual(keys(esminiFindingsOfAnalysis((await new Flattener(store).analyze(ref)).source)), expected, file);
      }
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});

describe("esmini: a run names esmini's findings without analysing the main again", function () {
  this.timeout(120_000);

  it("analyses nothing for esmini beyond the run's own flattening, and names the finding", async function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-esmini-findings-');
    fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
    const file = path.join(root, 'lane_change.xosc');
    const text = fs
      .readFileSync(file, 'utf8')
      .replace('<SimulationTimeCondition value="0" rule="greaterThan"/>', '<SimulationTimeCondition value="0" rule="equalTo"/>');
    fs.writeFileSync(file, text);
    const analyze = Flattener.prototype.analyze;
    let analysedForEsmini = 0;
    Flattener.prototype.analyze = function (this: Flattener, main: SourceRef) {
      if (this.simulator === 'esmini') analysedForEsmini++;
      return analyze.call(this, main);
    };
    try {
      const result = await runScenario(new Flattener(new ScenarioStore({ root })), diskRef(file), {
        esminiPath: esminiBinary,
        roadPath: [esminiRoads],
        duration: 0.5,
      });
      removeRunFolder(result);
      assert.equal(result.outcome, 'ok', result.message);
      assert.equal(analysedForEsmini, 0);
      const line = text.split('\n').findIndex((each) => each.includes('name="ActStart"'));
      assert.deepEqual(
        result.esminiFindings.map((finding) => [finding.range.start.line, finding.severity]),
        [[line, 'warning']],
      );
    } finally {
      Flattener.prototype.analyze = analyze;
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});
