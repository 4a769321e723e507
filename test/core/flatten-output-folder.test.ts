import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { repoRoot } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

/** The composed fixture of semantics-flatten: its imported group needs a catalog location carried into the output. */
const fixtureDir = path.join(repoRoot, 'test', 'fixtures', 'semantics');

function fixtureWorkspace(): string {
  const files: Record<string, string> = {};
  const walk = (directory: string) => {
    for (const entry of fs.readdirSync(directory, { withFileTypes: true })) {
      const full = path.join(directory, entry.name);
      if (entry.isDirectory()) walk(full);
      else files[path.relative(fixtureDir, full)] = fs.readFileSync(full, 'utf8');
    }
  };
  walk(fixtureDir);
  return temporaryWorkspace(files);
}

describe('core: one Flattener flattening a main file into several output folders', () => {
  it('writes the carried catalog directories relative to each output, not to the first one', async () => {
    const root = fixtureWorkspace();
    const flattener = new Flattener(new ScenarioStore({ scenarioPath: [], root }));
    const main = diskRef(path.join(root, 'main.xosc'));
    const directories = async (outputPath: string) => {
      const result = await flattener.flatten(main, { outputPath });
      assert.ok(result.text, result.problems.map((problem) => problem.message).join('\n'));
      return [...result.text.matchAll(/<Directory path="([^"]*Maneuvers)"\/>/g)].map((match) => match[1]);
    };
    assert.deepEqual(await directories(path.join(root, 'out', 'deeper', 'result.xosc')), ['../../catalogs/Maneuvers']);
    assert.deepEqual(await directories(path.join(root, 'result.xosc')), ['catalogs/Maneuvers']);
    assert.deepEqual(await directories(path.join(root, 'out', 'deeper', 'again.xosc')), ['../../catalogs/Maneuvers']);
  });
});
