/** Messages between the extension and the storyboard timeline's webview. Plain data: both bundles import it. */
import type { Timeline } from '../../../common/src/storyboardTimeline';

export type ToView =
  /** The timeline to draw; `live` while a debug session adds to it; `label` says where it comes from. */
  | { type: 'timeline'; timeline: Timeline; label: string; live: boolean }
  /** The current time (the bird's-eye view's, or a debug session's), s. */
  | { type: 'time'; time: number };

/** What the view drew, for tests: the rows' elements with their text as shown. */
export interface TimelineStats {
  rows: { element: string; text: string; bars: number; started: boolean }[];
  time: number;
}

export type FromView =
  | { type: 'ready' }
  /** A row was clicked: its element's place (`file` as the trace gives it, 1-based `line`). */
  | { type: 'open'; element: string }
  /** A click on the time axis: the time to show in the bird's-eye view. */
  | { type: 'time'; time: number }
  | { type: 'rendered'; stats: TimelineStats };

export const isFromView = (value: unknown): value is FromView =>
  typeof value === 'object' && value !== null && typeof (value as { type?: unknown }).type === 'string';
