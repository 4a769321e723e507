import { BatchRow, RUN_STATUSES, RunStatus } from './results';

/** Where a batch or a worker reports its progress and summaries: the CLI's standard error. */
export interface BatchOutput {
  err: (text: string) => void;
}

function clock(seconds: number): string {
  if (!Number.isFinite(seconds)) return '--:--';
  const whole = Math.round(seconds);
  const hours = Math.floor(whole / 3600);
  const minutes = Math.floor((whole % 3600) / 60);
  const rest = String(whole % 60).padStart(2, '0');
  return hours > 0 ? `${hours}:${String(minutes).padStart(2, '0')}:${rest}` : `${minutes}:${rest}`;
}

/** A run as the progress and a worker print it: `7: ok, collision`, or with why it failed, `7: error: esmini did not run …`. */
export function runLine(row: BatchRow): string {
  const why = (row.status === 'error' || row.status === 'timeout') && row.reason ? `: ${row.reason}` : '';
  return `${row.index}: ${row.status}${row.collision ? ', collision' : ''}${why}`;
}

/** A progress bar with the rate and the time left on a terminal; a plain line per run otherwise. */
export class Progress {
  private done = 0;
  private readonly started = Date.now();
  private lastDraw = 0;

  constructor(
    private readonly total: number,
    private readonly tty: { write(text: string): void; columns?: number } | undefined,
    private readonly line: (text: string) => void,
  ) {}

  /** One run ended. */
  tick(row: BatchRow): void {
    this.done++;
    if (!this.tty) {
      this.line(`[${this.done}/${this.total}] ${runLine(row)}`);
      return;
    }
    if (this.done < this.total && Date.now() - this.lastDraw < 100) return;
    this.lastDraw = Date.now();
    const elapsed = (Date.now() - this.started) / 1000;
    const rate = this.done / Math.max(elapsed, 1e-3);
    const left = (this.total - this.done) / rate;
    const text = ` ${this.done}/${this.total} ${Math.floor((100 * this.done) / Math.max(this.total, 1))}%  ${rate.toFixed(1)} runs/s  ETA ${clock(left)}`;
    const width = Math.max(10, Math.min(40, (this.tty.columns ?? 80) - text.length - 3));
    const filled = Math.round((width * this.done) / Math.max(this.total, 1));
    this.tty.write(`\r\x1b[K[${'#'.repeat(filled)}${'-'.repeat(width - filled)}]${text}`);
  }

  /** Ends the bar's line on a terminal. */
  end(): void {
    if (this.tty && this.done > 0) this.tty.write('\n');
  }
}

/** The statuses of runs that happened (a discarded combination did not run). */
const RAN_STATUSES = RUN_STATUSES.filter((status) => status !== 'discarded');

/** The runs of a batch counted by status, and the one-line summary `batch` prints at its end. */
export class Tally {
  private readonly counts: Record<RunStatus, number> = { ok: 0, limit: 0, timeout: 0, error: 0, discarded: 0 };
  private collisions = 0;

  add(row: BatchRow): void {
    this.counts[row.status]++;
    if (row.collision) this.collisions++;
  }

  /** `12 runs (3 ok, 9 limit, 0 timeout, 0 error; 1 with a collision)`, with what was there before and what was discarded. */
  summary(already: number, csvFile: string): string {
    const ran = RAN_STATUSES.reduce((sum, status) => sum + this.counts[status], 0);
    const discarded = this.counts.discarded;
    const counts = RAN_STATUSES.map((status) => `${this.counts[status]} ${status}`).join(', ');
    return (
      `${ran} run${ran === 1 ? '' : 's'} (${counts}; ${this.collisions} with a collision)` +
      (already > 0 ? `, ${already} already in ${csvFile}` : '') +
      (discarded > 0 ? `, ${discarded} discarded by the scenario's ValueConstraintGroups` : '')
    );
  }
}
