import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { checkCleanAndFlatten } from '../support/cliChecks';
import { EsminiStep, requireEsmini, runEsmini } from '../support/esmini';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const example = path.join(repoRoot, 'examples', 'case-study');

/**
 * The paper's case study (a collision at an intersection, police and ambulance arriving at the site) composed from
 * the built-in library's modules (issue 28, item 4): examples/case-study/main.xosc, docs/case-study-from-library.md.
 */
describe('cli: the case study rebuilt from library modules', function () {
  this.timeout(120_000);
  let folder: string;
  before(() => {
    folder = temporaryFolder('m2s-case-study-');
  });
  after(() => fs.rmSync(folder, { recursive: true, force: true }));

  it('checks clean, flattens, and in esmini the two cars collide and stop, police and ambulance stop behind them', async function () {
    const flat = path.join(folder, 'flat.xosc');
    const text = await checkCleanAndFlatten(path.join(example, 'main.xosc'), flat);
    assert.doesNotMatch(text, /ScenarioReference|parameterAttributes/);
    // Every module copy is there, named OUTER.INNER.
    for (const group of [
      'Collision.CrossingPath',
      'Vehicle0Stops.LeadBrake',
      'Vehicle1Stops.LeadBrake',
      'PoliceArrives.LeadBrake',
      'AmbulanceArrives.LeadBrake',
    ])
      assert.match(text, new RegExp(`<ManeuverGroup[^>]*name="${group.replace('.', '\\.')}"`), group);

    requireEsmini(this);
    const steps = await runEsmini(flat, 20);
    const last = steps[steps.length - 1];
    assert.ok(last.time > 19, `esmini ran to ${last.time} s`);
    const at = (time: number): EsminiStep => steps.find((step) => step.time >= time) ?? last;
    const distance = (step: EsminiStep, a: string, b: string) =>
      Math.hypot(step.positions[a][0] - step.positions[b][0], step.positions[a][1] - step.positions[b][1]);
    // The collision: crossing-path brings vehicle_1 to the conflict point as vehicle_0 gets there.
    const closest = steps.reduce((best, step) =>
      distance(step, 'vehicle_0', 'vehicle_1') < distance(best, 'vehicle_0', 'vehicle_1') ? step : best,
    );
    // Positions are the rear axles' (the boxes' centres are 1.5 m ahead): 5 m apart, crossing at right angles, the
    // boxes overlap, as esmini's --collision reports (at 4.8 s).
    assert.ok(
      distance(closest, 'vehicle_0', 'vehicle_1') < 5,
      `they meet (closest ${distance(closest, 'vehicle_0', 'vehicle_1').toFixed(2)} m at ${closest.time} s)`,
    );
    assert.ok(
      Math.abs(closest.positions.vehicle_0[0] - 1.75) < 4,
      `at the crossroads' conflict point (x ${closest.positions.vehicle_0[0]})`,
    );
    // Then everyone stands still: the same place at 15 s and at the end.
    for (const entity of ['vehicle_0', 'vehicle_1', 'police', 'ambulance']) {
      const moved = Math.hypot(
        at(15).positions[entity][0] - last.positions[entity][0],
        at(15).positions[entity][1] - last.positions[entity][1],
      );
      assert.ok(moved < 0.05, `${entity} stands still after 15 s (moved ${moved.toFixed(2)} m)`);
    }
    assert.ok(distance(last, 'vehicle_0', 'vehicle_1') < 6, 'the crashed cars stay together');
    // Police and ambulance arrive from the west behind vehicle_0, in its lane, without touching it or each other.
    const [crash, police, ambulance] = [last.positions.vehicle_0, last.positions.police, last.positions.ambulance];
    assert.ok(
      police[0] < crash[0] - 5 && police[0] > crash[0] - 40,
      `the police stops behind the crash (x ${police[0]} against ${crash[0]})`,
    );
    assert.ok(
      ambulance[0] < police[0] - 5 && ambulance[0] > police[0] - 40,
      `the ambulance stops behind the police (x ${ambulance[0]} against ${police[0]})`,
    );
    assert.ok(Math.abs(police[1] - crash[1]) < 0.1 && Math.abs(ambulance[1] - crash[1]) < 0.1, 'in vehicle_0 lane');
  });

  it('stats counts the main against its flattening and each library module it reuses once', async function () {
    const output: string[] = [];
    const errors: string[] = [];
    assert.equal(
      await main(['stats', example, '--format', 'json'], { out: (line) => output.push(line), err: (line) => errors.push(line) }),
      0,
      errors.join('\n'),
    );
    const stats = JSON.parse(output.join('\n')) as {
      rows: { scenario: string; modularLines: number; flattenedLines: number }[];
      shared: { file: string; lines: number }[];
    };
    assert.deepEqual(
      stats.rows.map((row) => row.scenario),
      ['main.xosc'],
    );
    const [row] = stats.rows;
    assert.ok(
      row.modularLines < row.flattenedLines,
      `the main (${row.modularLines} lines) is shorter than its flattening (${row.flattenedLines})`,
    );
    assert.deepEqual(stats.shared.map((item) => path.relative(repoRoot, item.file)).sort(), [
      'library/crossing-path.xosc',
      'library/lead-brake.xosc',
    ]);
    for (const item of stats.shared) assert.equal(item.lines, fs.readFileSync(item.file, 'utf8').split('\n').length - 1, item.file);
  });
});
