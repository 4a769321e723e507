import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { runBounded } from '../support/hostile';
import { temporaryWorkspace } from '../support/workspace';

describe('cli: reuse blow-up', function () {
  this.timeout(120_000);

  it('a group imported twice at each of 20 levels is an error naming the chain, not an out-of-memory crash', () => {
    const files: Record<string, string> = { 'l20.xosc': scenario(simpleGroup('G')) };
    for (let level = 0; level < 20; level++) {
      // G holds two groups that each import G of the next level, so G doubles at every level.
      const half = (name: string) => outerGroup(name, 'car', [{ file: `l${level + 1}.xosc`, groups: [{ name: 'G' }] }]);
      const group = `        <ManeuverGroup name="G" maximumExecutionCount="1">\n          <Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>\n${half('X')}${half('Y')}        </ManeuverGroup>\n`;
      files[`l${level}.xosc`] = scenario(group);
    }
    const root = temporaryWorkspace(files);
    const run = runBounded(['flatten', 'l0.xosc', '-o', 'out.xosc', '--max-output-size', '4M'], {
      cwd: root,
      timeoutMs: 60_000,
      heapMb: 256,
    });
    assert.ok(!run.timedOut, 'finished');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /would exceed 4,194,304 characters/);
    assert.match(run.stderr, /l\d+\.xosc -> l\d+\.xosc -> .*l20\.xosc/);
    assert.ok(!fs.existsSync(path.join(root, 'out.xosc')));
    // The same with the default bound: still an error, in bounded memory.
    const byDefault = runBounded(['check', 'l0.xosc'], { cwd: root, timeoutMs: 90_000, heapMb: 512 });
    assert.equal(byDefault.status, 1, byDefault.stderr.slice(-2000));
    assert.match(byDefault.stderr, /would exceed/);
  });

  it('references nested deeper than the bound are an error naming the chain', () => {
    const files: Record<string, string> = { 'd30.xosc': scenario(simpleGroup('Go')) };
    for (let level = 0; level < 30; level++)
      files[`d${level}.xosc`] = scenario(
        simpleGroup('Go').replace(
          '</ManeuverGroup>',
          '</ManeuverGroup>\n' + outerGroup('Car', 'car', [{ file: `d${level + 1}.xosc`, groups: [{ name: 'Go' }] }]),
        ),
      );
    const root = temporaryWorkspace(files);
    const run = runBounded(['check', 'd0.xosc', '--max-depth', '10'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /references nest deeper than 10 files: d0\.xosc -> d1\.xosc/);
    assert.equal(runBounded(['check', 'd0.xosc', '--max-depth', '40'], { cwd: root }).status, 0);
  });
});
