import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { RunEsminiRequest, RunEsminiResult } from '../../common/src/protocol';
import { Flattener } from '../../server/src/core/flatten';
import { SourceRef } from '../../server/src/core/sources';
import { esminiBinary, requireEsmini, esminiRoads } from '../support/esmini';
import { repoRoot } from '../support/paths';
import { fileUri, TestClient } from './harness';
import { temporaryFolder } from '../support/temporaryDirectory';

describe('language server: the Run in esmini request over JSON-RPC', function () {
  this.timeout(120_000);
  let root: string;
  let client: TestClient;

  beforeEach(async () => {
    root = temporaryFolder('m2s-server-run-');
    fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
    client = await TestClient.start({ root });
    await client.indexed();
  });
  afterEach(async () => client.stop());

  const run = (uri: string, options: Record<string, unknown> = {}) =>
    client.send(RunEsminiRequest, {
      uri,
      esminiPath: esminiBinary,
      roadPath: [esminiRoads],
      duration: 3,
      ...options,
    }) as Promise<RunEsminiResult>;

  it('a missing esmini is an answer that says how to get it, not a failure', async () => {
    const result = await run(fileUri(path.join(root, 'main.xosc')), { esminiPath: path.join(root, 'no-esmini') });
    assert.equal(result.outcome, 'no-esmini');
    assert.match(result.message, /modular2simple\.esmini\.path/);
    assert.deepEqual(result.problems, []);
  });

  it("adds one exit listener for every server's run folders, however many servers of one process run esmini", async () => {
    const noEsmini = { esminiPath: path.join(root, 'no-esmini') };
    await run(fileUri(path.join(root, 'main.xosc')), noEsmini);
    const listeners = process.listenerCount('exit');
    const other = await TestClient.start({ root });
    try {
      await other.indexed();
      for (const server of [other, client])
        await server.send(RunEsminiRequest, { uri: fileUri(path.join(root, 'main.xosc')), ...noEsmini });
    } finally {
      await other.stop();
    }
    assert.equal(process.listenerCount('exit'), listeners, 'exit listeners added by the later runs');
  });

  it('runs the unsaved text of an open simple scenario and answers with its message on that line, and the CSV', async function () {
    requireEsmini(this);
    const clean = await run(fileUri(path.join(root, 'main.xosc')));
    assert.equal(clean.outcome, 'ok', clean.message);
    assert.ok(clean.csvFile && fs.existsSync(clean.csvFile));
    assert.match(fs.readFileSync(clean.csvFile, 'utf8').split('\n')[6], /^Index \[-\], TimeStamp \[s\], #1 Entity_Name/);

    const simple = path.join(root, 'lane_change.xosc');
    const uri = await client.openFile(simple);
    const text = fs.readFileSync(simple, 'utf8');
    const offset = text.indexOf('dynamicsShape="linear"') + 'dynamicsShape="'.length;
    const line = text.slice(0, offset).split('\n').length - 1;
    const character = offset - text.lastIndexOf('\n', offset - 1) - 1;
    await client.change(uri, [
      { range: { start: { line, character }, end: { line, character: character + 'linear'.length } }, text: 'wobbly' },
    ]);
    const broken = await run(fileUri(path.join(root, 'main.xosc')));
    // esmini stops at the unknown shape before it simulates anything: the run did not happen, and says why.
    assert.equal(broken.outcome, 'failed', broken.message);
    assert.match(broken.message, /esmini did not run the scenario .*wobbly/);
    const [error] = broken.problems.filter((problem) => problem.severity === 'error');
    assert.equal(error.uri, uri);
    assert.equal(error.range.start.line, line);
    assert.match(error.message, /wobbly/);
    assert.equal(fs.readFileSync(simple, 'utf8'), text, 'the file on disk is untouched');
    assert.ok(!fs.existsSync(clean.csvFile), "the previous run's files are removed by the next run of the same file");
  });

  it('answers with what esmini runs otherwise than written (an Act it never starts), whatever the simulator setting (issue 27)', async function () {
    requireEsmini(this);
    const file = path.join(root, 'lane_change.xosc');
    const text = fs.readFileSync(file, 'utf8');
    // The paper's library's Act start: a rising edge of SimulationTime equalTo 0, which esmini never fires.
    const paper = text.replace(
      '<SimulationTimeCondition value="0" rule="greaterThan"/>',
      '<SimulationTimeCondition value="0" rule="equalTo"/>',
    );
    assert.notEqual(paper, text);
    fs.writeFileSync(file, paper);
    const result = await run(fileUri(file));
    assert.equal(result.outcome, 'ok', result.message);
    const line = paper.split('\n').findIndex((each) => each.includes('name="ActStart"'));
    assert.deepEqual(
      result.esminiFindings.map((finding) => [finding.uri, finding.line, finding.severity, finding.hint]),
      [[fileUri(file), line, 'warning', 'write conditionEdge="none" on this Condition: esmini then fires it when it is first evaluated']],
    );
    assert.match(result.esminiFindings[0].message, /^esmini checks a condition's edge only from its second evaluation/);
  });

  it("under the esmini setting, takes esmini's findings from the analysis the diagnostics show, without analysing the file again", async function () {
    requireEsmini(this);
    const file = path.join(root, 'lane_change.xosc');
    const paper = fs
      .readFileSync(file, 'utf8')
      .replace('<SimulationTimeCondition value="0" rule="greaterThan"/>', '<SimulationTimeCondition value="0" rule="equalTo"/>');
    fs.writeFileSync(file, paper);
    await client.settingsChanged({ simulator: 'esmini' });
    const uri = await client.openFile(file);
    const line = paper.split('\n').findIndex((each) => each.includes('name="ActStart"'));
    // The setting's analysis, shown: the finding the run answers with among its diagnostics.
    await client.diagnosticsOf(uri, (shown) => shown.some((diagnostic) => diagnostic.range.start.line === line));
    const analyze = Flattener.prototype.analyze;
    let analysedForEsmini = 0;
    Flattener.prototype.analyze = function (this: Flattener, main: SourceRef) {
      if (this.simulator === 'esmini') analysedForEsmini++;
      return analyze.call(this, main);
    };
    let result: RunEsminiResult;
    try {
      result = await run(uri);
    } finally {
      Flattener.prototype.analyze = analyze;
    }
    assert.equal(result.outcome, 'ok', result.message);
    assert.equal(analysedForEsmini, 0);
    assert.deepEqual(
      result.esminiFindings.map((finding) => [finding.uri, finding.line, finding.severity]),
      [[uri, line, 'warning']],
    );
    assert.match(result.esminiFindings[0].message, /^esmini checks a condition's edge only from its second evaluation/);
  });

  it('refuses a scenario with errors as forcible; with force (Run Anyway) runs it, listing the errors', async function () {
    requireEsmini(this);
    const main = path.join(root, 'main.xosc');
    const uri = await client.openFile(main);
    const text = fs.readFileSync(main, 'utf8');
    // A double parameter whose value is no number: an error by any policy, which esmini never reads.
    const at = text.indexOf('<ParameterDeclarations/>');
    const line = text.slice(0, at).split('\n').length - 1;
    const character = at - text.lastIndexOf('\n', at - 1) - 1;
    const declaration =
      '<ParameterDeclarations><ParameterDeclaration name="Pace" parameterType="double" value="fast"/></ParameterDeclarations>';
    await client.change(uri, [
      { range: { start: { line, character }, end: { line, character: character + '<ParameterDeclarations/>'.length } }, text: declaration },
    ]);
    const refused = await run(uri);
    assert.equal(refused.outcome, 'not-flattened', refused.message);
    assert.equal(refused.forcible, true);
    assert.match(refused.message, /^the scenario has 1 error; nothing was run$/);
    assert.equal(refused.csvFile, undefined);
    const [error] = refused.flattenProblems.filter((problem) => problem.severity === 'error');
    assert.equal(error.uri, uri);
    assert.equal(error.line, line);
    assert.match(error.message, /'fast' is not a double/);

    const forced = await run(uri, { force: true });
    assert.equal(forced.outcome, 'ok', forced.message);
    assert.equal(forced.forcible, undefined);
    assert.match(
      forced.message,
      /3\.00 s simulated: stopped at the 3 s limit set by the modular2simple\.esmini\.duration setting, before the scenario ended by itself.*\(run anyway despite 1 error in the scenario\)$/,
    );
    assert.deepEqual(
      forced.flattenProblems.filter((problem) => problem.severity === 'error'),
      [error],
    );
    assert.ok(forced.csvFile && fs.existsSync(forced.csvFile));

    // A group that does not exist leaves nothing to run, forced or not: no offer to run anyway.
    const group = text.indexOf('maneuverGroupName="') + 'maneuverGroupName="'.length;
    const groupLine = text.slice(0, group).split('\n').length - 1;
    const groupCharacter = group - text.lastIndexOf('\n', group - 1) - 1;
    await client.change(uri, [
      {
        range: { start: { line: groupLine, character: groupCharacter }, end: { line: groupLine, character: groupCharacter } },
        text: 'NoSuch',
      },
    ]);
    for (const force of [false, true]) {
      const missing = await run(uri, { force });
      assert.equal(missing.outcome, 'not-flattened', missing.message);
      assert.equal(missing.forcible, undefined);
      assert.match(missing.message, /cannot be flattened; nothing was run/);
    }
  });
});
