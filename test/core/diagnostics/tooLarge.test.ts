import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { TOO_LARGE, tooLargeWording } from '../../../server/src/core/diagnostics/tooLarge';
import { Flattener } from '../../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { outerGroup, scenario, simpleGroup } from '../../support/fixtures';
import { temporaryWorkspace } from '../../support/workspace';

describe('diagnostics: too-large', () => {
  it('names the bound, the count so far and the chain that multiplies', () => {
    assert.deepEqual(tooLargeWording('main.xosc', 4_194_304, 5_000_000, 'main.xosc -> a.xosc'), {
      severity: 'error',
      code: 'too-large',
      message:
        'the flattened main.xosc would exceed 4,194,304 characters (5,000,000 so far): groups imported through main.xosc -> a.xosc multiply at each level',
      hint: 'import fewer copies, or raise the bound with --max-output-size',
    });
    assert.equal(TOO_LARGE.severity, 'error');
  });

  it('is what flattening past the bound reports, on the reference', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('G')),
      'main.xosc': scenario(outerGroup('Outer', 'car', [{ file: 'simple.xosc', groups: [{ name: 'G' }, { name: 'G' }] }])),
    });
    try {
      const store = new ScenarioStore({ root, limits: { maxFlattenedChars: 200 } });
      const result = await new Flattener(store).flatten(diskRef(path.join(root, 'main.xosc')));
      const problem = result.problems.find((candidate) => candidate.code === 'too-large');
      assert.ok(problem, result.problems.map((candidate) => candidate.message).join('\n'));
      assert.equal(problem.severity, TOO_LARGE.severity);
      assert.match(problem.message, /^the flattened .*main\.xosc would exceed 200 characters \([\d,]+ so far\): groups imported through /);
      assert.equal(result.text, undefined);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});
