import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { UNKNOWN_CATALOG } from '../../../server/src/core/diagnostics/unknownCatalog';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { parseXml } from '../../../server/src/core/xml';
import { esminiBinary, esminiRoads, requireEsmini } from '../../support/esmini';
import { runBounded } from '../../support/processes';
import { twoCatalogs } from '../../support/twoCatalogs';
import { temporaryWorkspace } from '../../support/workspace';

/** twoCatalogs' files with first/Vehicles.xosc holding the Catalog VehicleCatalog, and second/VehicleCatalog.xosc as `second` makes it. */
function catalogInAnotherFile(entry: string, second: (text: string) => string | undefined): Record<string, string> {
  const files = twoCatalogs(entry, 'Vehicles.xosc');
  const text = second(files['second/VehicleCatalog.xosc']);
  if (text === undefined) delete files['second/VehicleCatalog.xosc'];
  else files['second/VehicleCatalog.xosc'] = text;
  return files;
}

async function problemsOf(root: string, simulator?: 'esmini', more: string[] = []) {
  const file = path.join(root, 'scenario.xosc');
  const semantics = await analyzeDocument(
    diskRef(file),
    parseXml(fs.readFileSync(file, 'utf8')),
    new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
    false,
    simulator,
  );
  const codes = ['unknown-catalog', 'unknown-catalog-entry', ...more];
  return semanticProblems(semantics).filter((problem) => codes.includes(problem.code));
}

async function esminiRun(root: string) {
  fs.copyFileSync(path.join(esminiRoads, 'straight_500m.xodr'), path.join(root, 'straight.xodr'));
  return runBounded(
    esminiBinary,
    ['--headless', '--osc', 'scenario.xosc', '--fixed_timestep', '0.05', '--disable_log'],
    { cwd: root },
    60_000,
  );
}

describe('diagnostics: unknown-catalog', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(UNKNOWN_CATALOG.code, 'unknown-catalog');
    assert.equal(UNKNOWN_CATALOG.severity, 'error');
  });

  it('a Catalog only in a file of another name: esmini, which looks for NAME.xosc, stops at it (an error for esmini, a warning otherwise)', async function () {
    requireEsmini(this);
    const root = temporaryWorkspace(catalogInAnotherFile('car_blue', () => undefined));
    try {
      const holder = path.join(root, 'first', 'Vehicles.xosc');
      const message = `the Catalog 'VehicleCatalog' is in ${holder}, but esmini looks a catalog up as the file VehicleCatalog.xosc: esmini stops at it ("Couldn't locate OpenSCENARIO file VehicleCatalog")`;
      assert.deepEqual(
        (await problemsOf(root, 'esmini')).map((problem) => [problem.severity, problem.message, problem.hint]),
        [['error', message, `rename ${holder} to VehicleCatalog.xosc`]],
      );
      assert.deepEqual(
        (await problemsOf(root)).map((problem) => problem.severity),
        ['warning'],
      );
      const refused = await esminiRun(root);
      assert.match(refused.output, /Couldn't locate OpenSCENARIO file VehicleCatalog/);
      assert.notEqual(refused.code, 0);
      // Named as esmini looks for it: nothing to say, and esmini runs it.
      fs.renameSync(holder, path.join(root, 'first', 'VehicleCatalog.xosc'));
      assert.deepEqual(await problemsOf(root, 'esmini'), []);
      const ran = await esminiRun(root);
      assert.equal(ran.code, 0, ran.output);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('NAME.xosc holding a Catalog of another name: esmini reads it all the same, which the warning names', async function () {
    requireEsmini(this);
    // car_red is only in second/VehicleCatalog.xosc, whose Catalog is named Cars: the standard does not find it there, esmini does.
    const root = temporaryWorkspace(
      catalogInAnotherFile('car_red', (text) => text.replace('<Catalog name="VehicleCatalog">', '<Catalog name="Cars">')),
    );
    try {
      const [holder, read] = [path.join(root, 'first', 'Vehicles.xosc'), path.join(root, 'second', 'VehicleCatalog.xosc')];
      const problems = await problemsOf(root);
      assert.deepEqual(
        problems.filter((problem) => problem.code === 'unknown-catalog').map((problem) => [problem.severity, problem.message]),
        [
          [
            'warning',
            `the Catalog 'VehicleCatalog' is in ${holder}, but esmini looks a catalog up as the file VehicleCatalog.xosc: esmini reads ${read} instead, whose Catalog is named 'Cars'`,
          ],
        ],
      );
      // The standard's catalog has no car_red; for esmini the entry is in the file it reads, so only the warning stays.
      assert.deepEqual(
        problems.map((problem) => problem.code),
        ['unknown-catalog', 'unknown-catalog-entry'],
      );
      assert.deepEqual(
        (await problemsOf(root, 'esmini')).map((problem) => [problem.code, problem.severity]),
        [['unknown-catalog', 'warning']],
      );
      const ran = await esminiRun(root);
      assert.equal(ran.code, 0, ran.output);
      // The entry esmini reads is checked as any other: a value for a parameter it does not declare.
      const scenario = path.join(root, 'scenario.xosc');
      const text = fs.readFileSync(scenario, 'utf8');
      fs.writeFileSync(
        scenario,
        text.replace(
          '<CatalogReference catalogName="VehicleCatalog" entryName="car_red"/>',
          '<CatalogReference catalogName="VehicleCatalog" entryName="car_red"><ParameterAssignments><ParameterAssignment parameterRef="Colour" value="red"/></ParameterAssignments></CatalogReference>',
        ),
      );
      assert.deepEqual(
        (await problemsOf(root, 'esmini', ['unknown-assigned-parameter'])).map((problem) => problem.code),
        ['unknown-catalog', 'unknown-assigned-parameter'],
      );
      fs.writeFileSync(scenario, text);
      // An entry the file esmini reads lacks: esmini fails on it, and the check says so for esmini.
      fs.writeFileSync(scenario, text.replace('entryName="car_red"', 'entryName="car_green"'));
      assert.deepEqual(
        (await problemsOf(root, 'esmini')).map((problem) => [problem.code, problem.severity, problem.message]),
        [
          ['unknown-catalog', 'warning', problems[0].message],
          [
            'unknown-catalog-entry',
            'error',
            `catalog 'VehicleCatalog' (${read}) has no entry named 'car_green'; it has: car_blue, car_red`,
          ],
        ],
      );
      const failed = await esminiRun(root);
      assert.match(failed.output, /car_green/);
      assert.notEqual(failed.code, 0);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});
