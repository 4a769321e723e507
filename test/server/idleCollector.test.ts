import * as assert from 'node:assert/strict';
import { constants, PerformanceEntry, PerformanceObserver } from 'node:perf_hooks';
import * as v8 from 'node:v8';
import { IdleCollector } from '../../server/src/idleCollector';

/**
 * Counts the collections of one kind while `run` goes on and over the next event-loop turns: the collector's
 * collection runs in an immediate, and its entry reaches the observer two turns later. Turns, not a time: on a
 * busy machine a 50 ms timer could fire before the queued collection ran.
 */
async function collectionsDuring(kind: number, run: () => void): Promise<number> {
  let count = 0;
  const observer = new PerformanceObserver((list) => {
    for (const entry of list.getEntries()) {
      const detail = (entry as PerformanceEntry & { detail?: { kind?: number } }).detail;
      if (detail?.kind === kind) count++;
    }
  });
  observer.observe({ entryTypes: ['gc'] });
  run();
  for (let turn = 0; turn < 10; turn++) await new Promise((resolve) => setImmediate(resolve));
  observer.disconnect();
  return count;
}

const majorCollectionsDuring = (run: () => void) => collectionsDuring(constants.NODE_PERFORMANCE_GC_MAJOR, run);
const scavengesDuring = (run: () => void) => collectionsDuring(constants.NODE_PERFORMANCE_GC_MINOR, run);

/** How full the young generation's current semi-space is, from 0 to 1. */
function youngFill(): number {
  const young = v8.getHeapSpaceStatistics().find((space) => space.space_name === 'new_space');
  assert.ok(young, 'V8 reports a new_space');
  return young.space_used_size / (young.space_used_size + young.space_available_size);
}

/** Allocates short-lived objects until the young generation is more than half full. */
function fillYoungGeneration(): void {
  let sink: unknown[] = [];
  for (let round = 0; youngFill() <= 0.5; round++) {
    sink = Array.from({ length: 1000 }, (_, i) => ({ round, i }));
    if (round > 1_000_000) throw new Error('the young generation never filled past half');
  }
  assert.ok(sink.length > 0);
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

  it('a young generation more than half full gets one scavenge between edits; a nearly empty one none', async () => {
    const collector = new IdleCollector(60_000, 1024 * 1024 * 1024);
    fillYoungGeneration();
    assert.ok((await scavengesDuring(() => collector.touch())) >= 1, 'a scavenge ran after the edit');
    assert.ok(youngFill() <= 0.5, `the scavenge emptied the young generation (${youngFill()})`);
    assert.equal(await scavengesDuring(() => collector.touch()), 0, 'no scavenge for a young generation at most half full');
  });
});
