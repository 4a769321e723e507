import * as assert from 'node:assert/strict';
import { collisionNotice } from '../../client/src/library/collisionNotice';

/** Issue 28: after Insert into Main, a notice names the scripted actors that touch in esmini's run; it never blocks the edit. */
describe('Insert into Main: the notice of scripted actors that touch (client/library/collisionNotice)', () => {
  it('names up to three collisions and counts the rest, saying what to do', () => {
    const at = (a: string, b: string, time: number) => ({ entities: [a, b] as [string, string], time });
    assert.equal(
      collisionNotice('lead-brake', { ran: true, message: '', collisions: [at('adversary', 'lead', 4.45), at('adversary', 'lead', 8.6)] }),
      "After inserting library:lead-brake, esmini's run has scripted actors touch: adversary and lead at 4.45 s, adversary and lead at 8.6 s. A scripted car neither brakes nor steers for another: move one, or change its speed or trigger (docs/library.md).",
    );
    const four = collisionNotice('cut-in', {
      ran: true,
      message: '',
      collisions: [at('a', 'b', 1), at('a', 'c', 2), at('b', 'c', 3), at('c', 'd', 4)],
    });
    assert.match(four ?? '', /: a and b at 1 s, a and c at 2 s, b and c at 3 s and 1 more\. /);
  });

  it('gives no notice where nothing touches or no run happened', () => {
    assert.equal(collisionNotice('cut-in', { ran: true, message: 'esmini: 0 errors', collisions: [] }), undefined);
    assert.equal(collisionNotice('cut-in', { ran: false, message: 'no esmini', collisions: [] }), undefined);
  });
});
