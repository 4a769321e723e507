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
});
