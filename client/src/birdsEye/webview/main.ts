/**
 * The bird's-eye view's page: draws the scene on a canvas (roads cached in a layer of their own,
 * entities per frame), plays a run, lists events on a timeline, and sends clicks and saves back.
 */
import type { SceneResult, SourceLocation } from '../../../../common/src/sceneProtocol';
import { centredOn, entitiesBounds, exportLayout, runSeries, tooltipPlace, wheelNotches, zoomAbout } from '../analysis';
import {
  boxAt,
  COLORS,
  drawEntities,
  drawExportOverlay,
  drawRoads,
  drawTrajectories,
  ENTITY_COLORS,
  fitTransform,
  laneAt,
  Painter,
  PlacedBox,
  poseAt,
  RoadShapes,
  roadShapes,
  sceneBounds,
  startBoxes,
  shiftedPainter,
  SvgPainter,
  toWorld,
  ViewTransform,
} from '../draw';
import type { FromView, RenderStats, RunTracks, ToView } from '../messages';
import { drawPlotCursor, drawPlots, type PlotArea, plotSpecs } from '../plots';

declare function acquireVsCodeApi(): { postMessage(message: FromView): void };
const vscode = acquireVsCodeApi();

const element = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const canvas = element<HTMLCanvasElement>('canvas');
const stage = element<HTMLDivElement>('stage');
const tooltip = element<HTMLDivElement>('tooltip');
const slider = element<HTMLInputElement>('slider');
const playButton = element<HTMLButtonElement>('play');
const timeLabel = element<HTMLSpanElement>('time');
const followList = element<HTMLSelectElement>('follow');
const plotsCanvas = element<HTMLCanvasElement>('plots');
const plotsContext = plotsCanvas.getContext('2d')!;
const context = canvas.getContext('2d')!;
/**
 * Roads and trajectories, one layer per pane, drawn LAYER_MARGIN px beyond each side of the pane so that
 * following and panning move it without redrawing.
 */
const layers = [document.createElement('canvas'), document.createElement('canvas')];
const LAYER_MARGIN = 256;
const compareMode = element<HTMLSelectElement>('compareMode');
const plotsLayer = document.createElement('canvas');
const plotsLayerContext = plotsLayer.getContext('2d')!;

let scene: SceneResult | undefined;
let run: RunTracks | undefined;
/** A second run (another concrete scenario): overlaid in a dashed style, or in a pane of its own beside the first. */
let compare: RunTracks | undefined;
let sideBySide = false;
/** The entity plotted and outlined; followed while `following`. */
let chosen: string | undefined;
let following = false;
/** The view the layer was drawn for. */
let layerView: ViewTransform | undefined;
let plotAreas: PlotArea[] = [];
let drawnLabels: string[] = [];
let shapes: RoadShapes = { lanes: [], borders: [], bounds: undefined };
let view: ViewTransform | undefined;
let time = 0;
let playing = false;
let lastTick = 0;
const frameTimes: number[] = [];
let staticDrawMs = 0;
let drawnLanes = 0;
const colors = new Map<string, string>();

function colorOf(name: string): string {
  let color = colors.get(name);
  if (!color) {
    color = ENTITY_COLORS[colors.size % ENTITY_COLORS.length];
    colors.set(name, color);
  }
  return color;
}

function canvasPainter(target: CanvasRenderingContext2D): Painter {
  const path = (xy: ArrayLike<number>) => {
    target.beginPath();
    target.moveTo(xy[0], xy[1]);
    for (let i = 2; i + 1 < xy.length; i += 2) target.lineTo(xy[i], xy[i + 1]);
  };
  return {
    polygon(xy, fill) {
      path(xy);
      target.closePath();
      target.fillStyle = fill;
      target.fill();
    },
    polyline(xy, stroke, width, dash) {
      path(xy);
      target.strokeStyle = stroke;
      target.lineWidth = width;
      target.setLineDash(dash ?? []);
      target.stroke();
    },
    clip(x, y, width, height) {
      target.save();
      target.beginPath();
      target.rect(x, y, width, height);
      target.clip();
    },
    unclip() {
      target.restore();
    },
    text(x, y, text, color, size) {
      target.font = `${size}px sans-serif`;
      target.lineWidth = 3;
      target.strokeStyle = 'rgba(0,0,0,0.7)';
      target.setLineDash([]);
      target.strokeText(text, x, y);
      target.fillStyle = color;
      target.fillText(text, x, y);
    },
  };
}

