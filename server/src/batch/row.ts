import type { Collision } from '../esmini/log';

/**
 * `ok`: the scenario ended by itself and esmini reported no error; `limit`: the limit the user set (--duration)
 * stopped it before it ended; `timeout`: it hung (no progress) or ran away; `error`: esmini reported an error or
 * could not run it; `discarded`: not run, its values break the scenario's ValueConstraintGroups (the row keeps its
 * index, esmini's --param_permutation, and its values).
 */
export type RunStatus = 'ok' | 'limit' | 'timeout' | 'error' | 'discarded';
export const RUN_STATUSES: readonly RunStatus[] = ['ok', 'limit', 'timeout', 'error', 'discarded'];

/** A run's verdict against the batch's --fail-if criteria. */
export type Verdict = 'pass' | 'fail' | '';

/** One concrete scenario's result: a line of results.csv, and with its messages an entry of results.json. */
export interface BatchRow {
  index: string;
  status: RunStatus;
  collision: boolean;
  min_distance_m: number | null;
  min_ttc_s: number | null;
  end_time_s: number | null;
  /** The varied parameters' values, by name, in the columns' order. */
  parameters: Record<string, string>;
  /** The entity the distances are measured from. */
  ego: string | null;
  collisions: Collision[];
  /** How the run ended, in one sentence. */
  message: string;
  /**
   * Why the run is not `ok`, in one sentence that is the same on every machine (no wall-clock figure): for `error`
   * esmini's own reason (or why it could not run), for `timeout` and `limit` what stopped it, for `discarded` the
   * constraint broken; empty when `ok`. The column `reason` of results.csv. Absent from rows of workers older than it.
   */
  reason?: string;
  /** esmini's errors and warnings. */
  messages: { level: 'error' | 'warn'; time: number | null; text: string }[];
  /** Against the batch's --fail-if criteria (absent without any), and why it fails. */
  verdict?: Verdict;
  failed?: string[];
}
