/**
 * The bird's-eye view's page: draws the scene on a canvas (roads cached in a layer of their own,
 * entities per frame), plays a run, lists events on a timeline, and sends clicks and saves back.
 */
import type { SceneResult, SourceLocation } from '../../../../common/src/sceneProtocol';
import {
  boxAt,
  COLORS,
  drawEntities,
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
  SvgPainter,
  toWorld,
  ViewTransform,
} from '../draw';
import type { FromView, RenderStats, RunTracks, ToView } from '../messages';

declare function acquireVsCodeApi(): { postMessage(message: FromView): void };
const vscode = acquireVsCodeApi();

const element = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const canvas = element<HTMLCanvasElement>('canvas');
const stage = element<HTMLDivElement>('stage');
const tooltip = element<HTMLDivElement>('tooltip');
const slider = element<HTMLInputElement>('slider');
const playButton = element<HTMLButtonElement>('play');
const timeLabel = element<HTMLSpanElement>('time');
const context = canvas.getContext('2d')!;
const layer = document.createElement('canvas');
const layerContext = layer.getContext('2d')!;

let scene: SceneResult | undefined;
let run: RunTracks | undefined;
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
const duration = () => (run && run.times.length > 0 ? run.times[run.times.length - 1] : 0);

/** Where each entity is now: on its trajectory after a run, at its start position before. */
function currentBoxes(): PlacedBox[] {
  if (!run) return startBoxes(scene?.entities ?? []);
  const boxes: PlacedBox[] = [];
  for (const track of run.entities) {
    const pose = poseAt(run, track, time);
    if (Number.isFinite(pose.x)) boxes.push({ name: track.name, ...pose, length: track.length, width: track.width, centerX: track.centerX });
  }
  return boxes;
}

function drawStatic(painter: Painter, width: number, height: number): void {
  if (!view) return;
  drawnLanes = drawRoads(painter, shapes, view, width, height);
  if (run) drawTrajectories(painter, run, view, colorOf);
  // The legend names the road file drawn, so that a saved picture says which road it shows.
  if (scene?.roadFile) painter.text(8, height - 8, `road: ${scene.roadFile.resolved ?? `${scene.roadFile.filepath} (not found)`}`, COLORS.label, 11);
}

/** Roads and trajectories change only with the view or the data: drawn once into their layer. */
function renderLayer(): void {
  const { width, height } = size();
  const ratio = window.devicePixelRatio || 1;
  for (const target of [canvas, layer]) {
    target.width = Math.max(1, Math.round(width * ratio));
    target.height = Math.max(1, Math.round(height * ratio));
  }
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  const started = performance.now();
  layerContext.setTransform(ratio, 0, 0, ratio, 0, 0);
  layerContext.fillStyle = COLORS.background;
  layerContext.fillRect(0, 0, width, height);
  drawStatic(canvasPainter(layerContext), width, height);
  staticDrawMs = performance.now() - started;
  renderFrame();
  report();
}

function renderFrame(): void {
  if (!view) return;
  const started = performance.now();
  const ratio = window.devicePixelRatio || 1;
  context.setTransform(1, 0, 0, 1, 0, 0);
  context.drawImage(layer, 0, 0);
  context.setTransform(ratio, 0, 0, ratio, 0, 0);
  drawEntities(canvasPainter(context), currentBoxes(), view, colorOf);
  if (playing) frameTimes.push(performance.now() - started);
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
  };
  document.body.dataset.stats = JSON.stringify(stats);
  vscode.postMessage({ type: 'rendered', stats });
}