const size = () => ({ width: stage.clientWidth, height: stage.clientHeight });
const lastTime = (tracks: RunTracks | undefined) => (tracks && tracks.times.length > 0 ? tracks.times[tracks.times.length - 1] : 0);
const duration = () => Math.max(lastTime(run), lastTime(compare));

function boxesAt(tracks: RunTracks): PlacedBox[] {
  const boxes: PlacedBox[] = [];
  for (const track of tracks.entities) {
    const pose = poseAt(tracks, track, time);
    if (Number.isFinite(pose.x))
      boxes.push({ name: track.name, ...pose, length: track.length, width: track.width, centerX: track.centerX });
  }
  return boxes;
}

/** Where each entity is now: on its trajectory after a run, at its start position before. */
function currentBoxes(): PlacedBox[] {
  return run ? boxesAt(run) : startBoxes(scene?.entities ?? []);
}

const comparedBoxes = () => (compare ? boxesAt(compare) : []);

/** A part of the map: the whole of it, or one of two runs side by side. */
interface Pane {
  x: number;
  width: number;
  /** The run drawn solid (none before a run: the start positions). */
  tracks: RunTracks | undefined;
  /** The run drawn dashed over it. */
  overlay: RunTracks | undefined;
}

function panesOf(width: number): Pane[] {
  if (compare && sideBySide) {
    const half = Math.floor(width / 2);
    return [
      { x: 0, width: half, tracks: run, overlay: undefined },
      { x: half, width: width - half, tracks: compare, overlay: undefined },
    ];
  }
  return [{ x: 0, width, tracks: run, overlay: compare }];
}

const panes = () => panesOf(size().width);
const paneBoxes = (pane: Pane) => (pane.tracks ? boxesAt(pane.tracks) : startBoxes(scene?.entities ?? []));
const paneAt = (x: number) => panes().find((pane) => x >= pane.x && x < pane.x + pane.width) ?? panes()[0];

function drawStatic(painter: Painter, width: number, height: number, pane: Pane = panes()[0]): void {
  if (!view) return;
  drawnLanes = drawRoads(painter, shapes, view, width, height);
  if (pane.tracks) drawTrajectories(painter, pane.tracks, view, colorOf);
  if (pane.overlay) drawTrajectories(painter, pane.overlay, view, colorOf, true);
}

/** The pane's entities, its overlay's dashed, labels kept inside the pane. */
function drawPane(painter: Painter, pane: Pane, paneView: ViewTransform, height: number, labelSize = 12): string[] {
  const labels = drawEntities(painter, paneBoxes(pane), paneView, colorOf, {
    width: pane.width,
    height,
    chosen,
    compare: pane.overlay ? boxesAt(pane.overlay) : [],
    labelSize,
  });
  if (sideBySide && compare && pane.tracks) painter.text(8, 8 + labelSize, `run: ${pane.tracks.label}`, COLORS.label, labelSize + 1);
  return labels.map((label) => label.text);
}

/** The legend names the road file drawn, so that a saved picture says which road it shows. */
function drawRoadLegend(painter: Painter, height: number): void {
  if (scene?.roadFile)
    painter.text(8, height - 8, `road: ${scene.roadFile.resolved ?? `${scene.roadFile.filepath} (not found)`}`, COLORS.label, 11);
}

