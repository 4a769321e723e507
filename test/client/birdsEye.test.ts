import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  boxAt,
  drawEntities,
  drawRoads,
  drawTrajectories,
  fitTransform,
  laneAt,
  poseAt,
  roadShapes,
  sceneBounds,
  startBoxes,
  SvgPainter,
  toScreen,
} from '../../client/src/birdsEye/draw';
import type { RunTracks } from '../../client/src/birdsEye/messages';
import { keptRunName, loadRun, runTracks } from '../../client/src/birdsEye/runData';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { sampleNetwork } from '../../server/src/core/opendrive/sample';
import { collisionSentence } from '../../server/src/esmini/run';
import type { SceneResult } from '../../common/src/sceneProtocol';
import { temporaryWorkspace } from '../support/workspace';
import { STRAIGHT_ROAD } from '../support/roads';

function straightScene(): SceneResult {
  return {
    uri: 'file:///s.xosc',
    title: 's.xosc',
    sections: sampleNetwork(parseOpenDrive(STRAIGHT_ROAD)),
    entities: [
      {
        name: 'ego',
        kind: 'Vehicle',
        length: 4,
        width: 2,
        centerX: 1,
        x: 50,
        y: -1.75,
        hdg: 0,
        described: 'LanePosition',
        source: { uri: 'file:///s.xosc', line: 3, character: 4 },
      },
    ],
    events: [],
    problems: [],
  };
}

const RUN: RunTracks = {
  label: 'out.csv',
  times: [0, 1, 2],
  entities: [{ name: 'ego', length: 4, width: 2, centerX: 1, x: [50, 60, 70], y: [-1.75, -1.75, 1.75], hdg: [0, 0, Math.PI / 2] }],
  starts: {},
  notes: [],
};

