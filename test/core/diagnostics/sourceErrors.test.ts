import * as assert from 'node:assert/strict';
import { sourceErrorsCause, sourceErrorsWording, standsForCycleOnly } from '../../../server/src/core/diagnostics/sourceErrors';
import { Problem, ProblemCode, ZERO_RANGE } from '../../../server/src/core/problems';
import { diskRef } from '../../../server/src/core/sources';

function problem(code: ProblemCode, message: string, cause?: Problem['cause']): Problem {
  return { source: diskRef('/w/b.xosc'), range: ZERO_RANGE, severity: 'error', code, message, ...(cause ? { cause } : {}) };
}

describe('diagnostics: source-errors', () => {
  it('counts the errors of the referenced file and quotes the first', () => {
    const errors = [problem('cycle', 'reference cycle: a -> b -> a'), problem('xml', 'bad')];
    assert.deepEqual(sourceErrorsWording('b.xosc', errors), {
      severity: 'error',
      code: 'source-errors',
      message: "'b.xosc' has 2 errors: reference cycle: a -> b -> a",
    });
    assert.equal(sourceErrorsWording('b.xosc', errors.slice(0, 1)).message, "'b.xosc' has 1 error: reference cycle: a -> b -> a");
  });

  it('stands for a cycle alone when its chain of first errors ends in a file whose one error is a cycle, however deep', () => {
    const direct = problem('source-errors', '', sourceErrorsCause([problem('cycle', '')]));
    assert.equal(standsForCycleOnly(direct), true);
    // a -> b -> c -> a: the reference to b quotes b's one error, the reference to c, whose one error is the cycle.
    const throughAnother = problem('source-errors', '', sourceErrorsCause([direct, problem('xml', '')]));
    assert.deepEqual(throughAnother.cause, { code: 'cycle', among: 1 });
    assert.equal(standsForCycleOnly(throughAnother), true);
    assert.equal(standsForCycleOnly(problem('source-errors', '', sourceErrorsCause([problem('cycle', ''), problem('xml', '')]))), false);
    assert.equal(standsForCycleOnly(problem('source-errors', '', sourceErrorsCause([problem('xml', '')]))), false);
  });
});