/** Roads and trajectories change only with the view or the data: drawn once into their layers, a margin around each pane. */
function renderLayer(): void {
  const { width, height } = size();
  const ratio = window.devicePixelRatio || 1;
  canvas.width = Math.max(1, Math.round(width * ratio));
  canvas.height = Math.max(1, Math.round(height * ratio));
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  if (!view) return;
  drawLayers();
  renderPlots();
  renderFrame();
  report();
}

/** Draws each pane's layer for the view now. */
function drawLayers(): void {
  if (!view) return;
  const { height } = size();
  const ratio = window.devicePixelRatio || 1;
  const started = performance.now();
  const shown = view;
  layerView = { scale: view.scale, left: view.left - LAYER_MARGIN / view.scale, top: view.top + LAYER_MARGIN / view.scale };
  const paneList = panes();
  // The first pane's lanes are the ones counted: it is drawn last.
  [...paneList.entries()].reverse().forEach(([index, pane]) => {
    const layer = layers[index];
    layer.width = Math.max(1, Math.round((pane.width + 2 * LAYER_MARGIN) * ratio));
    layer.height = Math.max(1, Math.round((height + 2 * LAYER_MARGIN) * ratio));
    const layerContext = layer.getContext('2d')!;
    layerContext.setTransform(ratio, 0, 0, ratio, 0, 0);
    layerContext.fillStyle = COLORS.background;
    layerContext.fillRect(0, 0, pane.width + 2 * LAYER_MARGIN, height + 2 * LAYER_MARGIN);
    view = layerView;
    try {
      drawStatic(canvasPainter(layerContext), pane.width + 2 * LAYER_MARGIN, height + 2 * LAYER_MARGIN, pane);
    } finally {
      view = shown;
    }
  });
  staticDrawMs = performance.now() - started;
}

/** Where the layers are, px, relative to their panes; undefined when they no longer cover the panes at this view. */
function layerOffset(): [number, number] | undefined {
  if (!view || !layerView || layerView.scale !== view.scale) return undefined;
  const dx = (layerView.left - view.left) * view.scale;
  const dy = (view.top - layerView.top) * view.scale;
  return dx <= 0 && dy <= 0 && dx >= -2 * LAYER_MARGIN && dy >= -2 * LAYER_MARGIN ? [dx, dy] : undefined;
}

function renderFrame(): void {
  if (!view) return;
  // A frame that has to redraw the layers (following or panning past their margin) counts that too.
  const started = performance.now();
  const paneList = panes();
  if (following && run && chosen) {
    const track = run.entities.find((entity) => entity.name === chosen);
    const pose = track && poseAt(run, track, time);
    if (pose && Number.isFinite(pose.x)) view = centredOn(view, pose.x, pose.y, paneList[0].width, size().height);
  }
  if (!layerOffset()) drawLayers();
  const offset = layerOffset();
  if (!offset) return;
  const ratio = window.devicePixelRatio || 1;
  const { height } = size();
  context.setTransform(1, 0, 0, 1, 0, 0);
  context.fillStyle = COLORS.background;
  context.fillRect(0, 0, canvas.width, canvas.height);
  drawnLabels = [];
  paneList.forEach((pane, index) => {
    context.save();
    context.setTransform(1, 0, 0, 1, 0, 0);
    context.beginPath();
    context.rect(Math.round(pane.x * ratio), 0, Math.round(pane.width * ratio), canvas.height);
    context.clip();
    context.drawImage(layers[index], Math.round((pane.x + offset[0]) * ratio), Math.round(offset[1] * ratio));
    context.setTransform(ratio, 0, 0, ratio, pane.x * ratio, 0);
    drawnLabels.push(...drawPane(canvasPainter(context), pane, view!, height));
    context.restore();
  });
  context.setTransform(ratio, 0, 0, ratio, 0, 0);
  const painter = canvasPainter(context);
  if (paneList.length > 1) painter.polyline([paneList[1].x, 0, paneList[1].x, height], '#000000', 2);
  drawRoadLegend(painter, height);
  if (plotAreas.length > 0) {
    plotsContext.setTransform(1, 0, 0, 1, 0, 0);
    plotsContext.drawImage(plotsLayer, 0, 0);
    plotsContext.setTransform(ratio, 0, 0, ratio, 0, 0);
    drawPlotCursor(canvasPainter(plotsContext), plotAreas, time);
  }
  if (playing) frameTimes.push(performance.now() - started);
}

