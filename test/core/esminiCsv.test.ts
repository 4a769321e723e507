import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { anyEntityMoved, parseEsminiCsv } from '../../common/src/esminiCsv';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { scenarioScene } from '../../server/src/core/scene';
import { parseXml } from '../../server/src/core/xml';
import { repoRoot } from '../support/paths';
import { esminiXodrDir, requireEsminiProgram } from '../support/esminiBinaries';
import { temporaryFolder } from '../support/temporaryDirectory';
import { repeatableRunArgs } from '../support/esmini';

const fixture = path.join(repoRoot, 'test', 'fixtures', 'birdsEye', 'cut_in.xosc');

describe('core: esmini CSV log', function () {
  this.timeout(60_000);

  it('tells a run in which no entity moved from one in which one did, reading no further than the first move', () => {
    const columns =
      'Index [-], TimeStamp [s], #1 Entity_Name [-], #1 World_Position_X [m], #1 World_Position_Y [m], #2 Entity_Name [-], #2 World_Position_X [m], #2 World_Position_Y [m]';
    const row = (index: number, x1: number, y2: number) => `${index}, ${index * 0.05}, Ego, ${x1}, -1.5, Car, 20, ${y2}`;
    const header = ['esmini GIT REV: v3.6.0', '', '', '', 'Scenario File Name: s.xosc', '', columns];
    assert.equal(anyEntityMoved([...header, row(0, 10, 1.5), row(1, 10, 1.5), row(2, 10, 1.5)]), false);
    // The second entity's y changes at the last row; a row cut short at the end is no move.
    assert.equal(anyEntityMoved([...header, row(0, 10, 1.5), row(1, 10, 1.5), row(2, 10, 1.6)]), true);
    assert.equal(anyEntityMoved([...header, row(0, 10, 1.5), row(1, 10, 1.5), '2, 0.1, Ego, 11']), false);
    // Nothing to tell from: no column line, or a single row.
    assert.equal(anyEntityMoved(['esmini GIT REV: v3.6.0', row(0, 10, 1.5)]), undefined);
    assert.equal(anyEntityMoved([...header, row(0, 10, 1.5)]), undefined);
    function* stopsAtTheMove(): Generator<string> {
      yield* [...header, row(0, 10, 1.5), row(1, 10.5, 1.5)];
      throw new Error('read past the first move');
    }
    assert.equal(anyEntityMoved(stopsAtTheMove()), true);
  });

  it('reads rows per step and the columns of each entity; a row cut short at the end is dropped', () => {
    const header = [
      'esmini GIT REV: v3.6.0',
      'esmini GIT TAG: ',
      'esmini GIT BRANCH: master',
      'esmini BUILD VERSION: N/A',
      'Scenario File Name: s.xosc',
      'Number of Vehicles: 1',
    ];
    const columns =
      'Index [-], TimeStamp [s], #1 Entity_Name [-], #1 Current_Speed [m/s], #1 bb_x [m], #1 bb_length [m], #1 bb_width [m], #1 World_Position_X [m], #1 World_Position_Y [m], #1 World_Heading_Angle [rad], ';
    const text = [
      ...header,
      columns,
      '0, 0.000000, Ego, 10, 1.4, 5, 2, 1.5, 2.5, 0.1, ',
      '1, 0.050000, Ego, 10, 1.4, 5, 2, 2.0, 2.5, 0.1, ',
      '2, 0.1000',
    ].join('\n');
    const run = parseEsminiCsv(text);
    assert.equal(run.version, 'v3.6.0');
    assert.equal(run.scenarioFile, 's.xosc');
    assert.deepEqual([...run.times], [0, 0.05]);
    assert.equal(run.entities[0].name, 'Ego');
    assert.deepEqual([...run.entities[0].x], [1.5, 2]);
    assert.deepEqual([run.entities[0].length, run.entities[0].width, run.entities[0].centerX], [5, 2, 1.4]);
    assert.equal(parseEsminiCsv(text, { maxRows: 1 }).truncated, true);
    assert.throws(() => parseEsminiCsv('x,y\n1,2\n'), /line 1: not an esmini CSV log/);
    assert.throws(
      () => parseEsminiCsv([...header, columns, '0, 0, Ego', '1, 0.05, Ego, 1, 1, 1, 1, 1, 1, 1, ', '', ''].join('\n')),
      /line 8: expected 10 fields, found 3/,
    );
  });

  it('on a real esmini run: every entity, every step, and start positions matching the view within 1 cm', function () {
    const esmini = requireEsminiProgram(this, 'esmini');
    const folder = temporaryFolder('m2s-esmini-csv-');
    try {
      const csv = path.join(folder, 'out.csv');
      const result = spawnSync(esmini, repeatableRunArgs(fixture, csv, '--path', esminiXodrDir), {
        cwd: folder,
        encoding: 'utf8',
        timeout: 30_000,
      });
      assert.equal(result.status, 0, result.stdout + result.stderr);
      const run = parseEsminiCsv(fs.readFileSync(csv, 'utf8'));
      assert.match(run.version, /^v3\./);
      assert.deepEqual(
        run.entities.map((entity) => entity.name),
        ['Ego', 'Adversary'],
      );
      // The StopTrigger fires past 12 s; one row per 0.05 s step from 0.
      assert.ok(run.times.length >= 240 && run.times.length < 260, `${run.times.length} rows`);
      for (let i = 1; i < run.times.length; i++) assert.ok(Math.abs(run.times[i] - run.times[i - 1] - 0.05) < 1e-6);
      const adversary = run.entities[1];
      assert.ok(adversary.speed[0] === 22 && adversary.speed[adversary.speed.length - 1] < 11, 'the adversary brakes to 10 m/s');
      // The view's start positions against esmini's first row.
      const network = parseOpenDrive(fs.readFileSync(path.join(esminiXodrDir, 'e6mini.xodr'), 'utf8'));
      const scene = scenarioScene(parseXml(fs.readFileSync(fixture, 'utf8')), network);
      for (const [index, entity] of scene.entities.entries()) {
        const track = run.entities[index];
        const distance = Math.hypot((entity.x ?? NaN) - track.x[0], (entity.y ?? NaN) - track.y[0]);
        assert.ok(distance < 0.01, `${entity.name}: (${entity.x}, ${entity.y}) vs esmini (${track.x[0]}, ${track.y[0]})`);
        assert.ok(Math.abs(Math.cos(entity.hdg! - track.hdg[0]) - 1) < 1e-4, `${entity.name} heading ${entity.hdg} vs ${track.hdg[0]}`);
      }
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});
