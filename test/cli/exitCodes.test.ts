import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { repoRoot } from '../support/paths';

describe('cli: messages', () => {
  it('an internal error exits with 4, not with 3 (could not write)', async () => {
    const errors: string[] = [];
    const code = await main(['--version'], {
      out: () => {
        throw new Error('a bug');
      },
      err: (text) => errors.push(text),
    });
    assert.equal(code, 4);
    assert.match(errors.join('\n'), /internal error: .*a bug/);
    assert.match(fs.readFileSync(path.join(repoRoot, 'docs', 'cli.md'), 'utf8'), /\| 4 \| internal error/);
  });

  it("a value that begins with '-' is named with how to give it, and run's --seed is bounded as esmini reads it (both were esmini's or node's bare words)", async () => {
    const said = async (args: string[]): Promise<[number, string]> => {
      const errors: string[] = [];
      const code = await main(args, { out: () => undefined, err: (text) => errors.push(text) });
      return [code, errors.join('\n')];
    };
    // node's parseArgs said only "Option '--duration' argument is ambiguous."
    const [durationCode, duration] = await said(['run', 'no-such.xosc', '--duration', '-5']);
    assert.equal(durationCode, 2);
    assert.match(
      duration,
      /--duration is followed by '-5', which begins with '-' as an option does: if it is --duration's value, write --duration=-5/,
    );
    assert.match((await said(['run', 'no-such.xosc', '--duration=-5']))[1], /--duration takes a positive number of seconds, not '-5'/);
    assert.match((await said(['vary', 'no-such.xosc', '--index', '-1']))[1], /--index is followed by '-1'.*write --index=-1/);
    // The shared options' parser said "-o needs a value" of a value it had.
    const [outputCode, output] = await said(['flatten', 'no-such.xosc', '-o', '-x.xosc']);
    assert.equal(outputCode, 2);
    assert.match(output, /-o is followed by '-x\.xosc'.*write --output=-x\.xosc/);
    assert.match((await said(['flatten', 'no-such.xosc', '-o']))[1], /-o needs a value/);
    // esmini reads --seed into an unsigned int with std::stoul: past 2^32 - 1 it stopped with "Exception: stoul", exit 3.
    for (const seed of ['99999999999999999999', '4294967296']) {
      const [seedCode, seedSaid] = await said(['run', 'no-such.xosc', '--seed', seed]);
      assert.equal(seedCode, 2);
      assert.match(
        seedSaid,
        new RegExp(`--seed takes a whole number from 0 to 4294967295 \\(esmini's seed is an unsigned int\\), not '${seed}'`),
      );
    }
  });
});
