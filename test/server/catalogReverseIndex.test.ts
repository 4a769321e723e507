import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { pathToFileURL } from 'node:url';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { diskRef } from '../../server/src/core/sources';
import { referencingScenarios } from '../../server/src/features/catalogVariables';
import { DEFAULT_SETTINGS } from '../../server/src/settings';
import { Workspace } from '../../server/src/workspace';
import { MANEUVER_CATALOG, roadScenario } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

/** A scenario whose group holds `maneuver`, finding maneuvers in `catalogs/`. */
function scenarioWith(maneuver: string, variables = ''): string {
  const group = `<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>${maneuver}</ManeuverGroup>`;
  return roadScenario({ groups: [group] }).replace(
    '<CatalogLocations/>',
    `${variables}<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>`,
  );
}

const referenceTo = (entry: string) => `<CatalogReference catalogName="ManeuverCatalog" entryName="${entry}"/>`;

/** The reverse index of catalog references (issue 25): a diagnostic pass reads the scenarios that reference the entry, no other. */
describe('language server: the workspace index knows which scenarios reference a catalog entry', function () {
  this.timeout(60_000);
  let root: string;

  before(function () {
    const files: Record<string, string> = {
      'catalogs/ManeuverCatalog.xosc': MANEUVER_CATALOG,
      'declares.xosc': scenarioWith(
        referenceTo('Flip'),
        '<VariableDeclarations><VariableDeclaration name="Flag" variableType="boolean" value="false"/></VariableDeclarations>',
      ),
      'lacks.xosc': scenarioWith(referenceTo('Flip')),
      'other-entry.xosc': scenarioWith(referenceTo('Other')),
      // A reference only in a comment is no reference.
      'commented.xosc': scenarioWith(`<!-- ${referenceTo('Flip')} --><Maneuver name="M"/>`),
    };
    for (let index = 0; index < 20; index++) files[`unrelated/u${index}.xosc`] = scenarioWith('<Maneuver name="M"/>');
    root = temporaryWorkspace(files);
  });

  after(function () {
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('notes each referencing scenario of a catalog variable, reading no file but the catalog and those scenarios', async () => {
    const workspace = new Workspace();
    workspace.configure([root], DEFAULT_SETTINGS);
    await workspace.indexAll();
    workspace.index.watched = true;
    const catalogRef = diskRef(path.join(root, 'catalogs', 'ManeuverCatalog.xosc'));
    const problem = (await workspace.analyze(catalogRef)).problems.find((candidate) => candidate.code === 'undeclared-variable');
    assert.ok(problem, 'the catalog notes its entry variable');

    const read = new Set<string>();
    const readFile = workspace.files.readFile.bind(workspace.files);
    workspace.files.readFile = (filePath, maxBytes) => {
      read.add(path.relative(root, filePath));
      return readFile(filePath, maxBytes);
    };
    const related = await referencingScenarios(workspace, catalogRef, problem);

    assert.deepEqual(related.map((item) => `${path.basename(item.location.uri)}: ${item.message}`).sort(), [
      "declares.xosc: declares variable 'Flag'",
      "lacks.xosc: does not declare variable 'Flag' (an error there)",
    ]);
    const outside = [...read].filter(
      (file) => !['declares.xosc', 'lacks.xosc', path.join('catalogs', 'ManeuverCatalog.xosc')].includes(file),
    );
    assert.deepEqual(outside, [], 'files read that reference no entry Flip');
  });

  it('finds a scenario that starts referencing the entry after an edit, and walks no folder for it', async () => {
    const workspace = new Workspace();
    workspace.configure([root], DEFAULT_SETTINGS);
    await workspace.indexAll();
    workspace.index.watched = true;
    let walks = 0;
    const walk = workspace.index.walk.bind(workspace.index);
    workspace.index.walk = (folders) => {
      walks++;
      return walk(folders);
    };
    const unrelated = path.join(root, 'unrelated', 'u0.xosc');
    assert.deepEqual(await workspace.catalogReferrers('Flip'), [
      diskRef(path.join(root, 'declares.xosc')),
      diskRef(path.join(root, 'lacks.xosc')),
    ]);
    const uri = pathToFileURL(unrelated).href;
    workspace.documents.add(
      uri,
      TextDocument.create(uri, 'xosc', 1, scenarioWith(referenceTo('Flip'))),
      Promise.resolve(diskRef(unrelated)),
    );
    workspace.open(uri, diskRef(unrelated));
    assert.ok(
      (await workspace.catalogReferrers('Flip')).some((ref) => ref.disk === unrelated),
      'an open document is a candidate',
    );
    assert.equal(walks, 0, 'the kept list served both passes');
    workspace.fileChanged(path.join(root, 'new.xosc'));
    await workspace.catalogReferrers('Flip');
    assert.equal(walks, 1, 'a file appearing makes the next pass list the folders again');
  });
});
