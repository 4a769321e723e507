import * as assert from 'node:assert/strict';
import {
  boxGap,
  centredOn,
  entitiesBounds,
  exportLayout,
  parseResolution,
  runSeries,
  scaleBar,
  tooltipPlace,
  wheelNotches,
  zoomAbout,
  ZOOM_STEP,
} from '../../client/src/birdsEye/analysis';
import {
  drawEntities,
  drawExportOverlay,
  fitTransform,
  type PlacedBox,
  roadShapes,
  sceneBounds,
  shiftedPainter,
  SvgPainter,
  toScreen,
  toWorld,
} from '../../client/src/birdsEye/draw';
import { type Bounds, overlaps, placeLabels } from '../../client/src/birdsEye/labels';
import type { RunTracks } from '../../client/src/birdsEye/messages';
import { drawPlots, plotRange, plotSpecs, TTC_CEILING_S } from '../../client/src/birdsEye/plots';
import { runTracks } from '../../client/src/birdsEye/runData';

const car = (name: string, x: number, y: number, hdg = 0): PlacedBox => ({ name, x, y, hdg, length: 4.5, width: 1.8, centerX: 1.4 });

/** Ego at 20 m/s behind Lead at 10 m/s in the same lane (30 m between reference points), for 4 s; Far in another lane far ahead. */
function followingRun(): RunTracks {
  const times = Array.from({ length: 81 }, (_, i) => i * 0.05);
  const track = (name: string, x0: number, y: number, speed: number) => ({
    name,
    length: 4.5,
    width: 1.8,
    centerX: 1.4,
    x: times.map((t) => x0 + speed * t),
    y: times.map(() => y),
    hdg: times.map(() => 0),
    speed: times.map(() => speed),
  });
  return {
    label: 'following.csv',
    times,
    entities: [track('Ego', 0, 0, 20), track('Lead', 30, 0, 10), track('Far', 500, 3.5, 30)],
    starts: {},
    notes: [],
  };
}