const PLOTS_HEIGHT = 150;

/** The plots of the chosen entity's speed, gap and TTC: drawn into their layer when the run, the choice or the size changes. */
function renderPlots(): void {
  const series = run && chosen ? runSeries(run, chosen) : undefined;
  plotsCanvas.style.display = series ? 'block' : 'none';
  plotAreas = [];
  if (!series || !run) return;
  const width = stage.clientWidth;
  const ratio = window.devicePixelRatio || 1;
  for (const target of [plotsCanvas, plotsLayer]) {
    target.width = Math.max(1, Math.round(width * ratio));
    target.height = Math.round(PLOTS_HEIGHT * ratio);
  }
  plotsCanvas.style.width = `${width}px`;
  plotsCanvas.style.height = `${PLOTS_HEIGHT}px`;
  plotsLayerContext.setTransform(ratio, 0, 0, ratio, 0, 0);
  plotAreas = drawPlots(canvasPainter(plotsLayerContext), plotSpecs(series), series.times, undefined, 0, 0, width, PLOTS_HEIGHT, colorOf);
}

function report(): void {
  const frames = frameTimes.length;
  const stats: RenderStats = {
    roads: new Set(shapes.lanes.map((lane) => lane.road)).size,
    lanes: drawnLanes,
    entities: currentBoxes().length,
    trajectories: run?.entities.length ?? 0,
    staticDrawMs,
    frameMeanMs: frames ? frameTimes.reduce((sum, value) => sum + value, 0) / frames : 0,
    frameWorstMs: frames ? Math.max(...frameTimes) : 0,
    frames,
    time,
    playing,
    ...(chosen ? { chosen } : {}),
    compared: compare?.entities.length ?? 0,
    labels: drawnLabels,
    spanMetres: view ? panes()[0].width / view.scale : 0,
    sideBySide: sideBySide && compare !== undefined,
  };
  document.body.dataset.stats = JSON.stringify(stats);
  vscode.postMessage({ type: 'rendered', stats });
}

/** Frames the entities where they are now (`focus`), or the whole road network. */
function fit(focus = true): void {
  const { height } = size();
  const width = panes()[0].width;
  const now = focus ? entitiesBounds([...currentBoxes(), ...comparedBoxes()]) : undefined;
  view = fitTransform(now ?? sceneBounds(shapes, scene, run, focus), width, height);
  if (!focus) setFollowing(false);
  renderLayer();
}

/** Chooses the entity plotted and outlined, and whether the camera follows it. */
function choose(name: string | undefined, follow: boolean): void {
  chosen = name;
  setFollowing(follow && name !== undefined);
  renderPlots();
  renderFrame();
  report();
}

function setFollowing(next: boolean): void {
  following = next;
  followList.value = following && chosen ? chosen : '';
}

function setTime(next: number): void {
  time = Math.min(Math.max(next, 0), duration());
  slider.value = String(duration() > 0 ? Math.round((time / duration()) * 1000) : 0);
  timeLabel.textContent = run ? `${time.toFixed(2)} s / ${duration().toFixed(2)} s` : 'no run loaded';
  const cursor = document.getElementById('cursor');
  if (cursor) cursor.style.left = `${duration() > 0 ? (time / duration()) * 100 : 0}%`;
  renderFrame();
}

function tick(now: number): void {
  if (!playing) return;
  setTime(time + (now - lastTick) / 1000);
  lastTick = now;
  if (time >= duration()) {
    setPlaying(false);
    return;
  }
  requestAnimationFrame(tick);
}

