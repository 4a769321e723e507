import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CATALOG_DIRECTORY, catalogDirectoryWording, catalogFolderWording } from '../../../server/src/core/diagnostics/catalogDirectory';
import { Flattener } from '../../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { roadScenario } from '../../support/fixtures';
import { temporaryWorkspace } from '../../support/workspace';

describe('diagnostics: catalog-directory', () => {
  it('names the kind and the path, and where it was looked for; an error with a scenario path and without one', () => {
    const hint =
      'correct the path, or add the folder that holds the catalogs to SCENARIO_PATH (--scenario-path, the modular2simple.scenarioPath setting)';
    assert.deepEqual(catalogDirectoryWording('ManeuverCatalog', 'missing'), {
      severity: 'error',
      code: 'catalog-directory',
      message:
        "the ManeuverCatalog directory 'missing' does not exist beside this file nor in SCENARIO_PATH, so the catalog references that need it resolve nowhere",
      hint,
    });
    assert.deepEqual(catalogDirectoryWording('ManeuverCatalog', 'missing', ['/shared']), {
      severity: 'error',
      code: 'catalog-directory',
      message:
        "the ManeuverCatalog directory 'missing' does not exist beside this file, and the SCENARIO_PATH folders searched for it (/shared) hold no catalog its references name",
      hint,
    });
    assert.equal(CATALOG_DIRECTORY.severity, 'error');
  });

  it('is what an analysis reports on a needed location whose folder is not there', async () => {
    const group = `<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><CatalogReference catalogName="ManeuverCatalog" entryName="Flip"/></ManeuverGroup>`;
    const text = roadScenario({ groups: [group] }).replace(
      '<CatalogLocations/>',
      '<CatalogLocations><ManeuverCatalog><Directory path="missing"/></ManeuverCatalog></CatalogLocations>',
    );
    const root = temporaryWorkspace({ 'main.xosc': text });
    try {
      const { problems } = await new Flattener(new ScenarioStore({ root })).analyze(diskRef(path.join(root, 'main.xosc')));
      const problem = problems.find((candidate) => candidate.code === 'catalog-directory');
      assert.ok(problem, problems.map((candidate) => candidate.code).join('\n'));
      const { severity, code, message, hint } = problem;
      assert.deepEqual({ severity, code, message, hint }, catalogDirectoryWording('ManeuverCatalog', 'missing'));
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  // The pattern of the corpus (esmini's synchronize.xosc: ../xosc/Catalogs/{Maneuvers,Vehicles,Controllers}; ScenarioRunner's
  // CatalogExample.xosc: 'catalogs' for six kinds) copied without its catalogs folder.
  it('directories missing because their one folder is missing are one error naming the folder and the kinds, the others related', async () => {
    const group = `<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><CatalogReference catalogName="ManeuverCatalog" entryName="Flip"/></ManeuverGroup>`;
    const route = `<Private entityRef="Ego"><PrivateAction><RoutingAction><AssignRouteAction><CatalogReference catalogName="RouteCatalog" entryName="R"/></AssignRouteAction></RoutingAction></PrivateAction></Private>`;
    const scenario = (maneuvers: string, routes: string) =>
      roadScenario({ groups: [group], init: route }).replace(
        '<CatalogLocations/>',
        `<CatalogLocations><ManeuverCatalog><Directory path="${maneuvers}"/></ManeuverCatalog><RouteCatalog><Directory path="${routes}"/></RouteCatalog></CatalogLocations>`,
      );
    const catalogProblems = async (text: string, folders: string[] = []) => {
      const root = temporaryWorkspace({ 'main.xosc': text });
      try {
        for (const folder of folders) fs.mkdirSync(path.join(root, folder), { recursive: true });
        const { problems } = await new Flattener(new ScenarioStore({ root })).analyze(diskRef(path.join(root, 'main.xosc')));
        return problems
          .filter((problem) => problem.code === 'catalog-directory')
          .map(({ severity, code, message, hint, range, related }) => ({
            wording: { severity, code, message, hint },
            line: range.start.line,
            related: (related ?? []).map((each) => each.message),
          }));
      } finally {
        fs.rmSync(root, { recursive: true, force: true });
      }
    };
    const text = scenario('Catalogs/Maneuvers', 'Catalogs/Routes');
    const [one, ...more] = await catalogProblems(text);
    assert.deepEqual(more, []);
    assert.deepEqual(one.wording, catalogFolderWording('Catalogs', ['ManeuverCatalog', 'RouteCatalog'], false));
    assert.equal(
      one.wording.message,
      "the folder 'Catalogs' does not exist beside this file nor in SCENARIO_PATH, so neither do the ManeuverCatalog and RouteCatalog directories in it: the catalog references that need them resolve nowhere",
    );
    assert.equal(
      one.line,
      text.split('\n').findIndex((line) => line.includes('Catalogs/Maneuvers')),
    );
    assert.deepEqual(one.related, ['in the same missing folder: the RouteCatalog directory']);
    // One path for both: the folder is each directory.
    const [same, ...others] = await catalogProblems(scenario('catalogs', 'catalogs'));
    assert.deepEqual(others, []);
    assert.equal(
      same.wording.message,
      "the ManeuverCatalog and RouteCatalog directory 'catalogs' does not exist beside this file nor in SCENARIO_PATH: the catalog references that need them resolve nowhere",
    );
    // The folder is there, its subfolders are not: a problem for each directory, no word of a missing folder.
    const apart = await catalogProblems(text, ['Catalogs']);
    assert.deepEqual(
      apart.map((problem) => problem.wording),
      [catalogDirectoryWording('ManeuverCatalog', 'Catalogs/Maneuvers'), catalogDirectoryWording('RouteCatalog', 'Catalogs/Routes')],
    );
  });
});
