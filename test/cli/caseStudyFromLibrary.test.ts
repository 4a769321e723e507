import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { checkCleanAndFlatten } from '../support/cliChecks';
import { EsminiStep, requireEsmini, runEsmini } from '../support/esmini';
import { runCli } from '../support/fixtures';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const example = path.join(repoRoot, 'examples', 'case-study');
/** The library's cars: the box's front is 3.75 m ahead of the reference point (the rear axle), its rear 0.75 m behind. */
const FRONT = 3.75;
const REAR = 0.75;
/** The original's four extra colliding cars, here a pile-up behind vehicle_1, each into the one ahead. */
const PILE_UP = ['vehicle_11', 'vehicle_12', 'vehicle_13', 'vehicle_14'];

/**
 * The paper's case study (a collision at an intersection, police and ambulance arriving at the site) composed from
 * the built-in library's modules (issue 28, item 4), with the leaving phase (arrive-leave-site): examples/case-study/main.xosc, docs/case-study-from-library.md.
 */
describe('cli: the case study rebuilt from library modules', function () {
  this.timeout(120_000);
  let folder: string;
  before(() => {
    folder = temporaryFolder('m2s-case-study-');
  });
  after(() => fs.rmSync(folder, { recursive: true, force: true }));

  it('checks clean, flattens, and in esmini the two cars collide and stop, four more pile up behind one, police and ambulance stop behind the other and leave', async function () {
    const flat = path.join(folder, 'flat.xosc');
    const text = await checkCleanAndFlatten(path.join(example, 'main.xosc'), flat);
    assert.doesNotMatch(text, /ScenarioReference|parameterAttributes/);
    // Every module copy is there, named OUTER.INNER.
    for (const group of [
      'Collision.CrossingPath',
      'Vehicle0Stops.LeadBrake',
      'Vehicle1Stops.LeadBrake',
      'PoliceAtSite.ArriveLeaveSite',
      'AmbulanceAtSite.ArriveLeaveSite',
      ...PILE_UP.map((vehicle) => `${vehicle.replace('vehicle_', 'Vehicle')}PilesUp.RearEndCollision`),
    ])
      assert.match(text, new RegExp(`<ManeuverGroup[^>]*name="${group.replace('.', '\\.')}"`), group);

    requireEsmini(this);
    const steps = await runEsmini(flat, 30);
    const last = steps[steps.length - 1];
    assert.ok(last.time > 29, `esmini ran to ${last.time} s`);
    const at = (time: number): EsminiStep => steps.find((step) => step.time >= time) ?? last;
    const distance = (step: EsminiStep, a: string, b: string) =>
      Math.hypot(step.positions[a][0] - step.positions[b][0], step.positions[a][1] - step.positions[b][1]);
    const samePlace = (one: EsminiStep, other: EsminiStep, entity: string) =>
      Math.hypot(one.positions[entity][0] - other.positions[entity][0], one.positions[entity][1] - other.positions[entity][1]) < 0.01;
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
    // Then everyone stands still a while: the same place at 16 s and at 18 s, the crashed cars to the end.
    for (const entity of ['hero', 'vehicle_0', 'vehicle_1', ...PILE_UP, 'police', 'ambulance']) {
      const moved = Math.hypot(
        at(16).positions[entity][0] - at(18).positions[entity][0],
        at(16).positions[entity][1] - at(18).positions[entity][1],
      );
      assert.ok(moved < 0.05, `${entity} stands still from 16 to 18 s (moved ${moved.toFixed(2)} m)`);
    }
    for (const entity of ['vehicle_0', 'vehicle_1', ...PILE_UP])
      assert.ok(samePlace(at(16), last, entity), `${entity} stays where it crashed`);
    // The pile-up (rear-end-collision): each of the four, set off at 6 s along the south arm, runs into the one ahead,
    // vehicle_1 first, and stands with its front on the other's rear (boxes touching, less than a step's 0.5 m over).
    PILE_UP.forEach((entity, index) => {
      const ahead = index === 0 ? 'vehicle_1' : PILE_UP[index - 1];
      const [x, y] = last.positions[entity];
      const [aheadX, aheadY] = last.positions[ahead];
      const gap = aheadY - REAR - (y + FRONT);
      assert.ok(
        Math.abs(x - aheadX) < 0.01 && gap <= 0.1 && gap > -0.55,
        `${entity} stands ${gap.toFixed(2)} m from ${ahead}'s rear, in its lane`,
      );
      assert.ok(samePlace(at(5.9), steps[0], entity), `${entity} waits until 6 s`);
    });
    assert.ok(samePlace(steps[0], last, 'hero'), 'the hero stands where it starts (it is the ego, driven in CARLA)');
    assert.ok(distance(last, 'vehicle_0', 'vehicle_1') < 6, 'the crashed cars stay together');
    // Police and ambulance arrive from the west behind vehicle_0, in its lane, without touching it or each other.
    const [crash, police, ambulance] = [at(17).positions.vehicle_0, at(17).positions.police, at(17).positions.ambulance];
    assert.ok(
      police[0] < crash[0] - 5 && police[0] > crash[0] - 40,
      `the police stops behind the crash (x ${police[0]} against ${crash[0]})`,
    );
    assert.ok(
      ambulance[0] < police[0] - 5 && ambulance[0] > police[0] - 40,
      `the ambulance stops behind the police (x ${ambulance[0]} against ${police[0]})`,
    );
    assert.ok(Math.abs(police[1] - crash[1]) < 0.1 && Math.abs(ambulance[1] - crash[1]) < 0.1, 'in vehicle_0 lane');
    // Then they leave the site (arrive-leave-site): the police first, each pulled out 3.5 m into the lane beside to pass
    // the crash, both past it by the end, the police ahead, and neither box ever over the crashed cars' (y below -0.62).
    const leaves = (entity: string) => steps.find((step) => step.time > 17 && !samePlace(step, at(17), entity))?.time ?? Infinity;
    assert.ok(leaves('police') < leaves('ambulance') && leaves('ambulance') < last.time, 'the police leaves, then the ambulance');
    const wreckEnd = Math.max(last.positions.vehicle_0[0] + FRONT, last.positions.vehicle_1[0] + 1);
    for (const entity of ['police', 'ambulance']) {
      const [x, y] = last.positions[entity];
      assert.ok(x - REAR > wreckEnd && Math.abs(y - (crash[1] + 3.5)) < 0.01, `${entity} ends past the crash, 3.5 m aside (${x}, ${y})`);
      for (const step of steps) {
        const [stepX, stepY] = step.positions[entity];
        assert.ok(stepX + FRONT < -1.5 || stepY - 1 > -0.62, `${entity} at ${step.time} s (${stepX}, ${stepY}) is over the crash`);
      }
    }
    assert.ok(last.positions.police[0] > last.positions.ambulance[0] + 10, 'the police ahead of the ambulance');
  });

  it("esmini follows the crossroads without a missing lane connection (library/roads/crossroads.xodr links its connecting roads' lanes)", function () {
    requireEsmini(this);
    // Before the connecting roads' lanes were linked, esmini warned "No connection from rid 101 lid -1 -> rid 2" in all
    // three (crossing-path also "rid 102 lid -1 -> rid 4") and moved the car to the closest lane.
    for (const scenario of [
      path.join(example, 'main.xosc'),
      path.join(repoRoot, 'library', 'examples', 'crossing-path.xosc'),
      path.join(repoRoot, 'library', 'examples', 'turn-across-path.xosc'),
    ]) {
      const run = runCli(['run', scenario, '--duration', '30']);
      const log = run.stdout + run.stderr;
      assert.equal(run.status, 0, log);
      assert.match(log, /esmini: 0 errors, \d+ warnings?; \d+\.\d+ s simulated/, log);
      assert.doesNotMatch(log, /No connection/, log);
    }
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
      'library/arrive-leave-site.xosc',
      'library/crossing-path.xosc',
      'library/lead-brake.xosc',
      'library/rear-end-collision.xosc',
    ]);
    for (const item of stats.shared) assert.equal(item.lines, fs.readFileSync(item.file, 'utf8').split('\n').length - 1, item.file);
  });
});
