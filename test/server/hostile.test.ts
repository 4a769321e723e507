import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import { Diagnostic } from 'vscode-languageserver/node';
import { FlattenToFileRequest, FlattenToTextRequest, PackRequest } from '../../common/src/protocol';
import { mainOf, outerGroup, packageOf, scenario, simpleGroup } from '../support/fixtures';
import { rawZip } from '../support/hostile';
import { fileUri, TestClient } from './harness';
import { temporaryWorkspace } from '../support/workspace';

/** Exceptions the server logged: a failed handler logs "... failed:" with a stack. */
function loggedExceptions(client: TestClient): string[] {
  return client.logs.filter((line) => /failed:|\n\s+at .*:\d+:\d+/.test(line));
}

describe('language server with hostile input (JSON-RPC)', function () {
  this.timeout(180_000);

  it('a group imported twice at each of 20 levels is reported with its chain; the server process stays alive in 256 MB', async function () {
    const files: Record<string, string> = { 'l20.xosc': scenario(simpleGroup('G')) };
    for (let level = 0; level < 20; level++) {
      const half = (name: string) => outerGroup(name, 'car', [{ file: `l${level + 1}.xosc`, groups: [{ name: 'G' }] }]);
      files[`l${level}.xosc`] = scenario(
        `        <ManeuverGroup name="G" maximumExecutionCount="1">\n          <Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>\n${half('X')}${half('Y')}        </ManeuverGroup>\n`,
      );
    }
    const root = temporaryWorkspace(files);
    const client = await TestClient.start({ root, process: { heapMb: 256, watchdogMs: 170_000 } });
    try {
      const uri = await client.openFile(path.join(root, 'l0.xosc'));
      const diagnostics: Diagnostic[] = await client.diagnosticsOf(uri, (found) => found.length > 0, 150_000);
      const text = JSON.stringify(diagnostics);
      assert.match(text, /would exceed/);
      assert.match(text, /l\d+\.xosc -> \S*l\d+\.xosc/);
      const hover = await client.request('textDocument/hover', client.at(uri, { line: 8, character: 12 }));
      assert.ok(hover === null || typeof hover === 'object', 'the server still answers');
      assert.equal(client.exit, undefined, 'the server process is alive');
    } finally {
      await client.stop();
    }
  });

  describe('in one workspace', () => {
    let root: string;
    let client: TestClient;

    before(async function () {
      root = temporaryWorkspace({
        'main.xosc': mainOf('simple.xosc'),
        'simple.xosc': scenario(simpleGroup('Go')),
        'pkg/main.xosc': mainOf('inner.mosc'),
        'pkg/inner.mosc': await packageOf({ 'main.xosc': scenario(simpleGroup('Go')) }),
        'open.mosc': await packageOf({ 'main.xosc': mainOf('simple.xosc'), 'simple.xosc': scenario(simpleGroup('Go')) }),
        'dup.mosc': rawZip([
          { name: 'main.xosc', data: scenario(simpleGroup('Go')) },
          { name: './main.xosc', data: scenario(simpleGroup('Other')) },
        ]),
        'uses-dup.xosc': mainOf('dup.mosc'),
        'latin.xosc': Buffer.from(
          scenario(simpleGroup('Go'))
            .replace('encoding="UTF-8"', 'encoding="ISO-8859-1"')
            .replace('name="GoManeuver"', 'name="Gr\u00fc\u00dfe"'),
          'latin1',
        ),
        'broken.xosc': Buffer.from(scenario(simpleGroup('Go')).replace('name="GoManeuver"', 'name="Gr\u00fc\u00dfe"'), 'latin1'),
        'text.xosc': scenario(
          outerGroup('A', 'car', [{ file: 'latin.xosc', groups: [{ name: 'Go' }] }]) +
            outerGroup('B', 'car', [{ file: 'broken.xosc', groups: [{ name: 'Go' }] }]),
        ),
      });
      const overlap = rawZip(
        [
          { name: 'main.xosc', data: scenario(simpleGroup('Go')) },
          { name: 'pad.xosc', data: new Uint8Array(4 * 1024 * 1024), deflate: true },
        ],
        Array.from({ length: 200 }, (_, index) => ({ name: `s${index}.xosc`, of: 1 })),
      );
      fs.writeFileSync(path.join(root, 'overlap.mosc'), overlap);
      fs.writeFileSync(path.join(root, 'uses-overlap.xosc'), mainOf('overlap.mosc'));
      fs.writeFileSync(
        path.join(root, 'control.xosc'),
        scenario(simpleGroup('Go')).replace('name="GoManeuver"', 'name="Go\u0001"').replace('<Event name="Go"', '<Event name="&#xFFFE;"'),
      );
      fs.writeFileSync(path.join(root, 'uses-control.xosc'), mainOf('control.xosc'));
      fs.writeFileSync(
        path.join(root, 'dtd.xosc'),
        scenario(simpleGroup('Go'))
          .replace('<OpenSCENARIO>', '<!DOCTYPE OpenSCENARIO [<!ENTITY height "0.5">]>\n<OpenSCENARIO>')
          .replace('z="0"', 'z="&height;"'),
      );
      fs.writeFileSync(path.join(root, 'uses-dtd.xosc'), mainOf('dtd.xosc'));
      // A FIFO in the workspace: reading it would wait for a writer forever.
      execFileSync('mkfifo', [path.join(root, 'stuck.xosc')]);
      client = await TestClient.start({ root });
      await client.indexed();
    });

    it('indexes a workspace holding a FIFO named like a scenario, and reports the FIFO where it is referenced', async () => {
      const uri = await client.open(fileUri(path.join(root, 'fifo-user.xosc')), mainOf('stuck.xosc'));
      const diagnostics = await client.diagnosticsOf(uri, (found) => found.length > 0);
      assert.ok(
        diagnostics.some((diagnostic) => diagnostic.severity === 1),
        JSON.stringify(diagnostics),
      );
      await client.close(uri);
    });

    it('reads a file as its XML declaration says and reports invalid UTF-8 naming the byte, never as U+FFFD', async () => {
      const uri = await client.openFile(path.join(root, 'text.xosc'));
      const diagnostics = await client.diagnosticsOf(uri, (found) => found.length > 0);
      const text = JSON.stringify(diagnostics);
      assert.match(text, /'broken\.xosc' has 1 error: .*byte 0xfc at offset \d+ is not valid UTF-8/);
      assert.doesNotMatch(text, /latin\.xosc/);
      const hover = await client.request<{ contents: unknown } | null>('textDocument/hover', client.at(uri, { line: 9, character: 50 }));
      assert.doesNotMatch(JSON.stringify(hover), /\uFFFD/);
      await client.close(uri);
    });

    after(async () => {
      await client?.stop();
    });

    it('flattenToFile writes only .xosc files, asks before writing outside the workspace, never over an input', async () => {
      const input = fileUri(path.join(root, 'main.xosc'));
      const wrongKind = await client.send(FlattenToFileRequest, { uri: input, outputPath: path.join(root, 'notes.txt') });
      assert.equal(wrongKind.written, null);
      assert.match(wrongKind.problems[0].message, /must end in \.xosc/);
      assert.ok(!fs.existsSync(path.join(root, 'notes.txt')));
      const outside = path.join(path.dirname(root), `${path.basename(root)}-outside.xosc`);
      const asked = await client.send(FlattenToFileRequest, { uri: input, outputPath: outside });
      assert.equal(asked.written, null);
      assert.equal(asked.needsConfirmation, 'outsideWorkspace');
      assert.ok(!fs.existsSync(outside));
      const confirmed = await client.send(FlattenToFileRequest, { uri: input, outputPath: outside, outsideWorkspace: true });
      assert.equal(confirmed.written, outside);
      fs.rmSync(outside);
      const before = fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8');
      const overInput = await client.send(FlattenToFileRequest, { uri: input, outputPath: path.join(root, 'simple.xosc') });
      assert.equal(overInput.written, null);
      assert.equal(fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8'), before);
    });

    it('pack never writes over a package the folder references', async () => {
      const inner = path.join(root, 'pkg', 'inner.mosc');
      const before = fs.readFileSync(inner);
      const result = await client.send(PackRequest, { inputs: [fileUri(path.join(root, 'pkg'))], outputPath: inner });
      assert.equal(result.written, null);
      assert.match(JSON.stringify(result.problems), /refusing to overwrite/);
      assert.deepEqual(fs.readFileSync(inner), before);
    });

    it('a package holding main.xosc and ./main.xosc is refused on the reference', async () => {
      const uri = await client.openFile(path.join(root, 'uses-dup.xosc'));
      const diagnostics = await client.diagnosticsOf(uri, (found) => found.length > 0);
      assert.match(JSON.stringify(diagnostics), /holds the entry 'main\.xosc' twice/);
      await client.close(uri);
    });

    it('an open package overwritten with garbage is reported as a broken archive', async () => {
      const packagePath = path.join(root, 'open.mosc');
      const uri = `mosc:${packagePath}/main.xosc`;
      await client.open(uri, mainOf('simple.xosc'));
      const clean = await client.diagnosticsOf(uri);
      assert.ok(!clean.some((diagnostic) => diagnostic.severity === 1), JSON.stringify(clean));
      fs.writeFileSync(packagePath, 'this is no longer a ZIP archive');
      await client.connection.sendNotification('workspace/didChangeWatchedFiles', { changes: [{ uri: fileUri(packagePath), type: 2 }] });
      await client.change(uri, [{ text: mainOf('simple.xosc') + ' ' }]);
      const broken = await client.diagnosticsOf(uri, (found) => found.some((diagnostic) => diagnostic.severity === 1));
      const text = JSON.stringify(broken);
      assert.match(text, /not a readable ZIP archive/);
      assert.doesNotMatch(text, /cannot find 'simple\.xosc'/);
      await client.close(uri);
    });

    it('entries sharing one compressed stream are refused on the reference', async () => {
      const uri = await client.openFile(path.join(root, 'uses-overlap.xosc'));
      const diagnostics = await client.diagnosticsOf(uri, (found) => found.length > 0);
      assert.match(JSON.stringify(diagnostics), /overlap in the archive/);
      await client.close(uri);
    });

    it('control characters and references to non-characters are errors at their position in the file that holds them', async () => {
      const uri = await client.openFile(path.join(root, 'control.xosc'));
      const diagnostics = await client.diagnosticsOf(uri, (found) => found.length > 0);
      const lines = fs.readFileSync(path.join(root, 'control.xosc'), 'utf8').split('\n');
      const control = diagnostics.find((diagnostic) => /U\+0001 is not allowed/.test(String(diagnostic.message)));
      assert.ok(control, JSON.stringify(diagnostics));
      assert.equal(
        control.range.start.line,
        lines.findIndex((line) => line.includes('\u0001')),
      );
      assert.equal(control.range.start.character, lines[control.range.start.line].indexOf('\u0001'));
      assert.ok(diagnostics.some((diagnostic) => /'&#xFFFE;' names U\+FFFE/.test(String(diagnostic.message))));
      await client.close(uri);
      const user = await client.openFile(path.join(root, 'uses-control.xosc'));
      assert.match(JSON.stringify(await client.diagnosticsOf(user, (found) => found.length > 0)), /'control\.xosc' has 2 errors/);
      await client.close(user);
    });

    it('an internal DTD entity of a simple scenario is expanded in the flattened text', async () => {
      const result = await client.send(FlattenToTextRequest, { uri: fileUri(path.join(root, 'uses-dtd.xosc')) });
      assert.deepEqual(
        result.problems.filter((problem) => problem.severity === 'error'),
        [],
      );
      assert.match(result.text ?? '', /z="0\.5"/);
      assert.doesNotMatch(result.text ?? '', /&height;/);
    });

    it('random edits (seeded) never make the server log an exception', async () => {
      const uri = fileUri(path.join(root, 'main.xosc'));
      const original = fs.readFileSync(path.join(root, 'main.xosc'), 'utf8');
      await client.open(uri, original);
      let text = original;
      const pieces = [
        '<',
        '>',
        '"',
        '</ManeuverGroup>',
        '<ScenarioReference scenarioFileName="',
        'dup.mosc',
        'pkg/inner.mosc',
        '&#1;',
        '&#xFFFE;',
        '\u0000',
        '<!DOCTYPE x [<!ENTITY a "&a;&a;">]>',
        '&a;',
        'key="',
        'parameterAttributes="',
        'x="1" x="2"',
      ];
      const edit = fc.record({
        at: fc.nat(),
        remove: fc.nat({ max: 60 }),
        insert: fc.oneof(fc.constantFrom(...pieces), fc.string({ maxLength: 12 })),
      });
      const edits = fc.sample(fc.array(edit, { minLength: 150, maxLength: 150 }), { seed: 20260808, numRuns: 1 })[0];
      for (const [index, { at, remove, insert }] of edits.entries()) {
        const start = text.length === 0 ? 0 : at % text.length;
        const end = Math.min(text.length, start + remove);
        const lines = text.slice(0, start).split('\n');
        const endLines = text.slice(0, end).split('\n');
        await client.change(uri, [
          {
            range: {
              start: { line: lines.length - 1, character: lines[lines.length - 1].length },
              end: { line: endLines.length - 1, character: endLines[endLines.length - 1].length },
            },
            text: insert,
          },
        ]);
        text = text.slice(0, start) + insert + text.slice(end);
        if (index % 10 === 9) {
          await client.diagnosticsOf(uri, () => true, 30_000);
          await Promise.all([
            client.request('textDocument/hover', client.at(uri, { line: lines.length - 1, character: 0 })),
            client.request('textDocument/completion', client.at(uri, { line: lines.length - 1, character: 0 })),
            client.request('textDocument/documentSymbol', { textDocument: { uri } }),
          ]);
        }
      }
      await client.diagnosticsOf(uri, () => true, 30_000);
      await client.close(uri);
      assert.deepEqual(loggedExceptions(client), []);
    });
  });
});
