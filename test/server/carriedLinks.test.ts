import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import { Flattener, LinkedReference } from '../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { editorGenerations } from '../support/generations';
import { temporaryFolder } from '../support/temporaryDirectory';

// G lists h without writing it: a key setting h has no default.
const simple = scenario(simpleGroup('G').replace('parameterAttributes="x, y"', 'parameterAttributes="x, y, h"'));

/** An outer group importing one group of a file with the given keys, on one line. */
function oneLine(name: string, keys: string[], file = 'simple.xosc', group = 'G'): string {
  const parameters = keys.map((key, index): [string, string] => [key, String(index + 5)]);
  return outerGroup(name, 'car', [{ file, groups: [{ name: group, parameters }] }]).replace(/\n\s*/g, '');
}

// References with and without problems of their own (unknown key, no default, missing file, unknown group), some
// sharing a line, so that problems of references the edit leaves alone move along the edited line.
const main = scenario(
  [
    oneLine('One', ['AbsoluteTargetSpeed.value']),
    oneLine('Two', ['AbsoluteTargetSpeed.valu']) + oneLine('Three', ['h', 'value']),
    oneLine('Four', ['value'], 'absent.xosc') + oneLine('Five', ['x']) + oneLine('Six', ['value'], 'simple.xosc', 'H'),
    oneLine('Seven', ['WorldPosition.y', 'entityRef']),
  ].join('\n') + '\n',
);

/** The offsets of every attribute value of a text (its raw value between the quotes). */
function valueRanges(text: string): { start: number; end: number }[] {
  return [...text.matchAll(/="([^"]*)"/g)].map((match) => ({
    start: (match.index ?? 0) + 2,
    end: (match.index ?? 0) + 2 + match[1].length,
  }));
}

const typed = fc.string({ unit: fc.constantFrom('1', '0', '.', '-', 'x', 'e', 'G', 'v', 'a', 'l', 'u'), maxLength: 4 });
// One edit in six puts back what it removes: a change that leaves the text as it was reads the same parse again.
const edit = fc.record({ which: fc.nat(), from: fc.nat(), length: fc.nat(3), inserted: typed, same: fc.nat(5) });

describe('server: the links of references an edit inside one value leaves alone', () => {
  const folder = temporaryFolder('m2s-carried-links-');
  fs.writeFileSync(path.join(folder, 'simple.xosc'), simple);
  const mainFile = path.join(folder, 'main.xosc');
  fs.writeFileSync(mainFile, main);

  it('carry over, the problems of the analysis equal those of the text read afresh', async () => {
    let reused = 0;
    await fc.assert(
      fc.asyncProperty(fc.array(edit, { minLength: 1, maxLength: 6 }), async (edits) => {
        const ref = diskRef(mainFile);
        const { generation, edited, fresh: afresh } = editorGenerations(folder);
        let current = main;
        edited(ref, current);
        const first = await generation().analyze(ref);
        // The problems to carry: those of references an edit leaves alone.
        for (const code of ['unknown-key', 'missing-file', 'unknown-group', 'no-default'])
          assert.ok(
            first.problems.some((problem) => problem.code === code),
            `${code} in ${first.problems.map((problem) => problem.code).join(', ')}`,
          );
        let links: LinkedReference[] = first.source.links;
        for (const { which, from, length, inserted: typedText, same } of edits) {
          const ranges = valueRanges(current);
          const range = ranges[which % ranges.length];
          const start = range.start + (from % (range.end - range.start + 1));
          const end = Math.min(range.end, start + length);
          const inserted = same === 0 ? current.slice(start, end) : typedText;
          current = current.slice(0, start) + inserted + current.slice(end);
          edited(ref, current);
          const incremental = await generation().analyze(ref);
          reused += incremental.source.links.filter((link) => links.includes(link)).length;
          links = incremental.source.links;
          const fresh = await afresh(ref, current);
          assert.deepEqual(
            JSON.parse(JSON.stringify(incremental.problems)),
            JSON.parse(JSON.stringify(fresh.problems)),
            `after replacing [${start}, ${end}) by '${inserted}'`,
          );
          assert.deepEqual(
            incremental.source.links.map((link) => [
              link.info.element.start,
              link.groups.map((group) => group.plan?.matches.map((match) => match.parameter.element.start)),
            ]),
            fresh.source.links.map((link) => [
              link.info.element.start,
              link.groups.map((group) => group.plan?.matches.map((match) => match.parameter.element.start)),
            ]),
            `the links after replacing [${start}, ${end}) by '${inserted}'`,
          );
        }
      }),
      { numRuns: 60 },
    );
    // References before the edit keep their link object: the carry is taken, not only allowed.
    assert.ok(reused > 100, `links carried over as they were: ${reused}`);
  });

  it('are linked again when the file they read changed', async () => {
    const ref = diskRef(mainFile);
    const simpleRef = diskRef(path.join(folder, 'simple.xosc'));
    const { store, generation, edited } = editorGenerations(folder);
    store.setOverlay(ref, main);
    const before = await generation().analyze(ref);
    assert.ok(!before.problems.some((problem) => problem.message.includes("'WorldPosition.y'")));
    // Edited in the editor: y is no longer listed. The main file's text stays (the same parse is read again) and
    // its references resolve as they did; the file they read is another source.
    const changed = simple.replace('parameterAttributes="x, y, h"', 'parameterAttributes="x, h"');
    edited(simpleRef, changed);
    edited(ref, main);
    // Read again first on its own (as its own diagnostics would), so the main file finds it among the shared sources.
    const flattener = generation();
    await flattener.source(simpleRef, []);
    const after = await flattener.analyze(ref);
    const freshStore = new ScenarioStore({ scenarioPath: [], root: folder });
    freshStore.setOverlay(ref, main);
    freshStore.setOverlay(simpleRef, changed);
    const fresh = await new Flattener(freshStore, 'asam', { version: 'auto' }).analyze(ref);
    assert.ok(after.problems.some((problem) => problem.code === 'unknown-key' && problem.message.includes("'WorldPosition.y'")));
    assert.deepEqual(JSON.parse(JSON.stringify(after.problems)), JSON.parse(JSON.stringify(fresh.problems)));
  });
});
