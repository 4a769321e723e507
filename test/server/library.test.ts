import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CompletionItem, Hover, Location, MarkupContent } from 'vscode-languageserver/node';
import { builtInLibraryFolder } from '../../server/src/libraries';
import { at, cursor } from '../support/cursor';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

/** library:NAME in the editor (issue 28, item 3): it resolves, hovers, goes to the module, completes; the user's folders come first. */
describe('language server: scenario library modules (JSON-RPC)', function () {
  const builtIn = builtInLibraryFolder() ?? '';
  const example = fs
    .readFileSync(path.join(builtIn, 'examples', 'cut-in.xosc'), 'utf8')
    .replace('filepath="../roads/', `filepath="${builtIn}/roads/`);
  let root: string;
  let client: TestClient;
  let mainUri: string;

  before(async function () {
    const userModule = fs
      .readFileSync(path.join(builtIn, 'lead-brake.xosc'), 'utf8')
      .replace('value="1.5" freespace', 'value="2.5" freespace');
    root = temporaryWorkspace({ 'main.xosc': example, 'mine/lead-brake.xosc': userModule });
    client = await TestClient.start({ root, settings: { library: { folders: ['mine'] } } });
    await client.indexed();
    mainUri = await client.openFile(path.join(root, 'main.xosc'));
  });
  after(() => client?.stop());

  it('a main naming library:cut-in has no problem: the module resolves in the built-in library', async function () {
    const diagnostics = await client.diagnosticsOf(mainUri);
    assert.deepEqual(
      diagnostics.map((diagnostic) => diagnostic.message),
      [],
    );
  });

  it('hover on the name says where it was found; F12 opens the module', async function () {
    const hover = await client.request<Hover>('textDocument/hover', client.at(mainUri, at(example, 'scenarioFileName="libr|ary:cut-in"')));
    assert.match((hover.contents as MarkupContent).value, /found at .*library\/cut-in\.xosc/);
    const [location] = await client.request<Location[]>(
      'textDocument/definition',
      client.at(mainUri, at(example, 'scenarioFileName="libr|ary:cut-in"')),
    );
    assert.equal(location.uri, fileUri(path.join(builtIn, 'cut-in.xosc')));
  });

  it("completion of scenarioFileName offers the library's modules, a module of the user's folder before the built-in one it hides", async function () {
    const typed = cursor(example.replace('scenarioFileName="library:cut-in"', 'scenarioFileName="|"'));
    const uri = await client.open(fileUri(path.join(root, 'typing.xosc')), typed.text);
    const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, typed.position));
    await client.close(uri);
    const labels = items.map((item) => item.label);
    for (const name of ['library:cut-in', 'library:lead-brake', 'library:pedestrian-crossing'])
      assert.ok(labels.includes(name), labels.join(', '));
    assert.equal(labels.filter((label) => label === 'library:lead-brake').length, 1);
    const leadBrake = items.find((item) => item.label === 'library:lead-brake');
    assert.match(JSON.stringify(leadBrake), /user library/);
  });

  it("the setting modular2simple.library.folders puts the user's module first: F12 goes to it", async function () {
    const text = example.replace('library:cut-in', 'library:lead-brake');
    const uri = await client.open(fileUri(path.join(root, 'lead.xosc')), text);
    const [location] = await client.request<Location[]>(
      'textDocument/definition',
      client.at(uri, at(text, 'scenarioFileName="libr|ary:lead-brake"')),
    );
    assert.equal(location.uri, fileUri(path.join(root, 'mine', 'lead-brake.xosc')));
    await client.close(uri);
  });
});