function setPlaying(next: boolean): void {
  playing = next && run !== undefined;
  playButton.textContent = playing ? 'Pause run' : 'Play run';
  if (playing) {
    if (time >= duration()) setTime(0);
    frameTimes.length = 0;
    lastTick = performance.now();
    requestAnimationFrame(tick);
  } else {
    report();
  }
}

function button(label: string, title: string, onClick: () => void, className = ''): HTMLButtonElement {
  const result = document.createElement('button');
  result.textContent = label;
  result.title = title;
  result.className = className;
  result.addEventListener('click', onClick);
  return result;
}

const open = (source: SourceLocation | undefined) => source && vscode.postMessage({ type: 'open', source });

function renderPanel(): void {
  const entities = element<HTMLDivElement>('entities');
  entities.replaceChildren();
  for (const entity of scene?.entities ?? []) {
    const item = button(
      `■ ${entity.name}`,
      `${entity.kind}: ${entity.described}${entity.problem ? ` — ${entity.problem}` : ''}`,
      () => open(entity.source),
      'entity',
    );
    item.style.color = colorOf(entity.name);
    entities.append(item);
  }
  const events = element<HTMLUListElement>('events');
  const markers = element<HTMLDivElement>('markers');
  events.replaceChildren();
  markers.replaceChildren();
  const total = duration();
  for (const event of scene?.events ?? []) {
    const started = run?.starts[event.name];
    const when =
      started !== undefined
        ? `started ${started.toFixed(2)} s`
        : event.plannedTime !== undefined
          ? `planned ${event.plannedTime} s`
          : run
            ? 'did not start'
            : 'start after a run';
    const item = document.createElement('li');
    item.append(
      button(event.name, `${event.act} / ${event.group} / ${event.maneuver}`, () => open(event.source), 'event'),
      ` ${when} · ${event.trigger}`,
    );
    events.append(item);
    const at = started ?? event.plannedTime;
    if (at !== undefined && total > 0 && at <= total) {
      const marker = document.createElement('div');
      marker.className = started !== undefined ? 'marker started' : 'marker planned';
      marker.style.left = `${(at / total) * 100}%`;
      marker.title = `${event.name}: ${when}`;
      marker.addEventListener('click', () => {
        setTime(at);
        open(event.source);
      });
      markers.append(marker);
    }
  }
  const cursor = document.createElement('div');
  cursor.id = 'cursor';
  markers.append(cursor);
  const problems = element<HTMLUListElement>('problems');
  const drawn = scene?.roadFile?.resolved;
  // The run and the picture resolve the road alike (core/roadFiles.ts); a run loaded elsewhere (an older CSV, another tool) is said so.
  const otherRoad =
    run?.roadFile && drawn && run.roadFile !== drawn ? [`the run loaded the road file ${run.roadFile}; the picture draws ${drawn}`] : [];
  problems.replaceChildren(
    ...[...(scene?.problems ?? []), ...(run?.notes ?? []), ...otherRoad].map((problem) =>
      Object.assign(document.createElement('li'), { textContent: problem }),
    ),
  );
  const road = scene?.roadFile
    ? ` · road ${drawn ?? `${scene.roadFile.filepath} (not found)`}${drawn ? ` (${scene.roadFile.roadCount} road${scene.roadFile.roadCount === 1 ? '' : 's'})` : ''}`
    : '';
  const title = element<HTMLSpanElement>('title');
  title.textContent = scene ? `${scene.title}${road}${run ? ` · run: ${run.label}` : ''}` : 'loading…';
  title.title = drawn ? `The road file drawn: ${drawn} (${scene?.roadFile?.filepath} as the scenario says)` : '';
  const names = [
    ...new Set([...(run?.entities.map((track) => track.name) ?? []), ...(scene?.entities.map((entity) => entity.name) ?? [])]),
  ];
  if (chosen && !names.includes(chosen)) chosen = undefined;
  followList.replaceChildren(
    Object.assign(document.createElement('option'), { value: '', textContent: 'Follow: none' }),
    ...names.map((name) => Object.assign(document.createElement('option'), { value: name, textContent: `Follow ${name}` })),
  );
  followList.value = following && chosen ? chosen : '';
  if (compare) title.textContent += ` · compared with: ${compare.label}${sideBySide ? ' (right)' : ' (dashed)'}`;
  compareMode.style.display = compare ? '' : 'none';
  compareMode.value = sideBySide ? 'side' : 'overlay';
  const hasRun = run !== undefined;
  playButton.disabled = !hasRun;
  slider.disabled = !hasRun;
}

