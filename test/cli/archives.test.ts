import * as assert from 'node:assert/strict';
import JSZip from 'jszip';
import { assertNoTrace, mainOf, outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { rawZip, runBounded } from '../support/hostile';
import { temporaryWorkspace } from '../support/workspace';

describe('cli: hostile archives', function () {
  this.timeout(60_000);

  it('refuses entries that share one compressed stream, without inflating each of them', () => {
    const zeros = new Uint8Array(8 * 1024 * 1024);
    const aliases = Array.from({ length: 300 }, (_, index) => ({ name: `s${index}.xosc`, of: 1 }));
    const root = temporaryWorkspace({
      'bomb.mosc': rawZip(
        [
          { name: 'main.xosc', data: mainOf('s0.xosc') },
          { name: 'pad.xosc', data: zeros, deflate: true },
        ],
        aliases,
      ),
    });
    const run = runBounded(['check', 'bomb.mosc'], { cwd: root, timeoutMs: 15_000, heapMb: 128 });
    assert.ok(!run.timedOut, `finished in ${run.ms} ms`);
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /overlap in the archive/);
    assertNoTrace(run.stderr);
  });

  it('bounds what one run unpacks from all packages together, not per package', async () => {
    // Four packages of 3 MB each (a few KB compressed): each within any bound, together over 8M.
    const padding = `<!-- ${'x'.repeat(3 * 1024 * 1024)} -->`;
    const files: Record<string, Uint8Array | string> = {};
    const groups: string[] = [];
    for (let index = 0; index < 4; index++) {
      const zip = new JSZip();
      zip.file('main.xosc', scenario(simpleGroup('Go')).replace('</OpenSCENARIO>', `${padding}</OpenSCENARIO>`));
      files[`p${index}.mosc`] = await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
      groups.push(outerGroup(`Car${index}`, 'car', [{ file: `p${index}.mosc`, groups: [{ name: 'Go' }] }]));
    }
    files['main.xosc'] = scenario(groups.join(''));
    const root = temporaryWorkspace(files);
    const within = runBounded(['check', 'main.xosc', '--max-unpacked-size', '16M'], { cwd: root });
    assert.equal(within.status, 0, within.stderr);
    const over = runBounded(['check', 'main.xosc', '--max-unpacked-size', '8M'], { cwd: root });
    assert.equal(over.status, 1, over.stderr);
    assert.match(over.stderr, /exceed the 8388608 bytes that one run may unpack from all packages together/);
    assert.match(over.stderr, /--max-unpacked-size/);
  });

  for (const [label, second] of [
    ['main.xosc twice', 'main.xosc'],
    ['main.xosc and ./main.xosc', './main.xosc'],
  ]) {
    it(`refuses a package holding ${label}`, () => {
      const evil = mainOf('missing.xosc');
      const root = temporaryWorkspace({
        'dup.mosc': rawZip([
          { name: 'main.xosc', data: scenario(simpleGroup('Go')) },
          { name: second, data: evil },
        ]),
      });
      const run = runBounded(['flatten', 'dup.mosc'], { cwd: root });
      assert.equal(run.status, 1, run.stderr);
      assert.match(run.stderr, /holds the entry 'main\.xosc' twice/);
      assert.equal(run.stdout, '', 'nothing was flattened from either copy');
    });
  }
});
