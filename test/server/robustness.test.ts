import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import JSZip from 'jszip';
import { CompletionItem, Diagnostic, DocumentSymbol, Location } from 'vscode-languageserver/node';
import { FlattenToTextRequest, StructureRequest } from '../../common/src/protocol';
import { SIMPLE } from './fixtures/scenarios';
import { fileUri, TestClient } from './harness';
import { positionAt } from '../support/cursor';
import { caseStudyDir, libraryDir, requireCorpus } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

const simple = SIMPLE;

function referenceTo(fileName: string, group = 'Brake'): string {
  return `<ManeuverGroup name="G_${fileName.replace(/\W/g, '_')}"><Actors><EntityRef entityRef="hero"/></Actors>
  <ScenarioReference scenarioFileName="${fileName}"><ManeuverGroupReference maneuverGroupName="${group}"/></ScenarioReference>
</ManeuverGroup>`;
}

/** A main file referencing every broken input, so that each is read, unpacked and parsed. */
function mainReferencing(fileNames: string[]): string {
  return `<?xml version="1.0"?>
<OpenSCENARIO><Entities><ScenarioObject name="hero"/></Entities><Storyboard><Story name="S"><Act name="A">
${fileNames.map((name) => referenceTo(name)).join('\n')}
</Act></Story></Storyboard></OpenSCENARIO>
`;
}

/** Every kind of request the server answers, at one position; resolves when all got an answer. */
async function askEverything(client: TestClient, uri: string, position: { line: number; character: number }): Promise<void> {
  const at = client.at(uri, position);
  await Promise.all([
    client.request('textDocument/definition', at),
    client.request('textDocument/hover', at),
    client.request('textDocument/completion', at),
    client.request('textDocument/references', { ...at, context: { includeDeclaration: true } }),
    client.request('textDocument/documentSymbol', { textDocument: { uri } }),
    client.request('textDocument/codeLens', { textDocument: { uri } }),
    client.request('textDocument/codeAction', {
      textDocument: { uri },
      range: { start: position, end: position },
      context: { diagnostics: [] },
    }),
    client.request('workspace/symbol', { query: 'a' }),
    client.send(StructureRequest, { uri }),
  ]);
}

