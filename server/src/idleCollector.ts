import * as v8 from 'node:v8';
import * as vm from 'node:vm';

/**
 * Runs one full, compacting garbage collection once the editor has been quiet for a while. Every
 * edit re-parses its file, and V8 otherwise keeps the memory of a burst of edits long after it is
 * garbage; a collection at rest gives it back without costing any request its latency.
 */
export class IdleCollector {
  private timer: NodeJS.Timeout | undefined;
  private readonly collect: (() => void) | undefined;

  constructor(private readonly quietMs = 1500) {
    try {
      v8.setFlagsFromString('--expose-gc');
      this.collect = vm.runInNewContext('gc') as () => void;
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
  }
}
