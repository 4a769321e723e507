import { strict as assert } from 'node:assert';
import { settled, shownFixed, shownValue } from '../../server/src/debug/watchExpression';

describe('debug: numbers of a run as the user reads them', () => {
  it('rounds a time in every view from one settled value, so a stop and an evaluation of `time` agree', () => {
    // esmini's clock is a sum of 0.0001 s steps; the 4,450th lands just under 0.445 and would round down alone.
    let time = 0;
    for (let step = 0; step < 4450; step++) time += 0.0001;
    assert.ok(time < 0.445, `the sum is ${time}`);
    assert.equal(time.toFixed(2), '0.44');
    assert.equal(settled(time), 0.445);
    assert.equal(shownValue(time), '0.445');
    assert.equal(shownFixed(time), Number(shownValue(time)).toFixed(2));
    assert.equal(shownFixed(time), '0.45');
  });

  it('holds that agreement at every step of a run of 10 s', () => {
    let time = 0;
    for (let step = 1; step <= 100_000; step++) {
      time += 0.0001;
      if (shownFixed(time) !== Number(shownValue(time)).toFixed(2))
        assert.fail(`step ${step}: ${shownFixed(time)} against ${shownValue(time)}`);
    }
  });

  it("shows no number as '—' and integers and words unchanged", () => {
    assert.equal(shownFixed(undefined), '—');
    assert.equal(shownFixed(Number.NaN), '—');
    assert.equal(shownFixed(2.5, 3), '2.500');
    assert.equal(shownValue(3), '3');
    assert.equal(shownValue(true), 'true');
    assert.equal(shownValue('ego'), 'ego');
  });
});