describe('language server with bad input', function () {
  this.timeout(120_000);
  let root: string;
  let client: TestClient;

  before(async function () {
    const good = new JSZip();
    good.file('main.xosc', simple);
    const goodBytes = await good.generateAsync({ type: 'uint8array' });
    const bomb = new JSZip();
    bomb.file('main.xosc', new Uint8Array(80 * 1024 * 1024), { compression: 'DEFLATE' });
    const deep = '<OpenSCENARIO>' + '<a>'.repeat(100_000) + '</a>'.repeat(100_000) + '</OpenSCENARIO>';
    const bigGroup = simple.slice(simple.indexOf('<ManeuverGroup name="Wait"'), simple.indexOf('</Act>'));
    let big = simple.slice(0, simple.indexOf('</Act>'));
    while (big.length < 20 * 1024 * 1024) big += bigGroup;
    big += simple.slice(simple.indexOf('</Act>'));
    const garbage = new Uint8Array(64 * 1024);
    for (let i = 0; i < garbage.length; i++) garbage[i] = (i * 7919 + 13) % 256;
    const names = ['garbage.xosc', 'truncated.mosc', 'bomb.mosc', 'big.xosc', 'deep.xosc', 'self.xosc', 'garbage.mosc', 'empty.xosc'];
    root = temporaryWorkspace({
      'garbage.xosc': garbage,
      'garbage.mosc': garbage,
      'truncated.mosc': goodBytes.slice(0, Math.floor(goodBytes.length / 2)),
      'bomb.mosc': await bomb.generateAsync({ type: 'uint8array', compression: 'DEFLATE' }),
      'big.xosc': big,
      'deep.xosc': deep,
      'empty.xosc': '',
      'self.xosc': mainReferencing(['self.xosc']),
      'main.xosc': mainReferencing(names),
    });
    client = await TestClient.start({ root });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('reports each broken input on its reference and goes on answering', async function () {
    const uri = await client.openFile(path.join(root, 'main.xosc'));
    // It reads a 20 MB file and inflates a bomb: seconds on a busy machine.
    const diagnostics: Diagnostic[] = await client.diagnosticsOf(uri, () => true, 60_000);
    const onLine = (fileName: string) =>
      diagnostics.filter(
        (diagnostic) =>
          diagnostic.range.start.line ===
          fs
            .readFileSync(path.join(root, 'main.xosc'), 'utf8')
            .split('\n')
            .findIndex((line) => line.includes(`"${fileName}"`)),
      );
    for (const fileName of ['garbage.xosc', 'truncated.mosc', 'bomb.mosc', 'deep.xosc', 'self.xosc', 'garbage.mosc', 'empty.xosc']) {
      assert.ok(
        onLine(fileName).some((diagnostic) => diagnostic.severity === 1),
        `an error on the reference to ${fileName}: ${JSON.stringify(diagnostics.map((d) => [d.range.start.line, d.message]))}`,
      );
    }
    assert.ok(
      onLine('bomb.mosc').some(
        (diagnostic) =>
          /more than .* bytes/.test(String(diagnostic.message)) || /more than/.test(JSON.stringify(diagnostic.relatedInformation)),
      ),
    );
    assert.ok(!onLine('big.xosc').some((diagnostic) => diagnostic.severity === 1), 'the 20 MB file is valid and read');
    const text = fs.readFileSync(path.join(root, 'main.xosc'), 'utf8');
    for (let offset = 0; offset < text.length; offset += 97) await askEverything(client, uri, positionAt(text, offset));
  });

  it('answers on an open 20 MB file and a deeply nested one', async function () {
    for (const name of ['big.xosc', 'deep.xosc']) {
      const uri = await client.openFile(path.join(root, name));
      const started = Date.now();
      const diagnostics = await client.diagnosticsOf(uri, () => true, 60_000);
      assert.ok(diagnostics.length <= 1000, `${name}: ${diagnostics.length} diagnostics in ${Date.now() - started} ms`);
      const symbols = await client.request<DocumentSymbol[]>('textDocument/documentSymbol', { textDocument: { uri } });
      assert.ok(Array.isArray(symbols));
      await askEverything(client, uri, { line: 0, character: 20 });
      await client.close(uri);
    }
  });

  it('survives files vanishing while the workspace is indexed', async function () {
    const files: Record<string, string> = {};
    for (let i = 0; i < 400; i++) files[`many/s${i}.xosc`] = simple;
    const folder = temporaryWorkspace(files);
    const other = await TestClient.start({ root: folder });
    fs.rmSync(path.join(folder, 'many'), { recursive: true });
    await other.indexed();
    const symbols = await other.request<unknown[]>('workspace/symbol', { query: 'Brake' });
    assert.ok(Array.isArray(symbols));
    await other.stop();
    fs.rmSync(folder, { recursive: true, force: true });
  });

  it('rejects a request on a URI that is no scenario with an error, and keeps answering', async function () {
    await assert.rejects(client.send(FlattenToTextRequest, { uri: 'http://example.com/x' }), /not a scenario URI/);
    const result = await client.send(FlattenToTextRequest, { uri: fileUri(path.join(root, 'big.xosc')) });
    assert.ok(result.text && result.text.length > 20 * 1024 * 1024 - 100_000);
  });
});

/** Random edits to a text: deletions, insertions of XML-ish or binary noise, duplications and truncation. */
const mutation = fc.oneof(
  fc.record({ kind: fc.constant('delete' as const), at: fc.nat(), length: fc.nat({ max: 400 }) }),
  fc.record({
    kind: fc.constant('insert' as const),
    at: fc.nat(),
    text: fc.oneof(
      fc.string({ maxLength: 30 }),
      fc.constantFrom(
        '<',
        '>',
        '"',
        "'",
        '</ManeuverGroup>',
        '<ScenarioReference scenarioFileName="',
        'key="',
        '&amp;',
        '<!DOCTYPE x [<!ENTITY a "b">]>',
        '\u0000',
        '\uFFFF',
      ),
    ),
  }),
  fc.record({ kind: fc.constant('duplicate' as const), at: fc.nat(), length: fc.nat({ max: 2000 }) }),
  fc.record({ kind: fc.constant('truncate' as const), at: fc.nat() }),
);
type Mutation = typeof mutation extends fc.Arbitrary<infer T> ? T : never;

function mutate(text: string, mutations: Mutation[]): string {
  let result = text;
  for (const change of mutations) {
    const at = result.length === 0 ? 0 : change.at % result.length;
    if (change.kind === 'delete') result = result.slice(0, at) + result.slice(at + change.length);
    else if (change.kind === 'insert') result = result.slice(0, at) + change.text + result.slice(at);
    else if (change.kind === 'duplicate') result = result.slice(0, at) + result.slice(at, at + change.length) + result.slice(at);
    else result = result.slice(0, at);
  }
  return result;
}

describe('language server under random mutations of corpus files (property)', function () {
  this.timeout(180_000);
  let client: TestClient;

  before(async function () {
    requireCorpus(this);
    client = await TestClient.start({ root: caseStudyDir });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
  });

  it('answers every request on every mutated file', async function () {
    const sources = ['main.xosc', 'simple_1.xosc', 'simple_2.xosc', 'modular_1/main.xosc'].map((name) => path.join(caseStudyDir, name));
    sources.push(path.join(libraryDir, 'modular_hero_right_left_front_back_pedestrian', 'main.xosc'));
    let run = 0;
    await fc.assert(
      fc.asyncProperty(
        fc.constantFrom(...sources),
        fc.array(mutation, { minLength: 1, maxLength: 6 }),
        fc.array(fc.nat(), { minLength: 3, maxLength: 3 }),
        async (source, mutations, cursorSeeds) => {
          // Each run opens the mutated text in place of the real file, as an editor's unsaved buffer.
          const uri = fileUri(source);
          const text = mutate(fs.readFileSync(source, 'utf8'), mutations);
          run++;
          await client.open(uri, text);
          await client.diagnosticsOf(uri);
          for (const seed of cursorSeeds)
            await askEverything(client, uri, positionAt(text, text.length === 0 ? 0 : seed % (text.length + 1)));
          await client.close(uri);
        },
      ),
      { numRuns: 60 },
    );
    assert.equal(run >= 60, true);
    const uri = await client.openFile(path.join(caseStudyDir, 'main.xosc'));
    const completion = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, { line: 308, character: 57 }));
    assert.ok(completion.length > 0, 'the server still completes after the mutations');
    const definition = await client.request<Location[]>('textDocument/definition', client.at(uri, { line: 309, character: 80 }));
    assert.equal(definition.length, 1);
  });
});
