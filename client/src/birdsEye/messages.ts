/** Messages between the extension and the bird's-eye webview. Plain data: both bundles import it. */
import type { SceneResult, SourceLocation } from '../../../common/src/sceneProtocol';

/** A run as the view draws it: frames downsampled from the esmini CSV, coordinates in centimetres' precision. */
export interface RunTracks {
  /** Where it came from, for the title. */
  label: string;
  times: number[];
  /** `speed`: esmini's Current_Speed, m/s, when the CSV has it (the plots otherwise derive it from the positions). */
  entities: { name: string; length: number; width: number; centerX: number; x: number[]; y: number[]; hdg: number[]; speed?: number[] }[];
  /**
   * esmini's path of a storyboard element (`Story::Act::ManeuverGroup::Maneuver::Event`, flattened names: one per copy
   * of a reused group) → the simulation time it first started, from the run's storyboard trace (eventList.ts).
   */
  starts: Record<string, number>;
  /** The same path → the condition that started it, in words, when the trace says what esmini measured. */
  causes?: Record<string, string>;
  /** What was left out or could not be read. */
  notes: string[];
  /** For a debug session's run: which run of the session (common/src/debugState.ts DebugState.run). */
  sessionRun?: number;
  /** The road file esmini's log says it loaded, when the log is known. */
  roadFile?: string;
}

export type ToView =
  | { type: 'scene'; scene: SceneResult }
  | { type: 'run'; run: RunTracks | undefined }
  /** A second run (another concrete scenario) to compare with the first, overlaid or side by side; undefined ends the comparison. */
  | { type: 'compare'; run: RunTracks | undefined; sideBySide?: boolean }
  | { type: 'error'; message: string }
  /** A debug session's run so far, drawn at its last time; `running`: the paths of the storyboard elements running now (highlighted). */
  | { type: 'live'; run: RunTracks; running: string[] }
  /** Asks for the picture as it is now; answered by a `save` with the same id. */
  | { type: 'export'; format: 'png' | 'svg'; id: number; width?: number; height?: number }
  /** Follows and plots an entity (undefined: none); for a command or a test. */
  | { type: 'choose'; entity: string | undefined }
  /** Shows the run at this time, s (the storyboard timeline's cursor was moved). */
  | { type: 'time'; time: number };

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
  /** The entity followed and plotted, if any. */
  chosen?: string;
  /** Entities of the compared run drawn, 0 without one. */
  compared: number;
  /** Names labelled on the map now (labels that found no free place are left out). */
  labels: string[];
  /** Metres across the map (its first pane) now. */
  spanMetres: number;
  /** The compared run is in a pane of its own beside the first. */
  sideBySide?: boolean;
}

export type FromView =
  | { type: 'ready' }
  | { type: 'open'; source: SourceLocation }
  /** `compare`: the run is a second one, compared with the first. */
  | { type: 'loadRun'; compare?: boolean }
  /** The picture: a PNG data URL or an SVG document; `id` when it answers an `export`. */
  | { type: 'save'; format: 'png' | 'svg'; data: string; id?: number }
  /** The Save buttons: the extension asks for the resolution, then sends an `export`. */
  | { type: 'saveAs'; format: 'png' | 'svg' }
  | { type: 'rendered'; stats: RenderStats }
  /** The time shown changed (the slider, playing, a marker): the storyboard timeline's cursor follows. */
  | { type: 'time'; time: number };

export const isFromView = (value: unknown): value is FromView =>
  typeof value === 'object' && value !== null && typeof (value as { type?: unknown }).type === 'string';
