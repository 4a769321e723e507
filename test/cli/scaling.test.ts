import * as assert from 'node:assert/strict';
import { OUTPUT_CHECKS, SEMANTIC_CHECKS } from '../../server/src/core/semantics';
import { checkScalingTimes, scalingRatio } from '../support/hostile';

describe('cli: parsing and resolution scale linearly', function () {
  this.timeout(600_000);
  // Ratios of CPU times at two sizes, best of three runs each, in a child process: a linear operation
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

  it("200,000 File entries in a vehicle's Properties (4 MB): 4x the siblings take under 10x the time to check and flatten", () => {
    const { ratio, smallMs, largeMs } = scalingRatio('sibling-files', 50_000);
    assert.ok(ratio < 10, `50,000 Files: ${smallMs.toFixed(0)} ms; 200,000: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });

  // Every check of a document alone, on a scenario with 200 and then 800 siblings of each kind a check
  // walks (ten times as many of the small ones; test/support/checkScaling.ts): a check added to
  // SEMANTIC_CHECKS or OUTPUT_CHECKS is measured without a word here. A few milliseconds are mostly noise
  // on a busy machine (and a small heap fits the processor's caches), so the smaller time counts as at
  // least 10 ms: a check that does real work per pair of 8,000 siblings still shows; the 200,000-sibling file
  // above is the bound for the cheaper ones.
  it('every check: 4x the siblings take under 10x the time, each check alone', () => {
    const times = checkScalingTimes(200);
    const names = new Set(times.map((time) => time.name));
    for (const name of [...SEMANTIC_CHECKS.map((entry) => entry.name), ...OUTPUT_CHECKS.map((entry) => `output: ${entry.name}`)])
      assert.ok(names.has(name), `the check '${name}' was not measured`);
    const report = times.map((time) => `${time.name}: ${time.smallMs.toFixed(1)} -> ${time.largeMs.toFixed(1)} ms`).join('\n');
    const slow = times.filter((time) => time.largeMs / Math.max(time.smallMs, 10) >= 10);
    assert.deepEqual(
      slow.map((time) => time.name),
      [],
      `not linear:\n${report}`,
    );
  });
});