window.addEventListener('message', (event: MessageEvent<ToView>) => {
  const message = event.data;
  if (message.type === 'scene') {
    const first = scene === undefined || scene.uri !== message.scene.uri;
    scene = message.scene;
    shapes = roadShapes(scene);
    for (const entity of scene.entities) colorOf(entity.name);
    renderPanel();
    if (first || !view) fit();
    else renderLayer();
  } else if (message.type === 'run') {
    run = message.run;
    compare = undefined;
    setPlaying(false);
    renderPanel();
    setTime(0);
    fit();
  } else if (message.type === 'compare') {
    compare = message.run;
    sideBySide = message.sideBySide === true;
    setPlaying(false);
    renderPanel();
    setTime(time);
    // Half as wide a pane: framed anew.
    if (sideBySide) fit(true);
    else renderLayer();
  } else if (message.type === 'choose') {
    choose(message.entity, message.entity !== undefined);
  } else if (message.type === 'export') {
    vscode.postMessage({
      type: 'save',
      format: message.format,
      data: picture(message.format, message.width, message.height),
      id: message.id,
    });
  } else if (message.type === 'error') {
    element<HTMLUListElement>('problems').replaceChildren(
      Object.assign(document.createElement('li'), { textContent: message.message, className: 'error' }),
    );
  }
});

// Pan by dragging, zoom with the wheel around the pointer, hover for ids, click to open the source.
let drag: { x: number; y: number; moved: boolean } | undefined;
canvas.addEventListener('mousedown', (event) => (drag = { x: event.offsetX, y: event.offsetY, moved: false }));
window.addEventListener('mouseup', (event) => {
  if (drag && !drag.moved && view && event.target === canvas) {
    const pane = paneAt(event.offsetX);
    const [x, y] = toWorld(view, event.offsetX - pane.x, event.offsetY);
    const box = boxAt(paneBoxes(pane), view, x, y);
    if (box) {
      choose(box.name, true);
      open(scene?.entities.find((entity) => entity.name === box.name)?.source);
    }
  }
  drag = undefined;
});
canvas.addEventListener('mousemove', (event) => {
  if (!view) return;
  if (drag) {
    const dx = event.offsetX - drag.x;
    const dy = event.offsetY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 2 || drag.moved) {
      drag.moved = true;
      setFollowing(false);
      view = { ...view, left: view.left - dx / view.scale, top: view.top + dy / view.scale };
      drag.x = event.offsetX;
      drag.y = event.offsetY;
      renderFrame();
    }
    return;
  }
  const pane = paneAt(event.offsetX);
  const [x, y] = toWorld(view, event.offsetX - pane.x, event.offsetY);
  const box = boxAt(paneBoxes(pane), view, x, y);
  const lane = box ? undefined : laneAt(shapes, x, y);
  const text = box
    ? `${box.name} (click to follow it and open its position in the source)`
    : lane
      ? `road ${lane.road} · lane ${lane.lane} · ${lane.type}${lane.junction ? ' · junction' : ''}`
      : '';
  tooltip.textContent = text;
  tooltip.style.display = text ? 'block' : 'none';
  const [left, top] = tooltipPlace(
    event.offsetX,
    event.offsetY,
    tooltip.offsetWidth,
    tooltip.offsetHeight,
    stage.clientWidth,
    stage.clientHeight,
  );
  tooltip.style.left = `${left}px`;
  tooltip.style.top = `${top}px`;
  canvas.style.cursor = box ? 'pointer' : 'default';
});
canvas.addEventListener('mouseleave', () => (tooltip.style.display = 'none'));
canvas.addEventListener(
  'wheel',
  (event) => {
    if (!view) return;
    event.preventDefault();
    view = zoomAbout(view, wheelNotches(event.deltaY, event.deltaMode), event.offsetX - paneAt(event.offsetX).x, event.offsetY);
    renderFrame();
  },
  { passive: false },
);

