/**
 * Draws the map on the page's canvas (roads and trajectories cached in a layer per pane, entities per frame)
 * and the chosen entity's plots below it, and reports what was drawn.
 */
import { centredOn, runSeries } from '../analysis';
import { COLORS, drawEntities, drawRoads, drawTrajectories, Painter, poseAt, ViewTransform } from '../draw';
import type { RenderStats } from '../messages';
import { drawPlotCursor, drawPlots, type PlotArea, plotSpecs } from '../plots';
import { canvasPainter } from './canvasPainter';
import { canvas, plotsCanvas, stage } from './dom';
import { vscode } from './host';
import { boxesAt, colorOf, currentBoxes, Pane, paneBoxes, panes, size, state } from './state';

const plotsContext = plotsCanvas.getContext('2d')!;
const context = canvas.getContext('2d')!;
/**
 * Roads and trajectories, one layer per pane, drawn LAYER_MARGIN px beyond each side of the pane so that
 * following and panning move it without redrawing.
 */
const layers = [document.createElement('canvas'), document.createElement('canvas')];
const LAYER_MARGIN = 256;
const plotsLayer = document.createElement('canvas');
const plotsLayerContext = plotsLayer.getContext('2d')!;

/** The view the layer was drawn for. */
let layerView: ViewTransform | undefined;
let plotAreas: PlotArea[] = [];
let drawnLabels: string[] = [];
export const frameTimes: number[] = [];
let staticDrawMs = 0;
let drawnLanes = 0;

export function drawStatic(painter: Painter, width: number, height: number, pane: Pane = panes()[0]): void {
  if (!state.view) return;
  drawnLanes = drawRoads(painter, state.shapes, state.view, width, height);
  if (pane.tracks) drawTrajectories(painter, pane.tracks, state.view, colorOf);
  if (pane.overlay) drawTrajectories(painter, pane.overlay, state.view, colorOf, true);
}

/** The pane's entities, its overlay's dashed, labels kept inside the pane. */
export function drawPane(painter: Painter, pane: Pane, paneView: ViewTransform, height: number, labelSize = 12): string[] {
  const labels = drawEntities(painter, paneBoxes(pane), paneView, colorOf, {
    width: pane.width,
    height,
    chosen: state.chosen,
    compare: pane.overlay ? boxesAt(pane.overlay) : [],
    labelSize,
  });
  if (state.sideBySide && state.compare && pane.tracks)
    painter.text(8, 8 + labelSize, `run: ${pane.tracks.label}`, COLORS.label, labelSize + 1);
  return labels.map((label) => label.text);
}

/** The legend names the road file drawn, so that a saved picture says which road it shows. */
export function drawRoadLegend(painter: Painter, height: number): void {
  if (state.scene?.roadFile)
    painter.text(
      8,
      height - 8,
      `road: ${state.scene.roadFile.resolved ?? `${state.scene.roadFile.filepath} (not found)`}`,
      COLORS.label,
      11,
    );
}

/** Roads and trajectories change only with the view or the data: drawn once into their layers, a margin around each pane. */
export function renderLayer(): void {
  const { width, height } = size();
  const ratio = window.devicePixelRatio || 1;
  canvas.width = Math.max(1, Math.round(width * ratio));
  canvas.height = Math.max(1, Math.round(height * ratio));
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  if (!state.view) return;
  drawLayers();
  renderPlots();
  renderFrame();
  report();
}

/** Draws each pane's layer for the view now. */
function drawLayers(): void {
  if (!state.view) return;
  const { height } = size();
  const ratio = window.devicePixelRatio || 1;
  const started = performance.now();
  const shown = state.view;
  layerView = {
    scale: state.view.scale,
    left: state.view.left - LAYER_MARGIN / state.view.scale,
    top: state.view.top + LAYER_MARGIN / state.view.scale,
  };
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
    state.view = layerView;
    try {
      drawStatic(canvasPainter(layerContext), pane.width + 2 * LAYER_MARGIN, height + 2 * LAYER_MARGIN, pane);
    } finally {
      state.view = shown;
    }
  });
  staticDrawMs = performance.now() - started;
}

/** Where the layers are, px, relative to their panes; undefined when they no longer cover the panes at this view. */
function layerOffset(): [number, number] | undefined {
  if (!state.view || !layerView || layerView.scale !== state.view.scale) return undefined;
  const dx = (layerView.left - state.view.left) * state.view.scale;
  const dy = (state.view.top - layerView.top) * state.view.scale;
  return dx <= 0 && dy <= 0 && dx >= -2 * LAYER_MARGIN && dy >= -2 * LAYER_MARGIN ? [dx, dy] : undefined;
}

export function renderFrame(): void {
  if (!state.view) return;
  // A frame that has to redraw the layers (following or panning past their margin) counts that too.
  const started = performance.now();
  const paneList = panes();
  if (state.following && state.run && state.chosen) {
    const track = state.run.entities.find((entity) => entity.name === state.chosen);
    const pose = track && poseAt(state.run, track, state.time);
    if (pose && Number.isFinite(pose.x)) state.view = centredOn(state.view, pose.x, pose.y, paneList[0].width, size().height);
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
    drawnLabels.push(...drawPane(canvasPainter(context), pane, state.view!, height));
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
    drawPlotCursor(canvasPainter(plotsContext), plotAreas, state.time);
  }
  if (state.playing) frameTimes.push(performance.now() - started);
}

const PLOTS_HEIGHT = 150;

/** The plots of the chosen entity's speed, gap and TTC: drawn into their layer when the run, the choice or the size changes. */
export function renderPlots(): void {
  const series = state.run && state.chosen ? runSeries(state.run, state.chosen) : undefined;
  plotsCanvas.style.display = series ? 'block' : 'none';
  plotAreas = [];
  if (!series || !state.run) return;
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

export function report(): void {
  const frames = frameTimes.length;
  const stats: RenderStats = {
    roads: new Set(state.shapes.lanes.map((lane) => lane.road)).size,
    lanes: drawnLanes,
    entities: currentBoxes().length,
    trajectories: state.run?.entities.length ?? 0,
    staticDrawMs,
    frameMeanMs: frames ? frameTimes.reduce((sum, value) => sum + value, 0) / frames : 0,
    frameWorstMs: frames ? Math.max(...frameTimes) : 0,
    frames,
    time: state.time,
    playing: state.playing,
    ...(state.chosen ? { chosen: state.chosen } : {}),
    compared: state.compare?.entities.length ?? 0,
    labels: drawnLabels,
    spanMetres: state.view ? panes()[0].width / state.view.scale : 0,
    sideBySide: state.sideBySide && state.compare !== undefined,
  };
  document.body.dataset.stats = JSON.stringify(stats);
  vscode.postMessage({ type: 'rendered', stats });
}
