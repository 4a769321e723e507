import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CompletionItem, Diagnostic, DiagnosticSeverity } from 'vscode-languageserver/node';
import { problemCodeOf } from '../support/diagnostics';
import { at, offsetAt, positionAt } from '../support/cursor';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

const cutInFile = path.join(openscenarioDir, 'esmini', 'cut-in.xosc');

/** esmini's cut-in.xosc with `Count` ('1.0', text) and `Start` ('25', text) declared after its own parameters. */
function cutIn(): string {
  return fs
    .readFileSync(cutInFile, 'utf8')
    .replace(
      '<ParameterDeclaration name="TargetSpeedFactor" parameterType="double" value="1.2"/>',
      '$&\n      <ParameterDeclaration name="Count" parameterType="string" value="1.0"/>\n      <ParameterDeclaration name="Start" parameterType="string" value="25"/>',
    );
}

function typeProblems(diagnostics: Diagnostic[]): Diagnostic[] {
  return diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'type-mismatch');
}

describe("language server: a parameter's value against the type of each attribute that uses it (JSON-RPC)", function () {
  this.timeout(60_000);
  let root: string;
  let client: TestClient;

  before(async function () {
    if (!fs.existsSync(cutInFile)) {
      console.log(`    (skipped: ${cutInFile} is absent)`);
      this.skip();
    }
    root = temporaryWorkspace({ 'cut-in.xosc': cutIn() });
    client = await TestClient.start({ root, schema: true });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('reports no type problem on the scenario as esmini ships it', async () => {
    const uri = await client.openFile(path.join(root, 'cut-in.xosc'));
    assert.deepEqual(typeProblems(await client.diagnosticsOf(uri)), []);
    await client.close(uri);
  });

  it('s="$HostVehicle" (a string parameter car_white) in a double is an error at the use, naming the declaration', async () => {
    const text = cutIn().replace('s="$EgoStartS"', 's="$HostVehicle"');
    const uri = fileUri(path.join(root, 'host.xosc'));
    await client.open(uri, text);
    const [problem, ...others] = typeProblems(await client.diagnosticsOf(uri, (found) => typeProblems(found).length > 0));
    assert.deepEqual(others, []);
    assert.equal(problem.severity, DiagnosticSeverity.Error);
    assert.deepEqual(problem.range.start, at(text, 's="|$HostVehicle"'));
    assert.match(
      String(problem.message),
      /^'car_white', the value of parameter 'HostVehicle' \(declared string\), cannot be converted to the attribute's type double \(LanePosition\.s\)/,
    );
    const [declaration] = problem.relatedInformation ?? [];
    assert.equal(declaration.location.uri, uri);
    assert.deepEqual(declaration.location.range.start, at(text, 'name="HostVehicle" parameterType="string" value="|car_white"'));
    await client.close(uri);
  });

  it('a numeric string converts to a double; `1.0` for an integer is a warning; an enumeration value must be one of its values', async () => {
    const text = cutIn()
      .replace('s="$EgoStartS"', 's="$Start"')
      .replace(
        '<ManeuverGroup maximumExecutionCount="1" name="CutInAndBrakeSequence">',
        '<ManeuverGroup maximumExecutionCount="$Count" name="CutInAndBrakeSequence">',
      )
      .replace('dynamicsShape="step"', 'dynamicsShape="$TargetVehicle"');
    const uri = fileUri(path.join(root, 'kinds.xosc'));
    await client.open(uri, text);
    const problems = typeProblems(await client.diagnosticsOf(uri, (found) => typeProblems(found).length >= 2));
    const described = problems.map((problem) => `${problem.range.start.line}:${problem.severity}:${problem.message}`).sort();
    assert.equal(described.length, 2, described.join('\n'));
    const countLine = at(text, 'maximumExecutionCount="|$Count"').line;
    const shapeLine = at(text, 'dynamicsShape="|$TargetVehicle"').line;
    assert.match(
      described.find((line) => line.startsWith(`${countLine}:`)) ?? '',
      new RegExp(
        `^${countLine}:${DiagnosticSeverity.Warning}:'1\\.0', the value of parameter 'Count' \\(declared string\\), is a number with a fraction of zero for the attribute's type unsignedInt`,
      ),
    );
    assert.match(
      described.find((line) => line.startsWith(`${shapeLine}:`)) ?? '',
      new RegExp(
        `^${shapeLine}:${DiagnosticSeverity.Error}:'car_red', the value of parameter 'TargetVehicle' .*cannot be converted to the attribute's type DynamicsShape \\(one of`,
      ),
    );
    await client.close(uri);
  });

  it('completion after $ in a double attribute offers the parameters whose value fits first', async () => {
    const base = cutIn();
    const offset = offsetAt(base, 's="|$EgoStartS"');
    const text = base.slice(0, offset) + '$' + base.slice(offset + '$EgoStartS'.length);
    const uri = fileUri(path.join(root, 'complete.xosc'));
    await client.open(uri, text);
    const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, positionAt(text, offset + 1)));
    const ordered = [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? '')).map((item) => item.label);
    assert.deepEqual(ordered, [
      '$EgoStartS',
      '$HeadwayTime_LaneChange',
      '$HeadwayTime_Brake',
      '$EgoSpeed',
      '$TargetSpeedFactor',
      '$Count',
      '$Start',
      '$HostVehicle',
      '$TargetVehicle',
    ]);
    await client.close(uri);
  });
});
