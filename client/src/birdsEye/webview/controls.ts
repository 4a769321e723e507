/** What the controls do: frame the map, choose and follow an entity, set the time, play the run. */
import { entitiesBounds } from '../analysis';
import { fitTransform, sceneBounds } from '../draw';
import { followList, playButton, slider, timeLabel } from './dom';
import { vscode } from './host';
import { frameTimes, renderFrame, renderLayer, renderPlots, report } from './render';
import { comparedBoxes, currentBoxes, duration, panes, size, state } from './state';

let lastTick = 0;

/** Frames the entities where they are now (`focus`), or the whole road network. */
export function fit(focus = true): void {
  const { height } = size();
  const width = panes()[0].width;
  const now = focus ? entitiesBounds([...currentBoxes(), ...comparedBoxes()]) : undefined;
  state.view = fitTransform(now ?? sceneBounds(state.shapes, state.scene, state.run, focus), width, height);
  if (!focus) setFollowing(false);
  renderLayer();
}

/** Chooses the entity plotted and outlined, and whether the camera follows it. */
export function choose(name: string | undefined, follow: boolean): void {
  state.chosen = name;
  setFollowing(follow && name !== undefined);
  renderPlots();
  renderFrame();
  report();
}

export function setFollowing(next: boolean): void {
  state.following = next;
  followList.value = state.following && state.chosen ? state.chosen : '';
}

export function setTime(next: number): void {
  state.time = Math.min(Math.max(next, 0), duration());
  slider.value = String(duration() > 0 ? Math.round((state.time / duration()) * 1000) : 0);
  timeLabel.textContent = state.run ? `${state.time.toFixed(2)} s / ${duration().toFixed(2)} s` : 'no run loaded';
  const cursor = document.getElementById('cursor');
  if (cursor) cursor.style.left = `${duration() > 0 ? (state.time / duration()) * 100 : 0}%`;
  renderFrame();
  // Without a run the view has no time of its own to share.
  if (state.run) shareTime();
}

let sharedAt = 0;
let shareTimer: number | undefined;
/** Tells the extension the time shown (for the storyboard timeline's cursor), at most about ten times a second. */
function shareTime(): void {
  const now = performance.now();
  clearTimeout(shareTimer);
  if (now - sharedAt >= 100) {
    sharedAt = now;
    vscode.postMessage({ type: 'time', time: state.time });
  } else shareTimer = window.setTimeout(shareTime, 100 - (now - sharedAt));
}

function tick(now: number): void {
  if (!state.playing) return;
  setTime(state.time + (now - lastTick) / 1000);
  lastTick = now;
  if (state.time >= duration()) {
    setPlaying(false);
    return;
  }
  requestAnimationFrame(tick);
}

export function setPlaying(next: boolean): void {
  state.playing = next && state.run !== undefined;
  playButton.textContent = state.playing ? 'Pause run' : 'Play run';
  if (state.playing) {
    if (state.time >= duration()) setTime(0);
    frameTimes.length = 0;
    lastTick = performance.now();
    requestAnimationFrame(tick);
  } else {
    report();
  }
}
