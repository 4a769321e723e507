import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { duplicateOuterGroupWording } from '../../../server/src/core/diagnostics/duplicateGroup';
import { Flattener } from '../../../server/src/core/flatten';
import { Problem } from '../../../server/src/core/problems';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { outerGroup, scenario, simpleGroup } from '../../support/fixtures';
import { temporaryWorkspace } from '../../support/workspace';

/** The duplicate-group problems of flattening `main` beside a simple.xosc holding groups G and H, with the text each covers. */
async function duplicateGroups(main: string): Promise<{ problem: Problem; text: string }[]> {
  const root = temporaryWorkspace({ 'simple.xosc': scenario(simpleGroup('G') + simpleGroup('H')), 'main.xosc': main });
  try {
    const result = await new Flattener(new ScenarioStore({ root })).flatten(diskRef(path.join(root, 'main.xosc')));
    return result.problems
      .filter((problem) => problem.code === 'duplicate-group')
      .map((problem) => {
        const lines = main.split('\n');
        const line = lines[problem.range.start.line];
        return { problem, text: line.slice(problem.range.start.character, problem.range.end.character) };
      });
  } finally {
    fs.rmSync(root, { recursive: true, force: true });
  }
}

describe('diagnostics: duplicate-group in an Act of a main', () => {
  it('says which copies flattening names alike, and that esmini runs both', () => {
    assert.deepEqual(duplicateOuterGroupWording('Cut', 'A', ['G']), {
      severity: 'information',
      code: 'duplicate-group',
      message:
        "another ManeuverGroup of Act 'A' is already named 'Cut': flattening names the copies of both 'Cut.G' (the standard wants the names of one Act unique; esmini runs both groups, and a reference to the name takes the first)",
      hint: 'give each ManeuverGroup of the Act a name of its own',
    });
    assert.doesNotMatch(duplicateOuterGroupWording('Cut', 'A', []).message, /copies/);
  });

  it('flags the second of two groups of one name in one Act, at its name, the first as related', async () => {
    const main = scenario(
      outerGroup('Cut', 'car', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]) +
        outerGroup('Cut', 'truck', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]),
      ['ego', 'car', 'truck'],
    );
    const found = await duplicateGroups(main);
    assert.equal(found.length, 1, JSON.stringify(found));
    const [{ problem, text }] = found;
    assert.equal(text, 'Cut');
    assert.equal(
      problem.range.start.line,
      main
        .split('\n')
        .map((line) => line.includes('name="Cut"'))
        .lastIndexOf(true),
    );
    assert.match(problem.message, /already named 'Cut': flattening names the copies of both 'Cut\.G'/);
    assert.equal(problem.related?.[0].message, 'the first group of that name in the Act');
    assert.equal(
      problem.related?.[0].range.start.line,
      main.split('\n').findIndex((line) => line.includes('name="Cut"')),
    );
  });

  it('flags groups of one name importing different groups, and a plain group named as an importing one', async () => {
    const different = await duplicateGroups(
      scenario(
        outerGroup('Cut', 'car', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]) +
          outerGroup('Cut', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'H' }] }]),
      ),
    );
    assert.equal(different.length, 1);
    assert.doesNotMatch(different[0].problem.message, /copies/);
    const plain = await duplicateGroups(
      scenario(simpleGroup('Cut') + outerGroup('Cut', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }])),
    );
    assert.equal(plain.length, 1);
  });

  it('leaves groups of distinct names, groups of one name in two Acts, and two plain groups of one name', async () => {
    const distinct = scenario(
      outerGroup('Cut', 'car', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]) +
        outerGroup('Cut2', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]),
    );
    assert.deepEqual(await duplicateGroups(distinct), []);
    const twoActs = distinct.replace(
      outerGroup('Cut2', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]),
      `      </Act>\n      <Act name="B">\n${outerGroup('Cut', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }])}`,
    );
    assert.notEqual(twoActs, distinct);
    assert.deepEqual(await duplicateGroups(twoActs), []);
    const plain = scenario(
      simpleGroup('Cut') + simpleGroup('Cut') + outerGroup('Other', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'G' }] }]),
    );
    assert.deepEqual(await duplicateGroups(plain), []);
  });
});
