/**
 * What the view shows (the scene, the runs, the camera, the time, the entity chosen) and what follows from it:
 * the panes, where the entities are.
 */
import type { SceneResult } from '../../../../common/src/sceneProtocol';
import { ENTITY_COLORS, PlacedBox, poseAt, RoadShapes, startBoxes, ViewTransform } from '../draw';
import type { RunTracks } from '../messages';
import { stage } from './dom';

interface ViewState {
  scene: SceneResult | undefined;
  run: RunTracks | undefined;
  /** A second run (another concrete scenario): overlaid in a dashed style, or in a pane of its own beside the first. */
  compare: RunTracks | undefined;
  sideBySide: boolean;
  /** The entity plotted and outlined; followed while `following`. */
  chosen: string | undefined;
  following: boolean;
  shapes: RoadShapes;
  view: ViewTransform | undefined;
  time: number;
  playing: boolean;
  /** Following a debug session: the storyboard elements running now (undefined: no session followed). */
  running: Set<string> | undefined;
}

export const state: ViewState = {
  scene: undefined,
  run: undefined,
  compare: undefined,
  sideBySide: false,
  chosen: undefined,
  following: false,
  shapes: { lanes: [], borders: [], bounds: undefined },
  view: undefined,
  time: 0,
  playing: false,
  running: undefined,
};

const colors = new Map<string, string>();

export function colorOf(name: string): string {
  let color = colors.get(name);
  if (!color) {
    color = ENTITY_COLORS[colors.size % ENTITY_COLORS.length];
    colors.set(name, color);
  }
  return color;
}

export const size = () => ({ width: stage.clientWidth, height: stage.clientHeight });
const lastTime = (tracks: RunTracks | undefined) => (tracks && tracks.times.length > 0 ? tracks.times[tracks.times.length - 1] : 0);
export const duration = () => Math.max(lastTime(state.run), lastTime(state.compare));

export function boxesAt(tracks: RunTracks): PlacedBox[] {
  const boxes: PlacedBox[] = [];
  for (const track of tracks.entities) {
    const pose = poseAt(tracks, track, state.time);
    if (Number.isFinite(pose.x))
      boxes.push({ name: track.name, ...pose, length: track.length, width: track.width, centerX: track.centerX });
  }
  return boxes;
}

/** Where each entity is now: on its trajectory after a run, at its start position before. */
export function currentBoxes(): PlacedBox[] {
  return state.run ? boxesAt(state.run) : startBoxes(state.scene?.entities ?? []);
}

export const comparedBoxes = () => (state.compare ? boxesAt(state.compare) : []);

/** A part of the map: the whole of it, or one of two runs side by side. */
export interface Pane {
  x: number;
  width: number;
  /** The run drawn solid (none before a run: the start positions). */
  tracks: RunTracks | undefined;
  /** The run drawn dashed over it. */
  overlay: RunTracks | undefined;
}

export function panesOf(width: number): Pane[] {
  if (state.compare && state.sideBySide) {
    const half = Math.floor(width / 2);
    return [
      { x: 0, width: half, tracks: state.run, overlay: undefined },
      { x: half, width: width - half, tracks: state.compare, overlay: undefined },
    ];
  }
  return [{ x: 0, width, tracks: state.run, overlay: state.compare }];
}

export const panes = () => panesOf(size().width);
export const paneBoxes = (pane: Pane) => (pane.tracks ? boxesAt(pane.tracks) : startBoxes(state.scene?.entities ?? []));
export const paneAt = (x: number) => panes().find((pane) => x >= pane.x && x < pane.x + pane.width) ?? panes()[0];
