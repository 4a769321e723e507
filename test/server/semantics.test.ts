import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Diagnostic, DiagnosticSeverity, DiagnosticTag } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { repoRoot } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';
import { TestClient } from './harness';

const fixtureDir = path.join(repoRoot, 'test', 'fixtures', 'semantics');
const read = (name: string) => fs.readFileSync(path.join(fixtureDir, name), 'utf8');

/** The semantic checks reach the editor as diagnostics, through the analysis the server already runs. */
describe('language server: semantic diagnostics', function () {
  this.timeout(60_000);
  let client: TestClient;
  let root: string;

  before(async function () {
    root = temporaryWorkspace({
      'main.xosc': read('main.xosc'),
      'speed_up.xosc': read('speed_up.xosc').replace('value="${$TargetSpeed / 4 + 3}"', 'value="${$TargetSpeed / 0}"'),
      'catalogs/Vehicles/VehicleCatalog.xosc': read('catalogs/Vehicles/VehicleCatalog.xosc'),
      'catalogs/Maneuvers/ManeuverCatalog.xosc': read('catalogs/Maneuvers/ManeuverCatalog.xosc'),
    });
    client = await TestClient.start({ root });
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('publishes expression errors, unused parameters (faded) and no false entity warning for entityRef="$owner"', async () => {
    const uri = await client.openFile(path.join(root, 'speed_up.xosc'));
    const diagnostics: Diagnostic[] = await client.diagnosticsOf(uri, (list) =>
      list.some((diagnostic) => problemCodeOf(diagnostic) === 'division-by-zero'),
    );
    const division = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'division-by-zero');
    assert.ok(division);
    assert.equal(division.severity, DiagnosticSeverity.Error);
    const line = fs.readFileSync(path.join(root, 'speed_up.xosc'), 'utf8').split('\n')[division.range.start.line];
    assert.equal(line.slice(division.range.start.character, division.range.end.character), '0');
    const unused = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'unused-parameter');
    assert.ok(unused && unused.severity === DiagnosticSeverity.Hint && unused.tags?.includes(DiagnosticTag.Unnecessary));
    assert.match(String(unused.message), /'Unrelated'/);

    const mainUri = await client.openFile(path.join(root, 'main.xosc'));
    const mainDiagnostics = await client.diagnosticsOf(mainUri);
    assert.ok(!mainDiagnostics.some((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-entity'), JSON.stringify(mainDiagnostics));
  });

  it('reports an undeclared parameter while typing, and clears it once declared', async () => {
    const uri = await client.openFile(path.join(root, 'main.xosc'));
    const text = fs.readFileSync(path.join(root, 'main.xosc'), 'utf8');
    const typed = text.replace('<AbsoluteTargetSpeed value="5"/>', '<AbsoluteTargetSpeed value="$Initial"/>');
    await client.change(uri, [{ text: typed }]);
    const withError = await client.diagnosticsOf(uri, (list) =>
      list.some((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-parameter'),
    );
    const undeclared = withError.find((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-parameter');
    assert.ok(undeclared);
    assert.equal(
      typed.split('\n')[undeclared.range.start.line].slice(undeclared.range.start.character, undeclared.range.end.character),
      '$Initial',
    );
    await client.change(uri, [
      {
        text: typed.replace(
          '<ParameterDeclaration name="owner"',
          '<ParameterDeclaration name="Initial" parameterType="double" value="5"/>\n    <ParameterDeclaration name="owner"',
        ),
      },
    ]);
    await client.diagnosticsOf(uri, (list) => !list.some((diagnostic) => problemCodeOf(diagnostic) === 'undeclared-parameter'));
  });
});
