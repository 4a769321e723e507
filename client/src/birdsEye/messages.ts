/** Messages between the extension and the bird's-eye webview. Plain data: both bundles import it. */
import type { SceneResult, SourceLocation } from '../../../common/src/sceneProtocol';

/** A run as the view draws it: frames downsampled from the esmini CSV, coordinates in centimetres' precision. */
export interface RunTracks {
  /** Where it came from, for the title. */
  label: string;
  times: number[];
  entities: { name: string; length: number; width: number; centerX: number; x: number[]; y: number[]; hdg: number[] }[];
  /** Storyboard element name → simulation time it started (from esmini's log), when known. */
  starts: Record<string, number>;
  /** What was left out or could not be read. */
  notes: string[];
  /** The road file esmini's log says it loaded, when the log is known. */
  roadFile?: string;
}

export type ToView =
  | { type: 'scene'; scene: SceneResult }
  | { type: 'run'; run: RunTracks | undefined }
  | { type: 'error'; message: string }
  /** Asks for the picture as it is now; answered by a `save` with the same id. */
  | { type: 'export'; format: 'png' | 'svg'; id: number };

/** What the view reports after drawing: what it drew and how long it took. */
export interface RenderStats {
  roads: number;
  lanes: number;
  entities: number;
  trajectories: number;
  /** Time to draw the static layer (roads and trajectories), ms. */
  staticDrawMs: number;
  /** Mean and worst time to draw one animation frame while playing, ms (0 before playing). */
  frameMeanMs: number;
  frameWorstMs: number;
  frames: number;
  /** Playback time shown now, s. */
  time: number;
  playing: boolean;
}

export type FromView =
  | { type: 'ready' }
  | { type: 'open'; source: SourceLocation }
  | { type: 'loadRun' }
  /** The picture: a PNG data URL or an SVG document; `id` when it answers an `export`. */
  | { type: 'save'; format: 'png' | 'svg'; data: string; id?: number }
  | { type: 'rendered'; stats: RenderStats };

export const isFromView = (value: unknown): value is FromView =>
  typeof value === 'object' && value !== null && typeof (value as { type?: unknown }).type === 'string';
