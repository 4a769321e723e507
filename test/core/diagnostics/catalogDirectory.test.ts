import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CATALOG_DIRECTORY, catalogDirectoryWording } from '../../../server/src/core/diagnostics/catalogDirectory';
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
});
