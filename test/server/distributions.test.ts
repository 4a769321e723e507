import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CodeLens, CompletionItem, Diagnostic, Hover, Location, MarkupContent, WorkspaceEdit } from 'vscode-languageserver/node';
import { applyEdits } from '../support/textEdits';
import { RunEsminiRequest, RunEsminiResult } from '../../common/src/protocol';
import { fileUri, useServer } from './harness';
import { problemCodeOf } from '../support/diagnostics';
import { cliPath, sharedDir } from '../support/paths';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { at } from '../support/cursor';
import { deterministic, distributionFile, fileHeader } from '../support/fixtures';

const esminiCorpus = path.join(sharedDir, 'corpus', 'openscenario', 'esmini');
const distributionName = 'cut-in_parameter_set.xosc';

function corpusFiles(): Record<string, string | Uint8Array> {
  const files: Record<string, string | Uint8Array> = {};
  if (!fs.existsSync(esminiCorpus)) return files;
  files[`xosc/${distributionName}`] = fs.readFileSync(path.join(esminiCorpus, distributionName));
  files['xosc/cut-in.xosc'] = fs.readFileSync(path.join(esminiCorpus, 'cut-in.xosc'));
  const vehicles = path.join(esminiCorpus, 'Catalogs', 'Vehicles');
  for (const name of fs.readdirSync(vehicles)) files[`xosc/Catalogs/Vehicles/${name}`] = fs.readFileSync(path.join(vehicles, name));
  return files;
}

const scenario = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" description="plain" author="test"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="30"/>
    <ParameterDeclaration name="Gap" parameterType="double" value="20">
      <ConstraintGroup>
        <ValueConstraint rule="greaterOrEqual" value="15"/>
      </ConstraintGroup>
    </ParameterDeclaration>
    <ParameterDeclaration name="Lanes" parameterType="int" value="2"/>
  </ParameterDeclarations>
