/** What the page does with each message from the extension. */
import { roadShapes } from '../draw';
import type { ToView } from '../messages';
import { choose, fit, setPlaying, setTime } from './controls';
import { element } from './dom';
import { vscode } from './host';
import { renderPanel } from './panelDom';
import { picture } from './picture';
import { renderLayer, report } from './render';
import { colorOf, state } from './state';

export function handleMessage(message: ToView): void {
  if (message.type === 'scene') {
    const first = state.scene === undefined || state.scene.uri !== message.scene.uri;
    state.scene = message.scene;
    state.shapes = roadShapes(state.scene);
    for (const entity of state.scene.entities) colorOf(entity.name);
    renderPanel();
    if (first || !state.view) fit();
    else renderLayer();
  } else if (message.type === 'run') {
    state.run = message.run;
    state.running = undefined;
    state.compare = undefined;
    setPlaying(false);
    renderPanel();
    setTime(0);
    fit();
  } else if (message.type === 'live') {
    const first = state.running === undefined || state.run === undefined;
    state.run = message.run;
    state.compare = undefined;
    state.running = new Set(message.running);
    setPlaying(false);
    renderPanel();
    setTime(message.run.times[message.run.times.length - 1] ?? 0);
    if (first) fit();
    report();
  } else if (message.type === 'compare') {
    state.compare = message.run;
    state.sideBySide = message.sideBySide === true;
    setPlaying(false);
    renderPanel();
    setTime(state.time);
    // Half as wide a pane: framed anew.
    if (state.sideBySide) fit(true);
    else renderLayer();
  } else if (message.type === 'time') {
    setTime(message.time);
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
}
