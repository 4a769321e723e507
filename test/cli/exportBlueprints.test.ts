import * as assert from 'node:assert/strict';
import { drivingScenario, runCli } from '../support/fixtures';
import { listFiles, temporaryWorkspace } from '../support/workspace';

/** `export --target carla` of a driving scenario with the blueprint table `table`, in a workspace of its own. */
function exportWithTable(table: string): { status: number; stderr: string; files: string[] } {
  const root = temporaryWorkspace({ 'scenario.xosc': drivingScenario('Town05', 'Drive'), 'blueprints.json': table });
  const run = runCli(['export', 'scenario.xosc', '--target', 'carla', '-o', 'out.xosc', '--blueprints', 'blueprints.json'], { cwd: root });
  return { status: run.status, stderr: run.stderr, files: listFiles(root) };
}

describe('cli: export --blueprints names the line and column of what is wrong in the table', () => {
  it('a table that is not JSON (a trailing comma): its line and column, exit 1, nothing written (was: "at position 68")', () => {
    const result = exportWithTable('{\n  "car_white": "vehicle.audi.tt",\n  "car_red": "vehicle.tesla.model3",\n}\n');
    assert.equal(result.status, 1, result.stderr);
    assert.match(result.stderr, /blueprints\.json: the blueprint table is not JSON \(line 4, column 1: /);
    assert.doesNotMatch(result.stderr, /position/);
    assert.deepEqual(result.files, ['blueprints.json', 'scenario.xosc']);
  });

  it('a blueprint CARLA does not have: where it is written, and the closest one CARLA has', () => {
    const result = exportWithTable('{\n  "car_white": "vehicle.audi.tt",\n  "car_red":   "vehicle.tesla.model_3"\n}\n');
    assert.equal(result.status, 1, result.stderr);
    assert.match(
      result.stderr,
      /blueprints\.json: the blueprint table maps 'car_red' to 'vehicle\.tesla\.model_3', which is no CARLA .* blueprint .*; did you mean 'vehicle\.tesla\.model3'\? \(line 3, column 16\)/,
    );
    assert.deepEqual(result.files, ['blueprints.json', 'scenario.xosc']);
  });

  it('without a table, a vehicle named otherwise is spawned as its category says, and the loss says how to choose in the file itself', () => {
    const root = temporaryWorkspace({ 'scenario.xosc': drivingScenario('Town05', 'Drive') });
    const run = runCli(['export', 'scenario.xosc', '--target', 'carla', '-o', 'out.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    // The editor's Export for CARLA… has no --blueprints: the remedy names what to write in the scenario first.
    assert.match(
      run.stderr,
      /'car' is no CARLA blueprint: spawned as vehicle\.tesla\.model3 .*to spawn another, name the Vehicle after a CARLA blueprint, such as vehicle\.audi\.tt; on the command line, a table given with --blueprints FILE\.json/,
    );
    assert.match(run.stderr, /<Storyboard\/StopTrigger> its condition groups are added to the StopTrigger of the one act \[/);
  });
});