playButton.addEventListener('click', () => setPlaying(!playing));
slider.addEventListener('input', () => {
  setPlaying(false);
  setTime((Number(slider.value) / 1000) * duration());
});
element('fit').addEventListener('click', () => fit(true));
element('network').addEventListener('click', () => fit(false));
element('load').addEventListener('click', () => vscode.postMessage({ type: 'loadRun' }));
element('compare').addEventListener('click', () => vscode.postMessage({ type: 'loadRun', compare: true }));
compareMode.addEventListener('change', () => {
  sideBySide = compareMode.value === 'side';
  renderPanel();
  fit(true);
});
followList.addEventListener('change', () => choose(followList.value || chosen, followList.value !== ''));
/**
 * The picture at `width` × `height` (the panel's size when not given): the map around what is shown,
 * and a band with the time, a legend and a scale bar; a PNG data URL or an SVG document.
 */
function picture(format: 'png' | 'svg', width = size().width, height = size().height): string {
  const shownSize = size();
  const shownPanes = panes();
  const shown = view ?? fitTransform(sceneBounds(shapes, scene, run), shownPanes[0].width, shownSize.height);
  const overlaid = compare !== undefined && !sideBySide;
  const compared = new Set(overlaid && compare ? compare.entities.map((track) => `${track.name} (2)`) : []);
  const names = [
    ...new Set([...currentBoxes().map((box) => box.name), ...(sideBySide ? comparedBoxes().map((box) => box.name) : [])]),
    ...compared,
  ];
  const timeText = `${run ? `t = ${time.toFixed(2)} s of ${duration().toFixed(2)} s` : 'start positions'}${compare ? ` · ${run?.label} vs ${compare.label}${overlaid ? ' (dashed)' : ''}` : ''}`;
  const layout = exportLayout(width, height, shown, shownPanes[0].width, shownSize.height, names, timeText, shownPanes.length);
  const draw = (painter: Painter) => {
    const kept = view;
    view = layout.view;
    try {
      for (const pane of panesOf(width)) {
        const paneView = layout.view;
        const target = shiftedPainter(painter, pane.x);
        target.clip?.(0, 0, pane.width, layout.map.height);
        drawStatic(target, pane.width, layout.map.height, pane);
        drawPane(target, pane, paneView, layout.map.height, layout.fontSize);
        target.unclip?.();
        if (pane.x > 0) painter.polyline([pane.x, 0, pane.x, layout.map.height], '#000000', 2);
      }
      drawRoadLegend(painter, layout.map.height);
    } finally {
      view = kept;
    }
    drawExportOverlay(painter, layout, colorOf, compared);
  };
  if (format === 'svg') {
    const svg = new SvgPainter(width, height, COLORS.background);
    draw(svg);
    return svg.toString();
  }
  const target = document.createElement('canvas');
  target.width = width;
  target.height = height;
  const targetContext = target.getContext('2d')!;
  targetContext.fillStyle = COLORS.background;
  targetContext.fillRect(0, 0, width, height);
  draw(canvasPainter(targetContext));
  return target.toDataURL('image/png');
}
element('png').addEventListener('click', () => vscode.postMessage({ type: 'saveAs', format: 'png' }));
element('svg').addEventListener('click', () => vscode.postMessage({ type: 'saveAs', format: 'svg' }));
new ResizeObserver(() => (view ? renderLayer() : undefined)).observe(stage);
vscode.postMessage({ type: 'ready' });
