import * as assert from 'node:assert/strict';
import { constants, PerformanceEntry, PerformanceObserver } from 'node:perf_hooks';
import { IdleCollector } from '../../server/src/idleCollector';

/** Counts the full (mark-compact) collections while `run` goes on and a little after. */
async function majorCollectionsDuring(run: () => void): Promise<number> {
  let count = 0;
  const observer = new PerformanceObserver((list) => {
    for (const entry of list.getEntries()) {
      const detail = (entry as PerformanceEntry & { detail?: { kind?: number } }).detail;
      if (detail?.kind === constants.NODE_PERFORMANCE_GC_MAJOR) count++;
    }
  });
  observer.observe({ entryTypes: ['gc'] });
  run();
  await new Promise((resolve) => setTimeout(resolve, 50));
  observer.disconnect();
  return count;
}

describe('server: garbage collection under heap pressure', () => {
  it('a used heap past the bound gets one full collection; the bound then follows what is live', async () => {
    // A floor of one byte: any heap is past it, so the first edit collects; the bound becomes twice the live heap.
    const collector = new IdleCollector(60_000, 1);
    const first = await majorCollectionsDuring(() => collector.touch());
    assert.ok(first >= 1, `a full collection ran (${first})`);
    const second = await majorCollectionsDuring(() => collector.touch());
    assert.equal(second, 0, 'the next edit finds the heap within twice what the collection kept');
  });

  it('a heap within the bound is left to V8', async () => {
    const collector = new IdleCollector(60_000, 1024 * 1024 * 1024);
    assert.equal(await majorCollectionsDuring(() => collector.touch()), 0);
  });
});
