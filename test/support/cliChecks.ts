import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import { main } from '../../server/src/cli';

/**
 * Runs the CLI in this process as a user would after composing a main: `check FILE --format json` must find no
 * error and no warning, then `flatten FILE -o FLAT` must succeed. Returns the flattened text.
 */
export async function checkCleanAndFlatten(file: string, flat: string): Promise<string> {
  const errors: string[] = [];
  const output: string[] = [];
  const code = await main(['check', file, '--format', 'json'], { out: (line) => output.push(line), err: (line) => errors.push(line) });
  assert.equal(code, 0, `${output.join('\n')}\n${errors.join('\n')}`);
  assert.match(output.join('\n'), /"errors": 0/);
  assert.match(output.join('\n'), /"warnings": 0/, output.join('\n'));
  assert.equal(await main(['flatten', file, '-o', flat, '-q'], { out: () => {}, err: (line) => errors.push(line) }), 0, errors.join('\n'));
  return fs.readFileSync(flat, 'utf8');
}
