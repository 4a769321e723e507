import * as assert from 'node:assert/strict';
import { markupFreeEdit } from '../../server/src/core/xml';

/** The definition: the longest common prefix, then the longest common suffix not overlapping it, compared one character at a time. */
function differingRegion(old: string, text: string) {
  let prefix = 0;
  const shorter = Math.min(old.length, text.length);
  while (prefix < shorter && old[prefix] === text[prefix]) prefix++;
  let suffix = 0;
  while (suffix < shorter - prefix && old[old.length - 1 - suffix] === text[text.length - 1 - suffix]) suffix++;
  return { prefix, removedEnd: old.length - suffix, insertedEnd: text.length - suffix };
}

describe('markupFreeEdit (chunked comparison)', () => {
  it('finds the same differing region as a comparison of every character, on large and small texts', () => {
    let seed = 7;
    const random = (n: number) => {
      seed = (seed * 1103515245 + 12345) % 2 ** 31;
      return seed % n;
    };
    const sizes = [0, 1, 5, 1023, 1024, 1025, 3000, 70_000];
    let checked = 0;
    for (const size of sizes) {
      // Repetitive text, so that equal chunks also occur away from the edit.
      const old = Array.from({ length: size }, (_, i) => 'ab c'[i % 4]).join('');
      for (let round = 0; round < 40; round++) {
        const at = random(size + 1);
        const removed = Math.min(size - at, random(4));
        const inserted = Array.from({ length: random(4) }, () => 'abcz'[random(4)]).join('');
        const text = old.slice(0, at) + inserted + old.slice(at + removed);
        assert.deepEqual(
          markupFreeEdit(old, text),
          differingRegion(old, text),
          `size ${size}, at ${at}, removed ${removed}, inserted '${inserted}'`,
        );
        checked++;
      }
    }
    assert.equal(checked, sizes.length * 40);
  });

  it('still refuses an edit that touches markup', () => {
    const old = `${'<A x="1"/>\n'.repeat(500)}`;
    assert.equal(markupFreeEdit(old, old.replace('x="1"/>\n<A', 'x="1"/><A')), undefined);
    const at = old.length - 200;
    assert.deepEqual(
      markupFreeEdit(old, old.slice(0, at) + old.slice(at).replace('x="1"', 'x="27"')),
      differingRegion(old, old.slice(0, at) + old.slice(at).replace('x="1"', 'x="27"')),
    );
  });
});
