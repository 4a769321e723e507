import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { laneBorderPoint, laneById, parseOpenDrive } from '../../server/src/core/opendrive/road';
import { esminiXodrDir, requireEsminiProgram } from '../support/esminiBinaries';
import { temporaryFolder } from '../support/temporaryDirectory';

interface OdrplotLane {
  road: string;
  section: number;
  lane: number;
  driving: boolean;
  points: { x: number; y: number }[];
}

/** odrplot's output: a `lane, road, section, lane, driving|no-driving` line, then `x, y, z, h` lines. */
function parseOdrplot(text: string): OdrplotLane[] {
  const lanes: OdrplotLane[] = [];
  for (const line of text.split('\n')) {
    if (line.startsWith('lane,')) {
      const [, road, section, lane, kind] = line.split(',').map((part) => part.trim());
      lanes.push({ road, section: Number(section), lane: Number(lane), driving: kind === 'driving', points: [] });
    } else if (line.trim()) {
      const [x, y] = line.split(',').map(Number);
      lanes[lanes.length - 1].points.push({ x, y });
    }
  }
  return lanes;
}

const STEP = 1.0;
// esmini's SMALL_NUMBER (CommonMini.hpp): odrplot's last point stops this short of the section's end.
const SMALL_NUMBER = 1e-10;
const TOLERANCE = 0.01;

describe('core: OpenDRIVE lane borders against esmini odrplot', function () {
  this.timeout(120_000);
  let odrplot: string;
  let outDir: string;
  before(function () {
    odrplot = requireEsminiProgram(this, 'odrplot');
    outDir = temporaryFolder('m2s-odrplot-');
  });
  after(() => outDir && fs.rmSync(outDir, { recursive: true, force: true }));

  const files = fs.existsSync(esminiXodrDir)
    ? fs
        .readdirSync(esminiXodrDir)
        .filter((name) => name.endsWith('.xodr'))
        .sort()
    : [];
  for (const file of files) {
    it(`${file}: every lane border point within 1 cm`, () => {
      const input = path.join(esminiXodrDir, file);
      const output = path.join(outDir, `${file}.csv`);
      const run = spawnSync(odrplot, [input, output, String(STEP)], { cwd: outDir, encoding: 'utf8' });
      assert.equal(run.status, 0, `odrplot failed: ${run.stdout}${run.stderr}`);
      const expected = parseOdrplot(fs.readFileSync(output, 'utf8'));
      const network = parseOpenDrive(fs.readFileSync(input, 'utf8'));
      assert.deepEqual(network.problems, []);
      assert.ok(expected.length > 0);
      let compared = 0;
      let worst = 0;
      for (const lane of expected) {
        const road = network.byId.get(lane.road);
        assert.ok(road, `road ${lane.road} missing`);
        const section = road.laneSections[lane.section];
        assert.ok(section && laneById(section, lane.lane), `road ${lane.road} section ${lane.section} lane ${lane.lane} missing`);
        const sEnd = section.s + section.length;
        const steps = Math.max(1, Math.trunc(section.length / STEP));
        assert.equal(lane.points.length, steps + 1, `road ${lane.road} section ${lane.section} lane ${lane.lane}: point count`);
        lane.points.forEach((point, k) => {
          const s = Math.min(sEnd - SMALL_NUMBER, section.s + (k * section.length) / steps);
          const ours = laneBorderPoint(road, lane.section, lane.lane, s);
          const distance = Math.hypot(ours.x - point.x, ours.y - point.y);
          worst = Math.max(worst, distance);
          assert.ok(
            distance <= TOLERANCE,
            `road ${lane.road} section ${lane.section} lane ${lane.lane} s=${s.toFixed(3)}: (${ours.x.toFixed(4)}, ${ours.y.toFixed(4)}) vs esmini (${point.x}, ${point.y}), ${(distance * 100).toFixed(2)} cm apart`,
          );
          compared++;
        });
      }
      console.log(`      ${compared} points, largest distance ${(worst * 1000).toFixed(2)} mm`);
    });
  }
});
