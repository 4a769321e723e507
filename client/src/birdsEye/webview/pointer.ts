/** The map's mouse: pan by dragging, zoom with the wheel around the pointer, hover for ids, click to open the source. */
import { tooltipPlace, wheelNotches, zoomAbout } from '../analysis';
import { boxAt, laneAt, toWorld } from '../draw';
import { choose, setFollowing } from './controls';
import { canvas, stage, tooltip } from './dom';
import { open } from './host';
import { renderFrame } from './render';
import { paneAt, paneBoxes, state } from './state';

let drag: { x: number; y: number; moved: boolean } | undefined;

export function listenToPointer(): void {
  canvas.addEventListener('mousedown', (event) => (drag = { x: event.offsetX, y: event.offsetY, moved: false }));
  window.addEventListener('mouseup', (event) => {
    if (drag && !drag.moved && state.view && event.target === canvas) {
      const pane = paneAt(event.offsetX);
      const [x, y] = toWorld(state.view, event.offsetX - pane.x, event.offsetY);
      const box = boxAt(paneBoxes(pane), state.view, x, y);
      if (box) {
        choose(box.name, true);
        open(state.scene?.entities.find((entity) => entity.name === box.name)?.source);
      }
    }
    drag = undefined;
  });
  canvas.addEventListener('mousemove', (event) => {
    if (!state.view) return;
    if (drag) {
      const dx = event.offsetX - drag.x;
      const dy = event.offsetY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2 || drag.moved) {
        drag.moved = true;
        setFollowing(false);
        state.view = { ...state.view, left: state.view.left - dx / state.view.scale, top: state.view.top + dy / state.view.scale };
        drag.x = event.offsetX;
        drag.y = event.offsetY;
        renderFrame();
      }
      return;
    }
    const pane = paneAt(event.offsetX);
    const [x, y] = toWorld(state.view, event.offsetX - pane.x, event.offsetY);
    const box = boxAt(paneBoxes(pane), state.view, x, y);
    const lane = box ? undefined : laneAt(state.shapes, x, y);
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
      if (!state.view) return;
      event.preventDefault();
      state.view = zoomAbout(
        state.view,
        wheelNotches(event.deltaY, event.deltaMode),
        event.offsetX - paneAt(event.offsetX).x,
        event.offsetY,
      );
      renderFrame();
    },
    { passive: false },
  );
}