describe("client: the bird's-eye view's drawing", () => {
  it('makes one polygon per lane between its borders, and finds the lane under a point', () => {
    const shapes = roadShapes(straightScene());
    assert.deepEqual(
      shapes.lanes.map((lane) => [lane.lane, lane.driving]),
      [
        [1, true],
        [-1, true],
        [-2, false],
      ],
    );
    assert.deepEqual(shapes.bounds, [0, -5.5, 200, 3.5]);
    assert.equal(laneAt(shapes, 100, 2)?.lane, 1);
    assert.equal(laneAt(shapes, 100, -2)?.lane, -1);
    assert.equal(laneAt(shapes, 100, -4)?.type, 'sidewalk');
    assert.equal(laneAt(shapes, 100, 10), undefined);
  });

  it('fits the picture in the screen with y up, and finds an entity under the pointer', () => {
    const scene = straightScene();
    const view = fitTransform(sceneBounds(roadShapes(scene), scene, undefined), 420, 120, 10);
    assert.equal(view.scale, 2);
    const [x, y] = toScreen(view, 0, 3.5);
    assert.ok(Math.abs(x - 10) < 1e-9 && y < toScreen(view, 0, -5.5)[1]);
    // Framing the entities: where they start, 40 m around, whatever the size of the network.
    assert.deepEqual(sceneBounds(roadShapes(scene), scene, undefined, true), [50 - 3 - 40, -1.75 - 3 - 40, 50 + 3 + 40, -1.75 + 3 + 40]);
    const boxes = startBoxes(scene.entities);
    assert.equal(boxAt(boxes, view, 52, -1.75)?.name, 'ego');
    assert.equal(boxAt(boxes, view, 40, -1.75), undefined);
  });

  it('interpolates a run between frames, heading the short way round', () => {
    const middle = poseAt(RUN, RUN.entities[0], 1.5);
    assert.deepEqual([middle.x, middle.y], [65, 0]);
    assert.ok(Math.abs(middle.hdg - Math.PI / 4) < 1e-12);
    assert.equal(poseAt(RUN, RUN.entities[0], 9).x, 70);
    assert.equal(poseAt(RUN, RUN.entities[0], -1).x, 50);
  });

  it('draws roads, trajectories and entities into an SVG document', () => {
    const scene = straightScene();
    const shapes = roadShapes(scene);
    const view = fitTransform(sceneBounds(shapes, scene, RUN), 800, 300);
    const svg = new SvgPainter(800, 300, '#000');
    assert.equal(drawRoads(svg, shapes, view, 800, 300), 3);
    drawTrajectories(svg, RUN, view, () => '#4fc3f7');
    drawEntities(svg, startBoxes(scene.entities), view, () => '#4fc3f7');
    const text = svg.toString();
    assert.match(text, /^<\?xml version="1.0" encoding="UTF-8"\?>\n<svg xmlns="http:\/\/www.w3.org\/2000\/svg" width="800" height="300"/);
    assert.equal((text.match(/<polygon /g) ?? []).length, 3 + 1);
    assert.match(text, /stroke="#4fc3f7" stroke-width="2"/);
    assert.match(text, /<text [^>]*>ego<\/text>/);
  });

  it('thins a long run for the view and finds the log beside the CSV', async () => {
    const rows = 20_000;
    const header =
      'esmini GIT REV: v3.6.0\nesmini GIT TAG: \nesmini GIT BRANCH: x\nesmini BUILD VERSION: x\nScenario File Name: s.xosc\nNumber of Vehicles: 1\nIndex [-], TimeStamp [s], #1 Entity_Name [-], #1 World_Position_X [m], #1 World_Position_Y [m], #1 World_Heading_Angle [rad], \n';
    const body = Array.from({ length: rows }, (_, i) => `${i}, ${(i * 0.01).toFixed(2)}, car, ${i * 0.1}, 0.123456, 0.5, `).join('\n');
    const folder = temporaryWorkspace({
      'out.csv': header + body + '\n',
      'out.log': '[1.230] [info] Go standbyState -> startTransition -> runningState\n',
    });
    try {
      const { tracks: run, log } = await loadRun({ csvPath: path.join(folder, 'out.csv') });
      assert.ok(run.times.length <= 6001 && run.times.length > 5000, `${run.times.length} frames`);
      assert.equal(run.times[run.times.length - 1], 199.99);
      assert.equal(run.entities[0].y[0], 0.12);
      // The starts are read from it by the language server, which knows the flattened elements (eventList.test.ts).
      assert.equal(log, '[1.230] [info] Go standbyState -> startTransition -> runningState\n');
      assert.deepEqual(run.starts, {});
      assert.match(run.notes.join(), /every 4th of 20000 steps/);
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
    const small = runTracks({ version: '', scenarioFile: '', times: Float64Array.from([0, 1]), entities: [], truncated: true }, 'x');
    assert.deepEqual(small.times, [0, 1]);
    assert.match(small.notes.join(), /end is left out/);
    // Run in esmini hands the collisions its run said: the view lists them with the run's other notes.
    const hit = runTracks({ version: '', scenarioFile: '', times: Float64Array.from([0, 1]), entities: [], truncated: false }, 'x', {}, [
      { entities: ['adversary', 'lead'], time: 4.45 },
    ]);
    assert.deepEqual(hit.notes, [
      'adversary and lead collide at t=4.45 s (their bounding boxes overlap; esmini drives on through each other)',
    ]);
    // Worded as the run's own message words it (esmini/run.ts), the names without their places.
    assert.equal(`; ${hit.notes[0]}`, collisionSentence([{ entities: ['adversary', 'lead'], time: 4.45 }]));
  });

  it("names a batch's kept run as the Variations view lists it (#I of RESULTS), any other run by its file", async () => {
    const csv =
      'esmini GIT REV: v3.6.0\nesmini GIT TAG: \nesmini GIT BRANCH: x\nesmini BUILD VERSION: x\nScenario File Name: s.xosc\nNumber of Vehicles: 1\n' +
      'Index [-], TimeStamp [s], #1 Entity_Name [-], #1 World_Position_X [m], #1 World_Position_Y [m], #1 World_Heading_Angle [rad], \n0, 0.00, car, 0, 0, 0, \n';
    ('Index [-], TimeStamp [s], #1 Entity_Name [-], #1 World_Position_X [m], #1 World_Position_Y [m], #1 World_Heading_Angle [rad], \n0, 0.00, car, 0, 0, 0, \n');
    const folder = temporaryWorkspace({ 'cut-in.results/runs/3/trajectories.csv': csv, 'elsewhere/trajectories.csv': csv });
    try {
      const kept = await loadRun({ csvPath: path.join(folder, 'cut-in.results', 'runs', '3', 'trajectories.csv') });
      assert.equal(kept.tracks.label, '#3 of cut-in.results');
      assert.equal(keptRunName(path.join(folder, 'cut-in.results', 'runs', '3', 'scenario.xosc')), '#3 of cut-in.results');
      assert.equal((await loadRun({ csvPath: path.join(folder, 'elsewhere', 'trajectories.csv') })).tracks.label, 'trajectories.csv');
      assert.equal(keptRunName(path.join(folder, 'runs', 'latest', 'trajectories.csv')), undefined);
      // A name given (Run in esmini's) wins.
      const named = await loadRun({ csvPath: path.join(folder, 'elsewhere', 'trajectories.csv'), label: 'esmini run of x.xosc, 10:00:00' });
      assert.equal(named.tracks.label, 'esmini run of x.xosc, 10:00:00');
      // Cut at the run's limit: esmini logs the step after it too.
      fs.appendFileSync(path.join(folder, 'elsewhere', 'trajectories.csv'), '1, 0.05, car, 1, 0, 0, \n2, 0.10, car, 2, 0, 0, \n');
      const cut = await loadRun({ csvPath: path.join(folder, 'elsewhere', 'trajectories.csv'), until: 0.05 });
      assert.deepEqual(cut.tracks.times, [0, 0.05]);
      assert.deepEqual(cut.tracks.entities[0].x, [0, 1]);
      assert.deepEqual((await loadRun({ csvPath: path.join(folder, 'elsewhere', 'trajectories.csv') })).tracks.times, [0, 0.05, 0.1]);
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });

  it("names the road file the run loaded, from esmini's log, so that the view can tell a run on another road", async () => {
    const csv =
      'esmini GIT REV: v3.6.0\nesmini GIT TAG: \nesmini GIT BRANCH: x\nesmini BUILD VERSION: x\nScenario File Name: s.xosc\nNumber of Vehicles: 1\nIndex [-], TimeStamp [s], #1 Entity_Name [-], #1 World_Position_X [m], #1 World_Position_Y [m], #1 World_Heading_Angle [rad], \n0, 0.00, car, 0, 0, 0, \n';
    const folder = temporaryWorkspace({ 'out.csv': csv });
    try {
      const { tracks: run } = await loadRun({
        csvPath: path.join(folder, 'out.csv'),
        logText: '[] [info] Loaded OpenDRIVE: /roads/e6mini.xodr\n',
      });
      assert.equal(run.roadFile, '/roads/e6mini.xodr');
      assert.equal((await loadRun({ csvPath: path.join(folder, 'out.csv'), logText: '' })).tracks.roadFile, undefined);
      // Run in esmini on a road packed in the .mosc names the package entry the picture draws, not the copy in its run folder.
      const packed = await loadRun({
        csvPath: path.join(folder, 'out.csv'),
        logText: '[] [info] Loaded OpenDRIVE: scenario.files/e6mini.xodr\n',
        roadFile: '/w/pkg.mosc/e6mini.xodr',
      });
      assert.equal(packed.tracks.roadFile, '/w/pkg.mosc/e6mini.xodr');
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});
