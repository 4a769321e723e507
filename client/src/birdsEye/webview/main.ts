/**
 * The bird's-eye view's page: draws the scene on a canvas (roads cached in a layer of their own,
 * entities per frame), plays a run, lists events on a timeline, and sends clicks and saves back.
 * This file wires the page's controls and messages to the modules that do the work.
 */
import type { ToView } from '../messages';
import { choose, fit, setPlaying, setTime } from './controls';
import { compareMode, element, followList, playButton, slider, stage } from './dom';
import { handleMessage } from './handleMessage';
import { vscode } from './host';
import { renderPanel } from './panelDom';
import { listenToPointer } from './pointer';
import { renderLayer } from './render';
import { duration, state } from './state';

window.addEventListener('message', (event: MessageEvent<ToView>) => handleMessage(event.data));
listenToPointer();

playButton.addEventListener('click', () => setPlaying(!state.playing));
slider.addEventListener('input', () => {
  setPlaying(false);
  setTime((Number(slider.value) / 1000) * duration());
});
element('fit').addEventListener('click', () => fit(true));
element('network').addEventListener('click', () => fit(false));
element('load').addEventListener('click', () => vscode.postMessage({ type: 'loadRun' }));
element('compare').addEventListener('click', () => vscode.postMessage({ type: 'loadRun', compare: true }));
compareMode.addEventListener('change', () => {
  state.sideBySide = compareMode.value === 'side';
  renderPanel();
  fit(true);
});
followList.addEventListener('change', () => choose(followList.value || state.chosen, followList.value !== ''));
element('png').addEventListener('click', () => vscode.postMessage({ type: 'saveAs', format: 'png' }));
element('svg').addEventListener('click', () => vscode.postMessage({ type: 'saveAs', format: 'svg' }));
new ResizeObserver(() => (state.view ? renderLayer() : undefined)).observe(stage);
vscode.postMessage({ type: 'ready' });
