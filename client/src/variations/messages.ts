/** Messages between the extension and the Variations webview. Plain data: both bundles import it. */
import type { ResultsTable } from '../../../common/src/variationsReport';

export type ToView =
  /** The results to show; `runs` says whether the batch kept its runs (batch --keep-runs), so rows can be opened. */
  | { type: 'results'; title: string; table: ResultsTable; runs: boolean }
  | { type: 'error'; message: string }
  /** Why a click did not open a run, shown in the view until the next click or the next results (not a toast that outlives them). */
  | { type: 'notice'; message: string };

/** What the view reports after drawing, for tests and a status line. */
export interface VariationsStats {
  rows: number;
  /** Rows after the outcome filter. */
  shown: number;
  points: number;
  sort: { column: string; direction: 'ascending' | 'descending' };
  x: string;
  y: string;
  outcomes: string[];
}

export type FromView = { type: 'ready' } | { type: 'openRun'; index: string } | { type: 'rendered'; stats: VariationsStats };

export const isFromView = (value: unknown): value is FromView =>
  typeof value === 'object' && value !== null && typeof (value as { type?: unknown }).type === 'string';
