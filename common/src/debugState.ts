/**
 * The debug adapter's custom DAP event for the bird's-eye view (server/src/debug/adapter.ts sends it, the extension
 * forwards it to the view): the entities and the running storyboard elements at one simulated time. Named as the
 * adapter's other custom event (common/src/trace.ts STORYBOARD_EVENT): camelCase, the adapter's name first.
 */
export const DEBUG_STATE_EVENT = 'modular2simpleState';

/**
 * The environment variable the extension starts the debug adapter with: a folder of its storage where the session
 * keeps V8's code cache of its bundle for the editor's runtime (server/src/debug/codeCache.ts).
 */
export const DEBUG_CODE_CACHE_ENV = 'M2S_DEBUG_CODE_CACHE';

export interface DebugStateEntity {
  name: string;
  x: number;
  y: number;
  /** Heading, rad. */
  h: number;
  /** m/s. */
  speed: number;
  length: number;
  width: number;
  /** The bounding box's centre ahead of the reference point, m. */
  centerX: number;
}

export interface DebugState {
  time: number;
  entities: DebugStateEntity[];
  /** The elements running now: esmini's name, its path (flattened names), kind, and the simulated time each started. */
  running: { name: string; path: string; type: string; since: number }[];
  /** The session paused (a stop) or ended; otherwise a sample while it runs. */
  paused: boolean;
  /** Which run of the session (1 from the launch, one more at each restart; common/src/trace.ts StoryboardEventBody.run). */
  run?: number;
}

export function isDebugState(value: unknown): value is DebugState {
  const state = value as Partial<DebugState> | undefined;
  return typeof state?.time === 'number' && Array.isArray(state.entities) && Array.isArray(state.running);
}