</OpenSCENARIO>
`;

function distribution(body: string, scenarioFile = 'plain.xosc'): string {
  return distributionFile(
    scenarioFile,
    deterministic(`${body}\n`),
    fileHeader({ date: '2024-01-01T00:00:00', description: 'values', author: 'test' }),
  );
}

const ranges = distribution(`      <DeterministicSingleParameterDistribution parameterName="Speed">
        <DistributionSet><Element value="20"/><Element value="25"/><Element value="30"/><Element value="35"/><Element value="40"/><Element value="45"/><Element value="50"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="Gap">
        <DistributionRange stepWidth="5"><Range lowerLimit="10" upperLimit="30"/></DistributionRange>
      </DeterministicSingleParameterDistribution>`);

const messageOf = (diagnostic: Diagnostic) => (typeof diagnostic.message === 'string' ? diagnostic.message : diagnostic.message.value);
const lensTitles = (lenses: CodeLens[]) => lenses.map((lens) => lens.command?.title ?? '');
const hoverText = (hover: Hover | null) => (hover?.contents as MarkupContent | undefined)?.value ?? '';

function varyCount(file: string): string {
  return execFileSync(process.execPath, [cliPath, 'vary', file, '--count'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }).trim();
}

describe("distribution files in the editor: esmini's cut-in_parameter_set.xosc", function () {
  before(function () {
    if (!fs.existsSync(esminiCorpus)) this.skip();
  });
  const fixture = useServer(fs.existsSync(esminiCorpus) ? corpusFiles() : {}, `xosc/${distributionName}`);
  const file = () => path.join(fixture.root, 'xosc', distributionName);

  it('has no problem of its own', async () => {
    const diagnostics = await fixture.client.diagnosticsOf(fixture.openUri);
    assert.deepEqual(
      diagnostics.filter((d: Diagnostic) => d.source === 'modular2simple' && d.severity === 1),
      [],
    );
  });

  it('shows the number of concrete scenarios, the same as vary --count, and Run Variations', async () => {
    const lenses = (await fixture.client.connection.sendRequest('textDocument/codeLens', {
      textDocument: { uri: fixture.openUri },
    })) as CodeLens[];
    const count = varyCount(file());
    assert.equal(count, '12');
    assert.deepEqual(lensTitles(lenses), [`${count} concrete scenarios`, 'Run Variations']);
    assert.equal(lenses[1].command?.command, 'modular2simple.runVariations');
  });

  it('hovers a distribution with its values', async () => {
    const text = fs.readFileSync(file(), 'utf8').replace(/^\uFEFF/, '');
    const hover = (await fixture.client.connection.sendRequest('textDocument/hover', {
      textDocument: { uri: fixture.openUri },
      position: at(text, 'parameterName="TargetSpeed|Factor"'),
    })) as Hover | null;
    assert.equal(
      hoverText(hover),
      '**3 values**\n\n- TargetSpeedFactor = 1.100000\n- TargetSpeedFactor = 1.300000\n- TargetSpeedFactor = 1.500000',
    );
    const multi = (await fixture.client.connection.sendRequest('textDocument/hover', {
      textDocument: { uri: fixture.openUri },
      position: at(text, '<DeterministicMulti|ParameterDistribution'),
    })) as Hover | null;
    assert.equal(hoverText(multi), '**2 values**\n\n- HostVehicle = car_blue, TargetVehicle = car_yellow\n- TargetVehicle = van_red');
  });

  it('completes a parameterName with the root parameters of the scenario, with type and default', async () => {
    const text = fs.readFileSync(file(), 'utf8').replace(/^\uFEFF/, '');
    const items = (await fixture.client.connection.sendRequest('textDocument/completion', {
      textDocument: { uri: fixture.openUri },
      position: at(text, 'parameterName="|EgoSpeed"'),
    })) as CompletionItem[];
    assert.deepEqual(
      items.map((item) => `${item.label}: ${item.detail}`),
      [
        'HostVehicle: string = car_white',
        'TargetVehicle: string = car_red',
        'EgoStartS: double = 50',
        'HeadwayTime_LaneChange: double = 0.4',
        'HeadwayTime_Brake: double = 0.7',
        'EgoSpeed: double = 108',
        'TargetSpeedFactor: double = 1.2',
      ],
    );
  });

  it('completes a parameterName being typed, its closing quote not yet written, replacing what is typed', async () => {
    const text = fs.readFileSync(file(), 'utf8').replace(/^\uFEFF/, '');
    const typed = text.replace('parameterName="EgoSpeed"', 'parameterName="Ego');
    assert.notEqual(typed, text);
    await fixture.client.change(fixture.openUri, [{ text: typed }]);
    try {
      const position = at(typed, 'parameterName="Ego|');
      const items = (await fixture.client.connection.sendRequest('textDocument/completion', {
        textDocument: { uri: fixture.openUri },
        position,
      })) as CompletionItem[];
      assert.ok(
        items.some((item) => item.label === 'EgoSpeed'),
        items.map((item) => item.label).join(', '),
      );
      const edit = items[0].textEdit as { range: { start: { line: number; character: number }; end: { line: number; character: number } } };
      assert.deepEqual(edit.range, { start: { line: position.line, character: position.character - 'Ego'.length }, end: position });
    } finally {
      await fixture.client.change(fixture.openUri, [{ text }]);
    }
  });

  it('goes from a parameterName to its declaration in the scenario', async () => {
    const text = fs.readFileSync(file(), 'utf8').replace(/^\uFEFF/, '');
    const locations = (await fixture.client.connection.sendRequest('textDocument/definition', {
      textDocument: { uri: fixture.openUri },
      position: at(text, 'parameterRef="Target|Vehicle"', 'car_blue'),
    })) as Location[];
    assert.equal(locations.length, 1);
    assert.equal(locations[0].uri, fileUri(path.join(fixture.root, 'xosc', 'cut-in.xosc')));
    const declared = fs.readFileSync(path.join(fixture.root, 'xosc', 'cut-in.xosc'), 'utf8').replace(/^\uFEFF/, '');
    const start = at(declared, 'ParameterDeclaration name="|TargetVehicle"');
    assert.deepEqual(locations[0].range, { start, end: { line: start.line, character: start.character + 'TargetVehicle'.length } });
  });

  it('runs the first concrete scenario in esmini, saying which', async function () {
    requireEsmini(this);
    this.timeout(120_000);
    const result = (await fixture.client.send(RunEsminiRequest, {
      uri: fixture.openUri,
      esminiPath: esminiBinary,
      roadPath: [esminiRoads],
      duration: 2,
    })) as RunEsminiResult;
    assert.match(
      result.message,
      /^ran concrete scenario 0 of 12 \(HostVehicle = car_blue, TargetVehicle = car_yellow, EgoSpeed = 70\.0, TargetSpeedFactor = 1\.100000\)/,
    );
    assert.equal(result.outcome, 'ok', result.log);
    assert.ok(result.csvFile && fs.existsSync(result.csvFile));
    // The file the run is drawn on: the ScenarioFile, which has the roads and entities the distribution lacks.
    assert.equal(result.scenarioOf, fileUri(path.join(fixture.root, 'xosc', 'cut-in.xosc')));
  });
});

describe('distribution files in the editor: checks, counts and fixes', function () {
  const fixture = useServer(
    {
      'plain.xosc': scenario,
      'ranges.xosc': ranges,
      'unknown.xosc': distribution(`      <DeterministicSingleParameterDistribution parameterName="Sped">
        <DistributionSet><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`),
      'missing.xosc': distribution(
        `      <DeterministicSingleParameterDistribution parameterName="Speed">
        <DistributionSet><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`,
        'nowhere.xosc',
      ),
      'steps.xosc': distribution(`      <DeterministicSingleParameterDistribution parameterName="Speed">
        <DistributionRange stepWidth="0"><Range lowerLimit="10" upperLimit="30"/></DistributionRange>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="Gap">
        <DistributionRange stepWidth="50"><Range lowerLimit="15" upperLimit="30"/></DistributionRange>
      </DeterministicSingleParameterDistribution>`),
      'types.xosc': distribution(`      <DeterministicSingleParameterDistribution parameterName="Lanes">
        <DistributionSet><Element value="two"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`),
    },
    'ranges.xosc',
  );
  const own = (diagnostics: Diagnostic[]) =>
    diagnostics.filter(
      (d) =>
        d.source === 'modular2simple' && (problemCodeOf(d) === 'distribution' || problemCodeOf(d) === 'unknown-distribution-parameter'),
    );

  it('counts what the ValueConstraintGroups keep, as vary --count', async () => {
    const lenses = (await fixture.client.connection.sendRequest('textDocument/codeLens', {
      textDocument: { uri: fixture.openUri },
    })) as CodeLens[];
    const count = varyCount(path.join(fixture.root, 'ranges.xosc'));
    assert.equal(
      count,
      "35 combinations (esmini's --param_permutation 0..34), 28 kept: 7 break the scenario's ValueConstraintGroups and are discarded",
    );
    assert.deepEqual(lensTitles(lenses), ['28 concrete scenarios (7 of 35 discarded by ValueConstraintGroups)', 'Run Variations']);
  });

  it('reports a parameter the scenario lacks at its name, with the closest name as a quick fix', async () => {
    const uri = await fixture.client.openFile(path.join(fixture.root, 'unknown.xosc'));
    const diagnostics = own(await fixture.client.diagnosticsOf(uri));
    assert.equal(diagnostics.length, 1);
    assert.equal(problemCodeOf(diagnostics[0]), 'unknown-distribution-parameter');
    assert.equal(diagnostics[0].severity, 1);
    const text = fs.readFileSync(path.join(fixture.root, 'unknown.xosc'), 'utf8');
    const start = at(text, 'parameterName="|Sped"');
    assert.deepEqual(diagnostics[0].range, { start, end: { line: start.line, character: start.character + 4 } });
    const actions = (await fixture.client.connection.sendRequest('textDocument/codeAction', {
      textDocument: { uri },
      range: diagnostics[0].range,
      context: { diagnostics },
    })) as { title: string }[];
    assert.deepEqual(
      actions.map((action) => action.title),
      ["Change to 'Speed'"],
    );
    const lenses = (await fixture.client.connection.sendRequest('textDocument/codeLens', { textDocument: { uri } })) as CodeLens[];
    assert.deepEqual(lensTitles(lenses), ['no concrete scenarios: the distribution has errors']);
  });

  it('reports a ScenarioFile that does not resolve at its filepath', async () => {
    const uri = await fixture.client.openFile(path.join(fixture.root, 'missing.xosc'));
    const diagnostics = own(await fixture.client.diagnosticsOf(uri));
    assert.equal(diagnostics.length, 1);
    assert.match(messageOf(diagnostics[0]), /^ScenarioFile nowhere\.xosc \(.*nowhere\.xosc\): no such file$/);
    const text = fs.readFileSync(path.join(fixture.root, 'missing.xosc'), 'utf8');
    assert.deepEqual(diagnostics[0].range.start, at(text, 'filepath="|nowhere.xosc"'));
  });

  it('reports a step of 0, and warns of a step wider than its range', async () => {
    const uri = await fixture.client.openFile(path.join(fixture.root, 'steps.xosc'));
    const text = fs.readFileSync(path.join(fixture.root, 'steps.xosc'), 'utf8');
    const diagnostics = own(await fixture.client.diagnosticsOf(uri));
    assert.deepEqual(
      diagnostics.map((d) => [d.severity, messageOf(d), d.range.start]),
      [[1, 'stepWidth 0 must be greater than 0', at(text, 'stepWidth="|0"')]],
    );
    // The step is checked once the distribution has no error left.
    fs.writeFileSync(path.join(fixture.root, 'steps2.xosc'), text.replace('stepWidth="0"', 'stepWidth="1"'));
    const second = await fixture.client.openFile(path.join(fixture.root, 'steps2.xosc'));
    const warnings = own(await fixture.client.diagnosticsOf(second));
    assert.deepEqual(
      warnings.map((d) => [d.severity, messageOf(d)]),
      [[2, 'stepWidth 50 is wider than the range 15..30: only 15 is used']],
    );
  });

  it("warns of a value that does not fit its parameter's type", async () => {
    const uri = await fixture.client.openFile(path.join(fixture.root, 'types.xosc'));
    const diagnostics = own(await fixture.client.diagnosticsOf(uri));
    assert.equal(diagnostics.length, 1);
    assert.equal(diagnostics[0].severity, 2);
    assert.match(messageOf(diagnostics[0]), /^the value 'two' for int parameter 'Lanes' /);
  });

  it('checks a file an edit makes a distribution file, after value edits, and stops once an edit makes it a scenario again', async () => {
    const file = path.join(fixture.root, 'becoming.xosc');
    fs.writeFileSync(file, scenario);
    const uri = await fixture.client.openFile(file);
    assert.deepEqual(own(await fixture.client.diagnosticsOf(uri)), []);
    // A value edit first: the answer 'no distribution' is carried over it, and must not be over the edits after it.
    await fixture.client.change(uri, [{ text: scenario.replace('value="30"', 'value="31"') }]);
    const unknown = distribution(`      <DeterministicSingleParameterDistribution parameterName="Sped">
        <DistributionSet><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`);
    await fixture.client.change(uri, [{ text: unknown }]);
    const named = (name: string) => (diagnostics: Diagnostic[]) =>
      own(diagnostics).length === 1 && messageOf(own(diagnostics)[0]).includes(`'${name}'`);
    await fixture.client.diagnosticsOf(uri, named('Sped'));
    await fixture.client.change(uri, [{ text: unknown.replace('parameterName="Sped"', 'parameterName="Spd"') }]);
    await fixture.client.diagnosticsOf(uri, named('Spd'));
    await fixture.client.change(uri, [{ text: scenario.replace('value="30"', 'value="32"') }]);
    await fixture.client.diagnosticsOf(uri, (diagnostics) => own(diagnostics).length === 0);
    const lenses = (await fixture.client.connection.sendRequest('textDocument/codeLens', { textDocument: { uri } })) as CodeLens[];
    assert.deepEqual(lensTitles(lenses), []);
    await fixture.client.close(uri);
  });

  it('checks again when the scenario changes', async () => {
    const uri = await fixture.client.openFile(path.join(fixture.root, 'unknown.xosc'));
    const scenarioUri = await fixture.client.openFile(path.join(fixture.root, 'plain.xosc'));
    await fixture.client.change(scenarioUri, [{ text: scenario.replace('name="Speed"', 'name="Sped"') }]);
    await fixture.client.diagnosticsOf(uri, (diagnostics) => own(diagnostics).length === 0);
    await fixture.client.close(scenarioUri);
  });
});

describe('distribution files in the editor: a modular main as the ScenarioFile', function () {
  const modularRun = path.join(__dirname, '..', 'fixtures', 'modularRun', 'xosc');
  const fixture = useServer(
    {
      'xosc/main.xosc': fs.readFileSync(path.join(modularRun, 'main.xosc')),
      'xosc/cut_in_group.xosc': fs.readFileSync(path.join(modularRun, 'cut_in_group.xosc')),
      'xosc/speeds.xosc': distribution(
        `      <DeterministicSingleParameterDistribution parameterName="EgoSpeed">
        <DistributionSet><Element value="20"/><Element value="25"/><Element value="30"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`,
        'main.xosc',
      ),
    },
    'xosc/speeds.xosc',
  );

  it('is flattened: no problem, the count as vary --count, definition in the main file', async () => {
    const diagnostics = await fixture.client.diagnosticsOf(fixture.openUri);
    assert.deepEqual(diagnostics.filter((d) => d.severity === 1).map(messageOf), []);
    const lenses = (await fixture.client.connection.sendRequest('textDocument/codeLens', {
      textDocument: { uri: fixture.openUri },
    })) as CodeLens[];
    const count = varyCount(path.join(fixture.root, 'xosc', 'speeds.xosc'));
    assert.equal(count, '3');
    assert.deepEqual(lensTitles(lenses), [`${count} concrete scenarios`, 'Run Variations']);
    const text = fs.readFileSync(path.join(fixture.root, 'xosc', 'speeds.xosc'), 'utf8');
    const locations = (await fixture.client.connection.sendRequest('textDocument/definition', {
      textDocument: { uri: fixture.openUri },
      position: at(text, 'parameterName="Ego|Speed"'),
    })) as Location[];
    assert.deepEqual(
      locations.map((location) => [location.uri, location.range.start.line]),
      [[fileUri(path.join(fixture.root, 'xosc', 'main.xosc')), 5]],
    );
  });
});

describe('distribution files in the editor: stochastic', function () {
  const stochastic = distributionFile(
    'plain.xosc',
    `    <Stochastic numberOfTestRuns="40" randomSeed="7">
      <StochasticDistribution parameterName="Speed">
        <UniformDistribution><Range lowerLimit="20" upperLimit="30"/></UniformDistribution>
      </StochasticDistribution>
    </Stochastic>
