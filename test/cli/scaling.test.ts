import * as assert from 'node:assert/strict';
import { scalingRatio } from '../support/hostile';

describe('cli: parsing and resolution scale linearly', function () {
  this.timeout(600_000);
  // Ratios of times at two sizes, best of three runs each, in a child process: a linear operation
  // gives about 4 for 4x the size, a quadratic one 16. The bound of 10 leaves room for a busy machine
  // and for the garbage collector, whose share grows with the heap.
  it('duplicate attributes: 4x the attributes take under 10x the time', () => {
    const { ratio, smallMs, largeMs } = scalingRatio('attributes', 50_000);
    assert.ok(ratio < 10, `50,000 attributes: ${smallMs.toFixed(0)} ms; 200,000: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });

  it('end tags that match nothing: 4x the tags take under 10x the time', () => {
    const { ratio, smallMs, largeMs } = scalingRatio('end-tags', 250_000);
    assert.ok(ratio < 10, `250,000 end tags: ${smallMs.toFixed(0)} ms; 1,000,000: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });

  it('nested packages: twice the levels take under 6x the time (the bytes unpacked grow as n^2; n^4 was the bug)', () => {
    const { ratio, smallMs, largeMs } = scalingRatio('nested-packages', 100, 2);
    assert.ok(ratio < 6, `100 levels: ${smallMs.toFixed(0)} ms; 200: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });
});
