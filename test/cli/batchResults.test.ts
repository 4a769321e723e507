import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import type { EntityTrack, EsminiRun } from '../../common/src/esminiCsv';
import { polygonGap, trajectoryMetrics } from '../../server/src/batch/metrics';
import { collisionsIn } from '../../server/src/esmini/log';
import { BatchIdentity, BatchRow, csvInIndexOrder, csvLine, ResultsError, ResultsFolder } from '../../server/src/batch/results';
import { temporaryFolder } from '../support/temporaryDirectory';

function track(name: string, xs: number[], speed = 0): EntityTrack {
  return {
    name,
    length: 4,
    width: 2,
    centerX: 0,
    x: Float64Array.from(xs),
    y: new Float64Array(xs.length),
    hdg: new Float64Array(xs.length),
    speed: new Float64Array(xs.length).fill(speed),
  };
}

function run(times: number[], entities: EntityTrack[]): EsminiRun {
  return { version: 'test', scenarioFile: 's.xosc', times: Float64Array.from(times), entities, truncated: false };
}

const IDENTITY: BatchIdentity = {
  distribution: '/d.xosc',
  distributionSha256: 'a',
  scenarioSha256: 'b',
  sample: null,
  seed: 0,
  duration: 5,
  esminiSeed: 1,
};

function row(index: string, parameters: Record<string, string>): BatchRow {
  return {
    index,
    status: 'ok',
    collision: false,
    min_distance_m: 1.23456,
    min_ttc_s: null,
    end_time_s: 3,
    parameters,
    ego: 'Ego',
    collisions: [],
    message: 'm',
    messages: [],
  };
}

describe('batch: trajectory metrics and results files', () => {
  it('gaps between bounding boxes: apart, touching, overlapping, turned', () => {
    const box = (cx: number, cy: number, angle = 0): [number, number][] => {
      const corners: [number, number][] = [
        [2, 1],
        [-2, 1],
        [-2, -1],
        [2, -1],
      ];
      return corners.map(([x, y]) => [cx + x * Math.cos(angle) - y * Math.sin(angle), cy + x * Math.sin(angle) + y * Math.cos(angle)]);
    };
    assert.equal(polygonGap(box(0, 0), box(10, 0)), 6);
    assert.equal(polygonGap(box(0, 0), box(4, 0)), 0);
    assert.equal(polygonGap(box(0, 0), box(3, 1)), 0);
    assert.ok(
      Math.abs(polygonGap(box(0, 0), box(0, 5, Math.PI / 2)) - 2) < 1e-9,
      'a box turned upright 5 m to the side: 1 m half width, 2 m half length',
    );
  });

  it('the ego against every other entity: the smallest gap, the smallest gap over closing speed, no TTC when nothing closes', () => {
    // Ego at 10 m/s behind a standing car 24 m ahead (20 m gap), a car alongside keeping pace.
    const times = [0, 0.5, 1];
    const metrics = trajectoryMetrics(
      run(times, [track('Other', [24, 24, 24]), track('Ego', [0, 5, 10], 10), track('Pace', [-10, -5, 0], 10)]),
      5,
    );
    assert.equal(metrics.ego, 'Ego');
    assert.equal(metrics.minDistance, 6);
    assert.ok(metrics.minTtc !== undefined && Math.abs(metrics.minTtc - 1) < 1e-9, `${metrics.minTtc}`);
    const apart = trajectoryMetrics(run(times, [track('First', [0, 5, 10], 10), track('Second', [20, 25, 30], 10)]), 5);
    assert.equal(apart.ego, 'First', 'without an Ego, the first entity');
    assert.equal(apart.minTtc, undefined);
    assert.equal(
      trajectoryMetrics(run(times, [track('First', [0, 5, 10], 10), track('Second', [20, 25, 30], 10)]), 0.4).minDistance,
      16,
      'rows past the duration are left out',
    );
  });

  it("reads esmini's collision warnings, not their end", () => {
    const messages = [
      { level: 'warn' as const, time: 3, text: 'Collision between Ego and Lead', logLine: 1 },
      { level: 'warn' as const, time: 4, text: 'Collision between Ego and Lead dissolved', logLine: 2 },
    ];
    assert.deepEqual(collisionsIn(messages), [{ entities: ['Ego', 'Lead'], time: 3 }]);
  });

  it('CSV rows quote what must be quoted; a folder with other columns or another batch is refused untouched', async () => {
    assert.equal(
      csvLine(row('3', { Car: 'a,b', Name: 'say "hi"', Speed: '1' }), ['Car', 'Name', 'Speed']),
      '3,ok,false,1.235,,3.000,"a,b","say ""hi""",1,\n',
    );
    const folder = temporaryFolder('m2s-results-');
    try {
      const results = await ResultsFolder.open(folder, ['Speed'], IDENTITY);
      await results.append(row('0', { Speed: '1' }));
      await results.append(row('0', { Speed: '1' }));
      await results.finish();
      const csv = fs.readFileSync(path.join(folder, 'results.csv'), 'utf8');
      assert.equal(csv, 'index,status,collision,min_distance_m,min_ttc_s,end_time_s,Speed,reason\n0,ok,false,1.235,,3.000,1,\n');
      await assert.rejects(
        ResultsFolder.open(folder, ['Gap'], IDENTITY),
        (error: Error) => error instanceof ResultsError && /holds another batch's results \(its columns/.test(error.message),
      );
      await assert.rejects(ResultsFolder.open(folder, ['Speed'], { ...IDENTITY, duration: 9 }), /differs in duration/);
      assert.equal(fs.readFileSync(path.join(folder, 'results.csv'), 'utf8'), csv);
      const again = await ResultsFolder.open(folder, ['Speed'], IDENTITY);
      assert.deepEqual([...again.done], ['0']);
      await again.finish();
      const json = JSON.parse(fs.readFileSync(path.join(folder, 'results.json'), 'utf8')) as { rows: BatchRow[] };
      assert.deepEqual(
        json.rows.map((each) => each.index),
        ['0'],
      );
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });

  it('rows appended as runs end are in index order once the batch finishes, each kept as written (issue 27)', async () => {
    const folder = temporaryFolder('m2s-results-order-');
    try {
      const results = await ResultsFolder.open(folder, ['Name'], IDENTITY);
      for (const [index, name] of [
        ['10', 'ten'],
        ['2', 'two\nlines, quoted'],
        ['0', 'zero'],
      ])
        await results.append(row(index, { Name: name }));
      await results.finish();
      const csv = fs.readFileSync(path.join(folder, 'results.csv'), 'utf8');
      assert.equal(
        csv,
        'index,status,collision,min_distance_m,min_ttc_s,end_time_s,Name,reason\n' +
          '0,ok,false,1.235,,3.000,zero,\n2,ok,false,1.235,,3.000,"two\nlines, quoted",\n10,ok,false,1.235,,3.000,ten,\n',
      );
      const json = JSON.parse(fs.readFileSync(path.join(folder, 'results.json'), 'utf8')) as { rows: BatchRow[] };
      assert.deepEqual(
        json.rows.map((each) => each.index),
        ['0', '2', '10'],
      );
      assert.equal(csvInIndexOrder(csv), csv, 'in order already: the same text');
      assert.equal(csvInIndexOrder('h\n"5",x\n4,y\n'), 'h\n4,y\n"5",x\n');
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});