/** Frames the entities and their trajectories (`focus`), or the whole road network. */
function fit(focus = true): void {
  const { width, height } = size();
  view = fitTransform(sceneBounds(shapes, scene, run, focus), width, height);
  renderLayer();
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
    const item = button(`■ ${entity.name}`, `${entity.kind}: ${entity.described}${entity.problem ? ` — ${entity.problem}` : ''}`, () => open(entity.source), 'entity');
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
    const when = started !== undefined ? `started ${started.toFixed(2)} s` : event.plannedTime !== undefined ? `planned ${event.plannedTime} s` : run ? 'did not start' : 'start after a run';
    const item = document.createElement('li');
    item.append(button(event.name, `${event.act} / ${event.group} / ${event.maneuver}`, () => open(event.source), 'event'), ` ${when} · ${event.trigger}`);
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
  const otherRoad = run?.roadFile && drawn && run.roadFile !== drawn ? [`the run loaded the road file ${run.roadFile}; the picture draws ${drawn}`] : [];
  problems.replaceChildren(...[...(scene?.problems ?? []), ...(run?.notes ?? []), ...otherRoad].map((problem) => Object.assign(document.createElement('li'), { textContent: problem })));
  const road = scene?.roadFile ? ` · road ${drawn ?? `${scene.roadFile.filepath} (not found)`}${drawn ? ` (${scene.roadFile.roadCount} road${scene.roadFile.roadCount === 1 ? '' : 's'})` : ''}` : '';
  const title = element<HTMLSpanElement>('title');
  title.textContent = scene ? `${scene.title}${road}${run ? ` · run: ${run.label}` : ''}` : 'loading…';
  title.title = drawn ? `The road file drawn: ${drawn} (${scene?.roadFile?.filepath} as the scenario says)` : '';
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
    setPlaying(false);
    renderPanel();
    fit();
    setTime(0);
  } else if (message.type === 'export') {
    vscode.postMessage({ type: 'save', format: message.format, data: picture(message.format), id: message.id });
  } else if (message.type === 'error') {
    element<HTMLUListElement>('problems').replaceChildren(Object.assign(document.createElement('li'), { textContent: message.message, className: 'error' }));
  }
});

// Pan by dragging, zoom with the wheel around the pointer, hover for ids, click to open the source.
let drag: { x: number; y: number; moved: boolean } | undefined;
canvas.addEventListener('mousedown', (event) => (drag = { x: event.offsetX, y: event.offsetY, moved: false }));
window.addEventListener('mouseup', (event) => {
  if (drag && !drag.moved && view && event.target === canvas) {
    const [x, y] = toWorld(view, event.offsetX, event.offsetY);
    const box = boxAt(currentBoxes(), view, x, y);
    if (box) open(scene?.entities.find((entity) => entity.name === box.name)?.source);
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
      view = { ...view, left: view.left - dx / view.scale, top: view.top + dy / view.scale };
      drag.x = event.offsetX;
      drag.y = event.offsetY;
      renderLayer();
    }
    return;
  }
  const [x, y] = toWorld(view, event.offsetX, event.offsetY);
  const box = boxAt(currentBoxes(), view, x, y);
  const lane = box ? undefined : laneAt(shapes, x, y);
  const text = box ? `${box.name} (click to open its position in the source)` : lane ? `road ${lane.road} · lane ${lane.lane} · ${lane.type}${lane.junction ? ' · junction' : ''}` : '';
  tooltip.textContent = text;
  tooltip.style.display = text ? 'block' : 'none';
  tooltip.style.left = `${event.offsetX + 14}px`;
  tooltip.style.top = `${event.offsetY + 14}px`;
  canvas.style.cursor = box ? 'pointer' : 'default';
});
canvas.addEventListener('mouseleave', () => (tooltip.style.display = 'none'));
canvas.addEventListener(
  'wheel',
  (event) => {
    if (!view) return;
    event.preventDefault();
    const factor = Math.exp(-event.deltaY / 500);
    const [x, y] = toWorld(view, event.offsetX, event.offsetY);
    const scale = Math.min(Math.max(view.scale * factor, 0.01), 500);
    view = { scale, left: x - event.offsetX / scale, top: y + event.offsetY / scale };
    renderLayer();
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
/** The picture as shown: the canvas as PNG, or the same drawing as an SVG document. */
function picture(format: 'png' | 'svg'): string {
  if (format === 'png') {
    renderFrame();
    return canvas.toDataURL('image/png');
  }
  const { width, height } = size();
  const svg = new SvgPainter(width, height, COLORS.background);
  drawStatic(svg, width, height);
  if (view) drawEntities(svg, currentBoxes(), view, colorOf);
  return svg.toString();
}
element('png').addEventListener('click', () => vscode.postMessage({ type: 'save', format: 'png', data: picture('png') }));
element('svg').addEventListener('click', () => vscode.postMessage({ type: 'save', format: 'svg', data: picture('svg') }));
new ResizeObserver(() => (view ? renderLayer() : undefined)).observe(stage);
vscode.postMessage({ type: 'ready' });
