import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import { linksOfParse } from '../../server/src/core/flatten/carriedLinks';
import { diskRef } from '../../server/src/core/sources';
import { editorGenerations } from '../support/generations';
import { caseStudyDir, requireCorpus } from '../support/paths';

/** The offsets of the attribute values of a text (between the quotes): of ParameterReferences and entity names, of declarations, all. */
function valueRanges(text: string): Record<'likely' | 'declared' | 'any', { start: number; end: number }[]> {
  const of = (pattern: RegExp) =>
    [...text.matchAll(pattern)].map((match) => {
      const start = (match.index ?? 0) + match[0].length - match[1].length - 1;
      return { start, end: start + match[1].length };
    });
  return {
    likely: of(/<(?:ParameterReference key="[^"]*" value|ScenarioObject name|EntityRef entityRef)="([^"]*)"/g),
    declared: of(/<ParameterDeclaration name="\w+" parameterType="\w+" value="([^"]*)"/g),
    any: of(/="([^"]*)"/g),
  };
}

// The file's empty global declarations, given two parameters that override values and entity references can name.
const declarations =
  '<ParameterDeclarations><ParameterDeclaration name="speed" parameterType="string" value="10"/>' +
  '<ParameterDeclaration name="who" parameterType="string" value="police"/></ParameterDeclarations>';

// Digits and letters make values that do not fit their attribute; parameters and entity names read declarations elsewhere.
const typed = fc.oneof(
  fc.string({ unit: fc.constantFrom('1', '0', '.', '-', 'x', 'e', '$', 'v'), maxLength: 4 }),
  fc.constantFrom('hero', 'police', 'vehicle_0', 'vehicle_9', 'ego', '$speed', '$who'),
);
// One edit in two types over as many characters as it writes, where the value has them: nothing after it moves.
const edit = fc.record({ which: fc.nat(), where: fc.nat(3), from: fc.nat(), length: fc.nat(12), inserted: typed, over: fc.boolean() });

/** Issue 25: the analysis's checks of references an edit leaves alone are carried with their links, never drifting from a fresh analysis. */
describe("server: the reference checks carried over an edit (the paper's case study)", () => {
  const mainFile = path.join(caseStudyDir, 'main.xosc');

  it('equal those of the text analysed afresh after each of a sequence of edits', async function () {
    requireCorpus(this);
    // Up to 150 fresh analyses of a 577-line file with packages: generous for a loaded 2-core machine.
    this.timeout(600_000);
    const written = fs.readFileSync(mainFile, 'utf8');
    // Two overrides name them from the start (the first speed and the first entity reference a group is given).
    const original = written
      .replace('<ParameterDeclarations/>', declarations)
      .replace('key="AbsoluteTargetSpeed.value" value="6.8"', 'key="AbsoluteTargetSpeed.value" value="$speed"')
      .replace('key="entityRef" value="police"', 'key="entityRef" value="$who"');
    assert.notEqual(original, written);
    let carried = 0;
    let found = 0;
    await fc.assert(
      fc.asyncProperty(fc.array(edit, { minLength: 1, maxLength: 6 }), async (edits) => {
        const ref = diskRef(mainFile);
        const { generation, edited, fresh: afresh } = editorGenerations(caseStudyDir);
        let current = original;
        edited(ref, current);
        await generation().analyze(ref);
        for (const { which, where, from, length, inserted, over } of edits) {
          const ranges = valueRanges(current);
          const among = where === 0 ? ranges.any : where === 1 ? ranges.declared : ranges.likely;
          const range = among[which % among.length];
          const start = range.start + (from % (range.end - range.start + 1));
          const end = Math.min(range.end, start + (over ? inserted.length : length));
          current = current.slice(0, start) + inserted + current.slice(end);
          edited(ref, current);
          const flattener = generation();
          const source = await flattener.source(ref, []);
          const document = source.original?.document;
          assert.ok(document);
          carried += linksOfParse(document, source.links)?.checks?.results.filter((result) => result !== undefined).length ?? 0;
          const incremental = await flattener.analyze(ref);
          const fresh = await afresh(ref, current);
          found += fresh.problems.filter((problem) => ['undeclared-entity', 'schema-value'].includes(problem.code)).length;
          assert.deepEqual(
            JSON.parse(JSON.stringify(incremental.problems)),
            JSON.parse(JSON.stringify(fresh.problems)),
            `after replacing [${start}, ${end}) by '${inserted}'`,
          );
        }
      }),
      { numRuns: 25 },
    );
    // The carry is taken, and what it carries includes problems, not only their absence.
    assert.ok(carried > 100, `reference checks carried over: ${carried}`);
    assert.ok(found > 10, `entity and override value problems met: ${found}`);
  });
});
