import * as v8 from 'node:v8';
import * as vm from 'node:vm';

/** Below this much used heap the server leaves collection to V8; above it, a burst of edits gets a collection of its own. */
const PRESSURE_FLOOR_BYTES = 128 * 1024 * 1024;

/**
 * Runs one full, compacting garbage collection once the editor has been quiet for a while. Every
 * edit re-parses its file, and V8 otherwise keeps the memory of a burst of edits long after it is
 * garbage; a collection at rest gives it back without costing any request its latency.
 *
 * During a burst (typing without pause in a 15,000-line file), V8 lets the heap grow to three or four
 * times what is live before it collects in full; when the used heap passes a bound (twice what the last
 * collection kept, at least PRESSURE_FLOOR_BYTES) one full collection runs before the next edit is analysed.
 */
export class IdleCollector {
  private timer: NodeJS.Timeout | undefined;
  private readonly collect: ((options?: { type: 'minor' | 'major' }) => void) | undefined;
  private pressureBound: number;
  private pressureCollectionQueued = false;

  constructor(
    private readonly quietMs = 1500,
    private readonly pressureFloorBytes = PRESSURE_FLOOR_BYTES,
  ) {
    this.pressureBound = pressureFloorBytes;
    try {
      v8.setFlagsFromString('--expose-gc');
      this.collect = vm.runInNewContext('gc') as (options?: { type: 'minor' | 'major' }) => void;
    } catch {
      this.collect = undefined;
    }
  }

  /** Notes activity: the collection waits until `quietMs` after the last call. */
  touch(): void {
    if (!this.collect) return;
    if (this.timer) clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      this.timer = undefined;
      this.collectCompacting();
    }, this.quietMs);
    this.timer.unref();
    this.relievePressure();
  }

  /**
   * Used heap past the bound: one full collection, queued behind what is already running. Otherwise,
   * a young generation more than half full: one scavenge now, between edits, where it copies only the
   * last analysis and overlaps the diagnostics delay, rather than inside the next analysis, where it
   * would copy the previous analysis and the one being built and hold the edit's diagnostics up.
   */
  private relievePressure(): void {
    if (this.pressureCollectionQueued) return;
    const full = v8.getHeapStatistics().used_heap_size > this.pressureBound;
    if (!full && !youngGenerationHalfFull()) return;
    this.pressureCollectionQueued = true;
    setImmediate(() => {
      this.pressureCollectionQueued = false;
      if (full) {
        this.collect?.();
        this.rebound();
      } else {
        this.collect?.({ type: 'minor' });
      }
    });
  }

  /** The next bound: twice what is live now, so a workspace whose live heap is large is not collected on every edit. */
  private rebound(): void {
    this.pressureBound = Math.max(this.pressureFloorBytes, 2 * v8.getHeapStatistics().used_heap_size);
  }

  /**
   * A full collection alone frees the objects but keeps every page that still holds one live object
   * (after many edits, most of the old generation); compacting moves the survivors together so the
   * emptied pages go back to the system. V8 offers no call for it, so the flag is on for this one collection.
   */
  private collectCompacting(): void {
    v8.setFlagsFromString('--compact-on-every-full-gc');
    try {
      this.collect?.();
    } finally {
      v8.setFlagsFromString('--no-compact-on-every-full-gc');
    }
    this.rebound();
  }
}

/** Whether the young generation's current semi-space is more than half used. */
function youngGenerationHalfFull(): boolean {
  const young = v8.getHeapSpaceStatistics().find((space) => space.space_name === 'new_space');
  return young !== undefined && young.space_used_size > young.space_available_size;
}