describe("client: the bird's-eye view as a tool for analysing a run", () => {
  it('*Entities* frames the entities where they are now, not their whole trajectories', () => {
    const run: RunTracks = {
      label: 'r',
      times: [0, 100],
      entities: [
        { name: 'A', length: 4, width: 2, centerX: 0, x: [0, 3000], y: [0, 0], hdg: [0, 0] },
        { name: 'B', length: 4, width: 2, centerX: 0, x: [20, 3020], y: [3.5, 3.5], hdg: [0, 0] },
      ],
      starts: {},
      notes: [],
    };
    const whole = sceneBounds({ lanes: [], borders: [], bounds: undefined }, undefined, run, true);
    assert.ok(whole[2] - whole[0] > 3000, 'the trajectories span 3 km');
    const now = entitiesBounds([car('A', 1500, 0), car('B', 1520, 3.5)])!;
    assert.ok(now[0] < 1500 - 2 && now[2] > 1520 + 4, `${now}`);
    assert.ok(now[2] - now[0] <= 80, `frames ${now[2] - now[0]} m across`);
    // A lone car is not blown up to lane level: at least 80 m across.
    const lone = entitiesBounds([car('A', 10, 10)])!;
    assert.ok(Math.abs(lone[2] - lone[0] - 80) < 1e-9 && Math.abs(lone[3] - lone[1] - 80) < 1e-9);
    assert.equal(entitiesBounds([]), undefined);
    assert.equal(entitiesBounds([car('A', NaN, NaN)]), undefined);
  });

  it('the camera that follows keeps the entity in the middle at the same scale', () => {
    const view = { scale: 4, left: 0, top: 0 };
    const followed = centredOn(view, 1234, -56, 600, 400);
    assert.deepEqual(toScreen(followed, 1234, -56), [300, 200]);
    assert.equal(followed.scale, 4);
  });

  it('zooms by the same factor at every wheel notch, about the pointer', () => {
    let view = fitTransform([0, 0, 2000, 1000], 600, 400);
    const start = view.scale;
    const pointer: [number, number] = [420, 130];
    const under = toWorld(view, ...pointer);
    const scales = [view.scale];
    for (let notch = 0; notch < 8; notch++) {
      view = zoomAbout(view, wheelNotches(-100, 0), ...pointer);
      scales.push(view.scale);
    }
    for (let i = 1; i < scales.length; i++)
      assert.ok(Math.abs(scales[i] / scales[i - 1] - ZOOM_STEP) < 1e-12, `notch ${i}: ${scales[i] / scales[i - 1]}`);
    // Eight notches: 3.06x, not from the network to lane level.
    assert.ok(Math.abs(view.scale / start - ZOOM_STEP ** 8) < 1e-9);
    const after = toWorld(view, ...pointer);
    assert.ok(Math.abs(after[0] - under[0]) < 1e-9 && Math.abs(after[1] - under[1]) < 1e-9, 'the point under the pointer stays');
    assert.equal(wheelNotches(3, 1), 1);
    assert.equal(wheelNotches(-1, 2), -1);
    assert.equal(wheelNotches(50, 0), 0.5);
    assert.ok(Math.abs(zoomAbout(view, 1, 0, 0).scale - view.scale / ZOOM_STEP) < 1e-12);
    assert.equal(zoomAbout({ scale: 499, left: 0, top: 0 }, -10, 0, 0).scale, 500);
  });

  it('places labels so that no two overlap, each beside its entity or led to it, the chosen one first', () => {
    // Six cars within a few pixels of each other, as at network scale: "A3 Eg A2 A5 A1 A4" before.
    const names = ['Ego', 'A1', 'A2', 'A3', 'A4', 'A5'];
    const anchors: Bounds[] = names.map((_, i) => [300 + i * 2, 200 + (i % 2) * 3, 305 + i * 2, 203 + (i % 2) * 3]);
    const labels = placeLabels(
      names.map((text, i) => ({ text, anchor: anchors[i], width: 30, height: 15, priority: text === 'A4' ? -1 : i })),
      anchors,
      600,
      400,
    );
    assert.equal(labels.length, 6);
    assert.equal(labels[0].text, 'A4', 'the chosen entity is labelled first');
    for (let i = 0; i < labels.length; i++) {
      const box = labels[i].box;
      assert.ok(box[0] >= 0 && box[1] >= 0 && box[2] <= 600 && box[3] <= 400, 'on screen');
      for (const anchor of anchors) assert.ok(!overlaps(box, anchor), `${labels[i].text} covers a car`);
      for (let j = i + 1; j < labels.length; j++) assert.ok(!overlaps(box, labels[j].box), `${labels[i].text} overlaps ${labels[j].text}`);
    }
    assert.ok(
      labels.some((label) => label.leader),
      'labels moved away have a leader line',
    );
    // No room at all: the lower-priority labels are left out rather than drawn over each other.
    const crowded = placeLabels(
      names.map((text, i) => ({ text, anchor: [40, 20, 42, 22] as Bounds, width: 30, height: 15, priority: i })),
      [],
      84,
      44,
    );
    assert.ok(crowded.length < 6 && crowded.length > 0);
    assert.equal(crowded[0].text, 'Ego');
    for (let i = 0; i < crowded.length; i++)
      for (let j = i + 1; j < crowded.length; j++) assert.ok(!overlaps(crowded[i].box, crowded[j].box));
  });

  it('draws cars at true size with a minimum on screen, their heading, and labels through the placement', () => {
    const svg = new SvgPainter(600, 400, '#000');
    // At network scale (0.2 px/m) a car would be 0.9 px long.
    const view = { scale: 0.2, left: 0, top: 1000 };
    const labels = drawEntities(
      svg,
      names6().map((name, i) => car(name, 1000 + i * 3, 0)),
      view,
      () => '#fff',
      { width: 600, height: 400, chosen: 'Eg' },
    );
    const text = svg.toString();
    const polygon = /<polygon points="([^"]+)"/
      .exec(text)![1]
      .split(' ')
      .map((pair) => pair.split(',').map(Number));
    const xs = polygon.map(([x]) => x);
    const ys = polygon.map(([, y]) => y);
    assert.ok(Math.max(...ys) - Math.min(...ys) >= 6.9 && Math.max(...xs) - Math.min(...xs) >= 10, 'at least 7 px wide');
    // The heading chevron: one polyline of three points per car besides its outline.
    assert.equal((text.match(/<polyline points="[^ "]+ [^ "]+ [^ "]+" fill="none" stroke="#1b1b1b"/g) ?? []).length, 6);
    for (let i = 0; i < labels.length; i++) for (let j = i + 1; j < labels.length; j++) assert.ok(!overlaps(labels[i].box, labels[j].box));
    assert.equal(labels[0].text, 'Eg');
    // At lane level the true size is drawn: 4.5 m at 10 px/m.
    const near = new SvgPainter(600, 400, '#000');
    drawEntities(near, [car('A', 10, 0)], { scale: 10, left: 0, top: 10 }, () => '#fff');
    const corners = /<polygon points="([^"]+)"/
      .exec(near.toString())![1]
      .split(' ')
      .map((pair) => Number(pair.split(',')[0]));
    assert.equal(Math.max(...corners) - Math.min(...corners), 45);
  });

  it('keeps the tooltip inside the panel', () => {
    assert.deepEqual(tooltipPlace(100, 100, 200, 20, 626, 688), [114, 114]);
    // Near the right edge: to the left of the pointer, whole.
    const [x, y] = tooltipPlace(600, 100, 200, 20, 626, 688);
    assert.ok(x + 200 <= 626 && x >= 0 && y === 114);
    const [, bottom] = tooltipPlace(100, 680, 200, 20, 626, 688);
    assert.ok(bottom + 20 <= 688);
    // Wider than the panel: from its left edge.
    assert.deepEqual(tooltipPlace(300, 10, 800, 20, 626, 688), [0, 24]);
  });

  it('computes speed, gap and time to collision of the chosen entity against the others', () => {
    const run = followingRun();
    const series = runSeries(run, 'Ego')!;
    assert.deepEqual(
      series.others.map((other) => other.name),
      ['Lead', 'Far'],
    );
    assert.equal(series.speed[10], 20);
    const lead = series.others[0];
    // Bumper to bumper: 30 m between reference points minus a car length (4.5 m, centred 1.4 m ahead on both).
    assert.ok(Math.abs(lead.gap[0] - 25.5) < 1e-9, `${lead.gap[0]}`);
    assert.ok(Math.abs(lead.gap[40] - (25.5 - 10 * 2)) < 1e-9, `${lead.gap[40]}`);
    // Closing at 10 m/s: TTC = gap / 10.
    for (const i of [1, 20, 40, 50]) assert.ok(Math.abs(lead.ttc[i] - lead.gap[i] / 10) < 1e-6, `TTC ${lead.ttc[i]} at frame ${i}`);
    // Far drives away: no TTC.
    assert.ok(series.others[1].ttc.every((value) => Number.isNaN(value)));
    // While the boxes overlap the gap is 0.
    assert.equal(lead.gap[55], 0);
    assert.equal(runSeries(run, 'Nobody'), undefined);
    // Without esmini's speed column the speed comes from the positions.
    const noSpeed: RunTracks = { ...run, entities: run.entities.map(({ speed: _speed, ...rest }) => rest) };
    assert.ok(Math.abs(runSeries(noSpeed, 'Lead')!.speed[30] - 10) < 1e-9);
    assert.equal(boxGap(car('A', 0, 0), car('B', 0, 0)), 0);
    assert.ok(Math.abs(boxGap(car('A', 0, 0), car('B', 0, 5)) - 3.2) < 1e-9);
  });

  it("carries esmini's speed column into the run the view draws", () => {
    const times = Float64Array.from([0, 1]);
    const track = {
      name: 'c',
      length: 4,
      width: 2,
      centerX: 1,
      x: Float64Array.from([0, 1]),
      y: Float64Array.from([0, 0]),
      hdg: Float64Array.from([0, 0]),
    };
    assert.deepEqual(
      runTracks(
        { version: '', scenarioFile: '', times, truncated: false, entities: [{ ...track, speed: Float64Array.from([1.234, 2]) }] },
        'x',
      ).entities[0].speed,
      [1.23, 2],
    );
    assert.equal(
      runTracks(
        { version: '', scenarioFile: '', times, truncated: false, entities: [{ ...track, speed: Float64Array.from([NaN, NaN]) }] },
        'x',
      ).entities[0].speed,
      undefined,
    );
  });

  it('plots the series as small multiples with the time marked', () => {
    const series = runSeries(followingRun(), 'Ego')!;
    const specs = plotSpecs(series);
    assert.deepEqual(
      specs.map((spec) => spec.unit),
      ['m/s', 'm', 's'],
    );
    // Scaled to the data: the constant 20 m/s sits mid-axis, not at the top of 0..20.
    assert.deepEqual([specs[0].low, specs[0].high], [19, 21]);
    assert.ok(specs[2].high <= TTC_CEILING_S && specs[2].low <= 1.5, 'the TTC axis holds the threshold');
    const svg = new SvgPainter(900, 150, '#000');
    const areas = drawPlots(svg, specs, series.times, 2, 0, 0, 900, 150, () => '#4fc3f7');
    assert.equal(areas.length, 3);
    for (let i = 1; i < areas.length; i++) assert.ok(areas[i].left > areas[i - 1].right, 'side by side');
    const text = svg.toString();
    assert.match(text, /speed of Ego \(m\/s\)/);
    assert.match(text, /time to collision with Ego \(s\)/);
    assert.match(text, /fill="#ef5350"[^>]*>1\.5 s</, 'the threshold line is labelled with its value');
    // The time marked: a vertical white line in the middle of each plot (2 s of 4 s).
    const marks = [...text.matchAll(/<polyline points="([\d.]+),[\d.]+ ([\d.]+),[\d.]+" fill="none" stroke="#ffffff"/g)];
    assert.equal(marks.length, 3);
    for (const [index, mark] of marks.entries()) assert.ok(Math.abs(Number(mark[1]) - (areas[index].left + areas[index].right) / 2) < 0.1);
  });

  it('scales each plot to its data with a margin, 0 kept for values that never go below it', () => {
    assert.deepEqual(plotRange([[3, 4, 6]], [0, 10]), [2, 7], 'a gap of a few metres fills the plot');
    assert.deepEqual(plotRange([[3, 6, 500]], [0, 10], 200), [2, 7], 'values past the ceiling do not stretch it');
    assert.deepEqual(plotRange([[0.2, 0.4]], [0, 10]), [0, 1], 'never below 0 when no value is');
    assert.deepEqual(plotRange([[-2, 2]], [0, 10]), [-4, 4]);
    assert.deepEqual(plotRange([[NaN]], [0, 10]), [0, 10], 'no value: the fallback');
    assert.deepEqual(plotRange([[5, 8]], [0, 10], 10, 1.5), [0, 10], 'the threshold is included');
  });

  it('lays out an export at a chosen resolution with legend, time and scale bar', () => {
    assert.deepEqual(scaleBar(2, 240), { metres: 100, pixels: 200 });
    assert.deepEqual(scaleBar(10, 240), { metres: 20, pixels: 200 });
    assert.deepEqual(scaleBar(0.1, 240), { metres: 2000, pixels: 200 });
    const shown = { scale: 3, left: 100, top: 50 };
    const layout = exportLayout(1920, 1080, shown, 626, 688, ['Ego', 'A1', 'A2', 'Ego (2)'], 't = 3.00 s of 20.00 s');
    assert.equal(layout.map.width, 1920);
    assert.ok(layout.map.height < 1080 && layout.map.height > 950);
    // Same centre, and at least what the panel showed.
    const centre = toWorld(shown, 313, 344);
    const mapped = toScreen(layout.view, ...centre);
    assert.ok(Math.abs(mapped[0] - 960) < 1e-6 && Math.abs(mapped[1] - layout.map.height / 2) < 1e-6);
    assert.ok(layout.map.height / layout.view.scale >= 688 / 3 - 1e-9);
    assert.deepEqual(
      layout.legend.map((item) => item.text),
      ['Ego', 'A1', 'A2', 'Ego (2)'],
    );
    assert.ok(layout.legend.every((item) => item.y > layout.map.height && item.y < 1080));
    assert.ok(layout.scale.x + layout.scale.pixels <= 1920 && layout.scale.x > layout.legend[3].x);
    const svg = new SvgPainter(1920, 1080, '#000');
    drawExportOverlay(svg, layout, () => '#fff', new Set(['Ego (2)']));
    const text = svg.toString();
    assert.match(text, /width="1920" height="1080"/);
    assert.match(text, />t = 3.00 s of 20.00 s</);
    assert.match(text, new RegExp(`>${layout.scale.text}<`));
    assert.match(text, /stroke-dasharray="3 2"/, 'the compared run is dashed in the legend');
    // With plots and the event list: both below the map, above the band, the map keeping at least half.
    const rows = [
      { text: 'ChangeLane · lead · CutIn · started 2.35 s', dim: false },
      { text: 'Brake · ego · Braking · never started · SimulationTimeCondition', dim: true },
    ];
    const full = exportLayout(1920, 1080, shown, 626, 688, ['Ego'], 't = 3.00 s', 1, { plots: true, events: rows });
    assert.ok(full.plots && full.plots.y === full.map.height && full.plots.width === 1920);
    assert.ok(full.map.height >= 540, 'the map keeps half the picture');
    assert.deepEqual(
      full.events.map((line) => line.text),
      rows.map((row) => row.text),
    );
    const plotsBottom = full.plots.y + full.plots.height;
    assert.ok(
      full.events.every((line) => line.y > plotsBottom && line.y < full.time.y),
      'events between the plots and the band',
    );
    assert.ok(full.time.y < 1080);
    const withEvents = new SvgPainter(1920, 1080, '#000');
    drawExportOverlay(withEvents, full, () => '#fff');
    assert.match(withEvents.toString(), />ChangeLane · lead · CutIn · started 2.35 s</);
    assert.match(withEvents.toString(), /fill="#9e9e9e"[^>]*>Brake · ego/, 'an event that never started is dimmed');
    // More events than fit: the last line says how many were left out.
    const many = Array.from({ length: 80 }, (_, index) => ({ text: `E${index} · started ${index}.00 s`, dim: false }));
    const crowded = exportLayout(1920, 1080, shown, 626, 688, ['Ego'], 't', 1, { plots: true, events: many });
    assert.ok(crowded.map.height >= 540 && crowded.events.length > 3 && crowded.events.length < 80);
    const shownCount = crowded.events.length - 1;
    assert.equal(crowded.events[crowded.events.length - 1].text, `… and ${80 - shownCount} more events`);
    assert.equal(crowded.events[0].text, 'E0 · started 0.00 s');
    // A narrow picture drops legend items rather than writing them over the scale bar.
    const narrow = exportLayout(300, 200, shown, 626, 688, ['Ego', 'A1', 'A2', 'A3', 'A4', 'A5'], 't = 3.00 s');
    assert.ok(narrow.legend.length < 6);
    for (const item of narrow.legend) assert.ok(item.x + 3 * narrow.fontSize < narrow.scale.x);
    // Two runs side by side: each pane half the width, showing what its pane showed (313 px of the panel).
    const split = exportLayout(1920, 1080, shown, 313, 688, ['Ego'], 't', 2);
    assert.ok(Math.abs(split.view.scale - Math.min(960 / (313 / 3), split.map.height / (688 / 3))) < 1e-9);
    assert.deepEqual(
      toScreen(split.view, ...toWorld(shown, 156.5, 344)).map((value) => Math.round(value * 1e6) / 1e6),
      [480, split.map.height / 2],
    );
    const panes = new SvgPainter(200, 100, '#000');
    const right = shiftedPainter(panes, 100);
    right.clip?.(0, 0, 100, 100);
    right.text(5, 10, 'B', '#fff', 12);
    right.polygon([0, 0, 10, 0, 10, 10], '#fff');
    right.unclip?.();
    assert.match(
      panes.toString(),
      /<clipPath id="pane1"><rect x="100" y="0" width="100" height="100"\/><\/clipPath><g clip-path="url\(#pane1\)">\n<text x="105" y="10"[^>]*>B<\/text>\n<polygon points="100,0 110,0 110,10" fill="#fff"\/>\n<\/g>/,
    );
    assert.deepEqual(parseResolution('1920x1080'), [1920, 1080]);
    assert.deepEqual(parseResolution(' 800 × 600 '), [800, 600]);
    assert.equal(parseResolution('8x8'), undefined);
    assert.equal(parseResolution('big'), undefined);
    assert.equal(roadShapes({ uri: '', title: '', sections: [], entities: [], events: [], problems: [] }).lanes.length, 0);
  });
});

function names6(): string[] {
  return ['Eg', 'A1', 'A2', 'A3', 'A4', 'A5'];
}
