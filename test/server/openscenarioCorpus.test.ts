import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { DiagnosticSeverity, Hover, InlayHint, Location, MarkupContent } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { corpusFiles, expectedCorpusFindings, openscenarioDir, SEMANTIC_CODES } from '../support/openscenarioCorpus';
import { fileUri, TestClient } from './harness';
import { positionAt } from '../support/cursor';

describe('language server on the real OpenSCENARIO corpus (../shared/corpus/openscenario)', function () {
  this.timeout(180_000);
  const esminiDir = path.join(openscenarioDir, 'esmini');
  const carlaDir = path.join(openscenarioDir, 'scenario_runner');
  let esmini: TestClient;
  let carla: TestClient;

  before(async function () {
    if (!fs.existsSync(openscenarioDir)) {
      console.log(`    (skipped: ${openscenarioDir} is absent)`);
      this.skip();
    }
    // Catalogs are found as each simulator is told to find them: esmini through its catalog folders, CARLA beside the scenario.
    esmini = await TestClient.start({ root: esminiDir, settings: { scenarioPath: [path.join(esminiDir, 'Catalogs')] } });
    carla = await TestClient.start({ root: carlaDir, settings: { scenarioPath: [carlaDir] } });
    await Promise.all([esmini.indexed(), carla.indexed()]);
  });

  after(async function () {
    await esmini?.stop();
    await carla?.stop();
  });

  it('publishes no false error or warning of the semantic checks on any of the 101 files, and highlights and hints each without failing', async function () {
    const files = corpusFiles();
    assert.equal(files.length, 101);
    const found: Record<string, string[]> = {};
    let tokenCount = 0;
    let hintCount = 0;
    for (const file of files) {
      const relative = path.relative(openscenarioDir, file);
      const client = relative.startsWith('esmini') ? esmini : carla;
      const uri = await client.openFile(file);
      const diagnostics = await client.diagnosticsOf(uri, () => true, 30_000);
      for (const diagnostic of diagnostics) {
        const severe = diagnostic.severity === DiagnosticSeverity.Error || diagnostic.severity === DiagnosticSeverity.Warning;
        if (severe && SEMANTIC_CODES.has(problemCodeOf(diagnostic) as never))
          (found[relative] ??= []).push(`${diagnostic.range.start.line + 1}:${String(problemCodeOf(diagnostic))}`);
      }
      const tokens = await client.request<{ data: number[] }>('textDocument/semanticTokens/full', { textDocument: { uri } });
      const hints = await client.request<InlayHint[]>('textDocument/inlayHint', {
        textDocument: { uri },
        range: { start: { line: 0, character: 0 }, end: { line: 1_000_000, character: 0 } },
      });
      tokenCount += tokens.data.length / 5;
      hintCount += hints.length;
      await client.close(uri);
    }
    // Most files use $parameters; 27 use ${...}.
    assert.ok(tokenCount > 1000 && hintCount > 60, `${tokenCount} tokens, ${hintCount} hints`);
    const sorted = (lists: Record<string, string[]>) =>
      Object.fromEntries(Object.entries(lists).map(([file, problems]) => [file, [...problems].sort()]));
    assert.deepEqual(sorted(found), sorted(expectedCorpusFindings()));
  });

  it('goes from an entryName written $HostVehicle to the entry in esmini Catalogs and to the parameter', async function () {
    const file = path.join(esminiDir, 'cut-in.xosc');
    const text = fs.readFileSync(file, 'utf8');
    const uri = await esmini.openFile(file);
    const at = text.indexOf('entryName="$HostVehicle"') + 'entryName="$Ho'.length;
    const locations = await esmini.request<Location[]>('textDocument/definition', esmini.at(uri, positionAt(text, at)));
    const catalogPath = path.join(esminiDir, 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc');
    const catalogText = fs.readFileSync(catalogPath, 'utf8');
    assert.equal(locations.length, 2);
    assert.equal(locations[0].uri, fileUri(catalogPath));
    assert.equal(
      catalogText.split('\n')[locations[0].range.start.line].slice(locations[0].range.start.character, locations[0].range.end.character),
      'car_white',
    );
    assert.equal(locations[1].uri, uri);
    assert.equal(locations[1].range.start.line, text.slice(0, text.indexOf('name="HostVehicle"')).split('\n').length - 1);
    await esmini.close(uri);
  });

  it('shows the values of the expressions of a real file as inlay hints and in the hover', async function () {
    const file = path.join(esminiDir, 'cut-in.xosc');
    const text = fs.readFileSync(file, 'utf8');
    const uri = await esmini.openFile(file);
    const hints = await esmini.request<InlayHint[]>('textDocument/inlayHint', {
      textDocument: { uri },
      range: { start: { line: 0, character: 0 }, end: { line: text.split('\n').length, character: 0 } },
    });
    // cut-in.xosc: EgoSpeed 108 km/h as m/s, ${$EgoSpeed / 3.6} = 30.
    const expression = text.indexOf('${$EgoSpeed / 3.6}');
    assert.ok(expression > 0);
    const hint = hints.find((candidate) => candidate.position.line === positionAt(text, expression).line);
    assert.equal(hint?.label, '= 30');
    const hover = await esmini.request<Hover>('textDocument/hover', esmini.at(uri, positionAt(text, expression + 4)));
    assert.match(
      (hover.contents as MarkupContent).value,
      /= \*\*30\*\* \(double\)[\s\S]*`\$EgoSpeed` = 108 \(double\), declared in `<OpenSCENARIO>`/,
    );
    await esmini.close(uri);
  });
});
