/** The map saved as a picture (PNG or SVG), drawn with the same functions as the page. */
import { exportLayout, runSeries } from '../analysis';
import { COLORS, drawExportOverlay, fitTransform, Painter, sceneBounds, shiftedPainter, SvgPainter } from '../draw';
import { eventRowText } from '../eventList';
import { drawPlots, plotSpecs } from '../plots';
import { canvasPainter } from './canvasPainter';
import { shownEventRows } from './panelDom';
import { drawPane, drawRoadLegend, drawStatic } from './render';
import { colorOf, comparedBoxes, currentBoxes, duration, panes, panesOf, size, state } from './state';

/**
 * The picture at `width` × `height` (the panel's size when not given): the map around what is shown, the
 * followed entity's plots, the event list as the panel words it, and a band with the time, a legend and a
 * scale bar; a PNG data URL or an SVG document.
 */
export function picture(format: 'png' | 'svg', width = size().width, height = size().height): string {
  const shownSize = size();
  const shownPanes = panes();
  const shown = state.view ?? fitTransform(sceneBounds(state.shapes, state.scene, state.run), shownPanes[0].width, shownSize.height);
  const overlaid = state.compare !== undefined && !state.sideBySide;
  const compared = new Set(overlaid && state.compare ? state.compare.entities.map((track) => `${track.name} (2)`) : []);
  const names = [
    ...new Set([...currentBoxes().map((box) => box.name), ...(state.sideBySide ? comparedBoxes().map((box) => box.name) : [])]),
    ...compared,
  ];
  const timeText = `${state.run ? `t = ${state.time.toFixed(2)} s of ${duration().toFixed(2)} s` : 'start positions'}${state.compare ? ` · ${state.run?.label} vs ${state.compare.label}${overlaid ? ' (dashed)' : ''}` : ''}`;
  const series = state.run && state.chosen ? runSeries(state.run, state.chosen) : undefined;
  const events = shownEventRows().map((row) => ({ text: eventRowText(row), dim: row.state === 'never' }));
  const layout = exportLayout(width, height, shown, shownPanes[0].width, shownSize.height, names, timeText, shownPanes.length, {
    plots: series !== undefined,
    events,
  });
  const draw = (painter: Painter) => {
    const kept = state.view;
    state.view = layout.view;
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
      state.view = kept;
    }
    drawExportOverlay(painter, layout, colorOf, compared);
    const area = layout.plots;
    if (series && area) drawPlots(painter, plotSpecs(series), series.times, state.time, area.x, area.y, area.width, area.height, colorOf);
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