`,
    fileHeader({ date: '2024-01-01T00:00:00', description: 'draws', author: 'test' }),
  );
  const fixture = useServer({ 'plain.xosc': scenario, 'draws.xosc': stochastic }, 'draws.xosc');

  it('counts the runs as vary --count and hovers the first draws', async () => {
    const lenses = (await fixture.client.connection.sendRequest('textDocument/codeLens', {
      textDocument: { uri: fixture.openUri },
    })) as CodeLens[];
    const count = varyCount(path.join(fixture.root, 'draws.xosc'));
    assert.equal(count, '40');
    assert.deepEqual(lensTitles(lenses), ['40 concrete scenarios', 'Run Variations']);
    const hover = (await fixture.client.connection.sendRequest('textDocument/hover', {
      textDocument: { uri: fixture.openUri },
      position: at(stochastic, '<Stochastic|Distribution'),
    })) as Hover | null;
    const lines = hoverText(hover).split('\n');
    assert.equal(lines[0], '**40 draws** from a uniform distribution (seed 7)');
    assert.equal(lines.length, 2 + 5 + 1);
    for (const line of lines.slice(2, 7)) {
      const value = Number(/^- run \d: (.*)$/.exec(line)?.[1]);
      assert.ok(value >= 20 && value <= 30, line);
    }
    assert.equal(lines[7], '- … (35 more)');
  });
});

describe('distribution files in the editor: renaming a root parameter', function () {
  const varies = distribution(`      <DeterministicSingleParameterDistribution parameterName="Speed">
        <DistributionSet><Element value="20"/><Element value="25"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="$Speed">
        <DistributionSet><Element value="30"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicMultiParameterDistribution><ValueSetDistribution><ParameterValueSet>
        <ParameterAssignment parameterRef="Speed" value="5"/><ParameterAssignment parameterRef="Gap" value="16"/>
      </ParameterValueSet></ValueSetDistribution></DeterministicMultiParameterDistribution>`);
  const fixture = useServer(
    {
      'plain.xosc': scenario,
      'other.xosc': scenario,
      'varies.xosc': varies,
      // The same parameter name in a distribution of another scenario: not this parameter.
      'elsewhere.xosc': varies.replace('filepath="plain.xosc"', 'filepath="other.xosc"'),
    },
    'plain.xosc',
  );

  it('renames the parameterName and parameterRef of every distribution that varies it, and only those', async () => {
    const edit = (await fixture.client.connection.sendRequest('textDocument/rename', {
      textDocument: { uri: fixture.openUri },
      position: at(scenario, 'name="S|peed"'),
      newName: 'EgoSpeed',
    })) as WorkspaceEdit;
    const changes = edit.changes ?? {};
    assert.deepEqual(Object.keys(changes).sort(), [fixture.openUri, fileUri(path.join(fixture.root, 'varies.xosc'))].sort());
    const renamed = applyEdits(varies, changes[fileUri(path.join(fixture.root, 'varies.xosc'))]);
    assert.equal(renamed.match(/parameterName="EgoSpeed"/g)?.length, 1);
    assert.equal(renamed.match(/parameterName="\$EgoSpeed"/g)?.length, 1, "the '$' written before the name is kept");
    assert.match(renamed, /<ParameterAssignment parameterRef="EgoSpeed" value="5"\/><ParameterAssignment parameterRef="Gap"/);
    assert.doesNotMatch(renamed, /"\$?Speed"/);
    assert.match(
      applyEdits(scenario, changes[fixture.openUri]),
      /<ParameterDeclaration name="EgoSpeed" parameterType="double" value="30"\/>/,
    );
  });
});

describe('distribution files in the editor: a file deleted on disk or closed leaves no stale problem (workspace pull)', function () {
  const sped = distribution(`      <DeterministicSingleParameterDistribution parameterName="Sped">
        <DistributionSet><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`);
  const fixture = useServer({ 'plain.xosc': scenario, 'values.xosc': sped, 'other.xosc': sped }, 'plain.xosc', {
    pullDiagnostics: true,
  });
  interface WorkspaceReport {
    items: { uri: string; kind: string; resultId?: string; items?: Diagnostic[] }[];
  }
  // What VS Code's client keeps: the last full report of each file, and the result id it sends back.
  const shown = new Map<string, Diagnostic[]>();
  const resultIds = new Map<string, string>();
  async function pull(): Promise<void> {
    const report = await fixture.client.request<WorkspaceReport>('workspace/diagnostic', {
      previousResultIds: [...resultIds].map(([uri, value]) => ({ uri, value })),
    });
    for (const item of report.items) {
      if (item.kind === 'full') shown.set(item.uri, item.items ?? []);
      if (item.resultId === undefined) resultIds.delete(item.uri);
      else resultIds.set(item.uri, item.resultId);
    }
  }
  const codes = (file: string) => (shown.get(fileUri(path.join(fixture.root, file))) ?? []).map((d) => problemCodeOf(d));
  async function notify(file: string, type: 1 | 2 | 3): Promise<void> {
    const before = fixture.client.refreshes;
    await fixture.client.connection.sendNotification('workspace/didChangeWatchedFiles', {
      changes: [{ uri: fileUri(path.join(fixture.root, file)), type }],
    });
    await fixture.client.until(() => fixture.client.refreshes > before || undefined, 'a workspace/diagnostic/refresh');
  }

  it('clears the problems of a distribution file deleted on disk, and shows them again when it comes back', async () => {
    await pull();
    assert.deepEqual(codes('values.xosc'), ['unknown-distribution-parameter']);
    fs.rmSync(path.join(fixture.root, 'values.xosc'));
    await notify('values.xosc', 3);
    await pull();
    assert.deepEqual(codes('values.xosc'), []);
    assert.deepEqual(codes('other.xosc'), ['unknown-distribution-parameter'], 'another file keeps its problem');
    await pull();
    assert.deepEqual(codes('values.xosc'), [], 'nothing brings the deleted file back');
    fs.writeFileSync(path.join(fixture.root, 'values.xosc'), sped);
    await notify('values.xosc', 1);
    await pull();
    assert.deepEqual(codes('values.xosc'), ['unknown-distribution-parameter']);
  });

  it('clears the problems of an open distribution file once it is deleted and closed', async () => {
    const file = path.join(fixture.root, 'values.xosc');
    if (!fs.existsSync(file)) {
      fs.writeFileSync(file, sped);
      await notify('values.xosc', 1);
    }
    const uri = await fixture.client.openFile(file);
    await pull();
    assert.deepEqual(codes('values.xosc'), ['unknown-distribution-parameter']);
    fs.rmSync(file);
    await notify('values.xosc', 3);
    await pull();
    // Open, the editor's text still stands for it (VS Code keeps a deleted file's editor open).
    assert.deepEqual(codes('values.xosc'), ['unknown-distribution-parameter']);
    await fixture.client.close(uri);
    const closed = await fixture.client.request<{ kind: string; items: Diagnostic[] }>('textDocument/diagnostic', {
      textDocument: { uri },
    });
    assert.deepEqual(closed.items, []);
    await pull();
    assert.deepEqual(codes('values.xosc'), []);
  });

  it("recomputes a distribution's problems when its ScenarioFile is deleted and when it comes back", async () => {
    await pull();
    assert.deepEqual(codes('other.xosc'), ['unknown-distribution-parameter']);
    const plain = path.join(fixture.root, 'plain.xosc');
    fs.rmSync(plain);
    await notify('plain.xosc', 3);
    await pull();
    assert.deepEqual(codes('other.xosc'), ['distribution'], 'the ScenarioFile that no longer resolves');
    fs.writeFileSync(plain, scenario);
    await notify('plain.xosc', 1);
    await pull();
    assert.deepEqual(codes('other.xosc'), ['unknown-distribution-parameter']);
  });
});
