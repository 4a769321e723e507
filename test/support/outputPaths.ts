import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, EsminiStep, readEsminiCsv, repeatableRunArgs } from './esmini';
import { esminiXodrDir } from './esminiBinaries';
import { sharedDir } from './paths';
import { runBounded } from './processes';
import { temporaryFolder } from './temporaryDirectory';

/**
 * What the SPEC 11.6 tests (CLI and language server) share: a composition of esmini's cut-in laid out as
 * esmini's corpus is, and esmini run on an output alone (no --path, from an unrelated working folder).
 */
export const esminiCorpus = path.join(sharedDir, 'corpus', 'openscenario', 'esmini');

/** esmini evaluates this expression to the literal below; the project's own reading of it is another task's. */
const GLUED_NAME = '${BrakeCondition_HWT + _ + $HeadwayTime_Brake}';

/**
 * ws/xosc/{cut-in.xosc, main.xosc, Catalogs/Vehicles}, ws/xodr/e6mini.xodr; returns ws, two folders below a
 * temporary folder, so that an output written two folders up from ws lands in that folder, which goes with it.
 */
export function cutInWorkspace(): string {
  const ws = path.join(temporaryFolder('m2s-paths-'), 'parent', 'ws');
  fs.mkdirSync(path.join(ws, 'xosc', 'Catalogs', 'Vehicles'), { recursive: true });
  fs.mkdirSync(path.join(ws, 'xodr'));
  fs.copyFileSync(path.join(esminiXodrDir, 'e6mini.xodr'), path.join(ws, 'xodr', 'e6mini.xodr'));
  fs.copyFileSync(
    path.join(esminiCorpus, 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'),
    path.join(ws, 'xosc', 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'),
  );
  const original = fs.readFileSync(path.join(esminiCorpus, 'cut-in.xosc'), 'utf8').replace(GLUED_NAME, 'BrakeCondition_HWT_0.7');
  fs.writeFileSync(path.join(ws, 'xosc', 'cut-in.xosc'), original);
  // The main file is the same scenario with its one group imported from cut-in.xosc.
  const groupStart = original.indexOf('<ManeuverGroup maximumExecutionCount="1" name="CutInAndBrakeSequence">');
  const groupEnd = original.indexOf('</ManeuverGroup>', groupStart) + '</ManeuverGroup>'.length;
  assert.ok(groupStart > 0 && groupEnd > groupStart, 'cut-in.xosc has its group');
  const outer = `<ManeuverGroup maximumExecutionCount="1" name="CutIn">
               <Actors selectTriggeringEntities="false">
                  <EntityRef entityRef="OverTaker"/>
               </Actors>
               <ScenarioReference scenarioFileName="cut-in.xosc">
                  <ManeuverGroupReference maneuverGroupName="CutInAndBrakeSequence"/>
               </ScenarioReference>
            </ManeuverGroup>`;
  fs.writeFileSync(path.join(ws, 'xosc', 'main.xosc'), original.slice(0, groupStart) + outer + original.slice(groupEnd));
  return ws;
}

/** Runs esmini on a scenario headless, fixed step 0.05, seed 1, from an unrelated working folder and with no --path but those `extraArgs` name. */
export async function runAlone(scenario: string, extraArgs: string[] = []): Promise<{ steps: EsminiStep[]; log: string }> {
  const cwd = temporaryFolder('m2s-paths-cwd-');
  const csv = path.join(cwd, 'run.csv');
  const { code, output } = await runBounded(esminiBinary, repeatableRunArgs(scenario, csv, ...extraArgs), { cwd }, 120_000);
  const log = output;
  assert.ok(code === 0 && fs.existsSync(csv), `esmini failed on ${scenario} (exit ${code}):\n${log.slice(-2000)}`);
  return { steps: readEsminiCsv(csv), log };
}

export function assertSameRun(actual: EsminiStep[], expected: EsminiStep[], what: string): void {
  assert.ok(expected.length > 100, `the original runs (${expected.length} steps)`);
  assert.equal(actual.length, expected.length, `${what}: number of steps`);
  for (let index = 0; index < expected.length; index++)
    assert.deepEqual(actual[index], expected[index], `${what}: step ${index} (t=${expected[index].time})`);
}

/** The file or folder a path attribute of a written scenario names, resolved from the scenario's folder. */
export function namedPaths(scenario: string): string[] {
  const text = fs.readFileSync(scenario, 'utf8');
  return [...text.matchAll(/<(?:LogicFile|Directory) (?:filepath|path)="([^"]*)"/g)].map((match) =>
    path.resolve(path.dirname(scenario), match[1]),
  );
}
