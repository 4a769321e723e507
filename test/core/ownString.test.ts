import * as assert from 'node:assert/strict';
import * as v8 from 'node:v8';
import * as vm from 'node:vm';
import { ownString } from '../../server/src/core/text';

function collect(): void {
  v8.setFlagsFromString('--expose-gc');
  (vm.runInNewContext('gc') as () => void)();
  // V8 rejects code caches made under other flags: the later tests of this process load the CLI's cached bundles.
  v8.setFlagsFromString('--no-expose-gc');
}

/** The heap held, after a full collection, while `keep` is kept: a value read from a 32 MB text, the text itself dropped. */
function heldWith(keep: (text: string) => string): { bytes: number; kept: string } {
  let text: string | undefined = 'ParameterReference key="x" '.repeat(1_200_000);
  const kept = keep(text);
  text = undefined;
  collect();
  return { bytes: v8.getHeapStatistics().used_heap_size, kept };
}

describe('core: ownString', () => {
  it('keeps the characters of a value, not the text it was read from', () => {
    collect();
    const before = v8.getHeapStatistics().used_heap_size;
    const owned = heldWith((text) => ownString(text.slice(27, 54)));
    assert.ok(owned.bytes - before < 4_000_000, `its own string keeps ${owned.bytes - before} bytes`);
    assert.equal(owned.kept, 'ParameterReference key="x" ');
    // The control: a plain slice of 27 characters keeps the whole 32 MB text alive (a V8 sliced string).
    const sliced = heldWith((text) => text.slice(27, 54));
    assert.ok(sliced.bytes - before > 20_000_000, `a slice keeps ${sliced.bytes - before} bytes`);
    assert.equal(sliced.kept, owned.kept);
    assert.equal(ownString('short'), 'short');
  });
});
