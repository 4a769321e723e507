import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as v8 from 'node:v8';
import * as vm from 'node:vm';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { FlatSource } from '../../server/src/core/flatten';
import { schemaProblems } from '../../server/src/core/diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { parseXml } from '../../server/src/core/xml';
import { DEFAULT_SETTINGS } from '../../server/src/settings';
import { SharedSources } from '../../server/src/sharedSources';
import { CachingFileSystem, Workspace } from '../../server/src/workspace';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { outerGroup, packageOf, scenario, simpleGroup } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

describe('core: the package cache is bounded by size', () => {
  it('keeps unpacked packages up to its bound and reads evicted ones again when needed', async () => {
    const padding = `<!-- ${'x'.repeat(1024 * 1024)} -->`;
    const files: Record<string, Uint8Array> = {};
    for (let index = 0; index < 12; index++)
      files[`p${index}.mosc`] = await packageOf({ 'main.xosc': scenario(simpleGroup(`Go${index}`)) + padding });
    const root = temporaryWorkspace(files);
    const store = new ScenarioStore({ root, scenarioPath: [], packageCacheBytes: 3 * 1024 * 1024 });
    for (let index = 0; index < 12; index++) await store.readPackage(diskRef(path.join(root, `p${index}.mosc`)));
    assert.ok(store.cachedPackageBytes <= 3 * 1024 * 1024, `${store.cachedPackageBytes} bytes held`);
    assert.ok(store.cachedPackageBytes > 0);
    // The first package was evicted long ago; it is read again, whole and correct.
    const text = await store.readText(childRef(diskRef(path.join(root, 'p0.mosc')), 'main.xosc'));
    assert.match(text, /name="Go0"/);
  });

  it('the server keeps file bytes up to its bound too', async () => {
    const root = temporaryWorkspace({ 'a.xosc': 'a'.repeat(600), 'b.xosc': 'b'.repeat(600) });
    const files = new CachingFileSystem(undefined, 1000);
    await files.readFile(path.join(root, 'a.xosc'));
    await files.readFile(path.join(root, 'b.xosc'));
    assert.equal(files.size, 600);
    assert.equal(Buffer.from((await files.readFile(path.join(root, 'a.xosc'))) as Uint8Array).toString(), 'a'.repeat(600));
  });

  it('the index reads each file once and keeps no bytes of its own; those an analysis reads are kept', async () => {
    const root = temporaryWorkspace({ 'a.xosc': scenario(simpleGroup('A')), 'b.xosc': scenario(simpleGroup('B')) });
    const workspace = new Workspace();
    workspace.configure([root], DEFAULT_SETTINGS);
    assert.equal(await workspace.indexAll(), 2);
    assert.deepEqual(
      (await workspace.indexedFiles()).map((entry) => entry.groups.map((group) => group.name)),
      [['A'], ['B']],
    );
    assert.equal(workspace.files.size, 0, 'the scan kept no bytes');
    await workspace.analyze(diskRef(path.join(root, 'a.xosc')));
    assert.equal(workspace.files.size, Buffer.byteLength(scenario(simpleGroup('A'))), 'the analysed file is kept');
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('the server keeps read sources up to an approximate size, least recently used out, those of open documents always', async () => {
    // A source of n characters counts about 30 n bytes.
    const sourceOf = (characters: number) =>
      Promise.resolve({ original: { document: { text: 'x'.repeat(characters) } }, text: undefined } as unknown as FlatSource);
    const sources = new SharedSources(30 * 1500, () => new Set(['open']));
    sources.set('open', sourceOf(1000));
    sources.set('a', sourceOf(1000));
    sources.set('b', sourceOf(1000));
    await new Promise((resolve) => setImmediate(resolve));
    assert.deepEqual(sources.keys(), ['open', 'b'], 'the oldest source not open went first');
    void sources.get('open');
    sources.set('c', sourceOf(1000));
    await new Promise((resolve) => setImmediate(resolve));
    assert.deepEqual(sources.keys(), ['open', 'c']);
    assert.equal(sources.size, 30 * 1000, 'an open document does not count');
  });

  it('a source kept while its document is open counts again once it closes, and goes past the bound', async () => {
    const sourceOf = (characters: number) =>
      Promise.resolve({ original: { document: { text: 'x'.repeat(characters) } }, text: undefined } as unknown as FlatSource);
    let kept = new Set(['main', 'imported']);
    const sources = new SharedSources(30 * 1500, () => kept);
    sources.set('main', sourceOf(1000));
    sources.set('imported', sourceOf(1000));
    sources.set('other', sourceOf(1000));
    await new Promise((resolve) => setImmediate(resolve));
    assert.deepEqual(sources.keys(), ['main', 'imported', 'other'], 'the kept ones do not count: all within the bound');
    assert.equal(sources.size, 30 * 1000);
    kept = new Set();
    sources.trim();
    assert.deepEqual(sources.keys(), ['other'], 'closed, the two oldest went');
    assert.equal(sources.size, 30 * 1000);
  });
});

/** A full garbage collection, after the current job (a WeakRef keeps its target until the job ends). */
async function collectGarbage(): Promise<void> {
  v8.setFlagsFromString('--expose-gc');
  const gc = vm.runInNewContext('gc') as () => void;
  // V8 rejects code caches made under other flags: the later tests of this process load the CLI's cached bundles.
  v8.setFlagsFromString('--no-expose-gc');
  // Twice, a turn of the event loop before each: what the last turn's callbacks still held is let go by the second.
  for (let round = 0; round < 2; round++) {
    await new Promise((resolve) => setImmediate(resolve));
    gc();
  }
}

describe('core: the last schema checks are bounded by size', () => {
  const fileText = (name: string) => scenario(simpleGroup(name));

  it('keeps checks up to its bound, least recently checked out; a file checked again after eviction gets the same findings', () => {
    const sizing = new SchemaCheckMemory();
    const first = schemaProblems(diskRef('/virtual/a.xosc'), parseXml(fileText('A')), sizing);
    assert.ok(first.length > 0, 'the fixture breaks the schema');
    const one = sizing.size;
    const memory = new SchemaCheckMemory(64, Math.floor(2.5 * one));
    for (const name of ['a', 'b', 'c'])
      schemaProblems(diskRef(`/virtual/${name}.xosc`), parseXml(fileText(name === 'a' ? 'A' : name)), memory);
    assert.deepEqual(memory.keys(), ['/virtual/b.xosc', '/virtual/c.xosc'], 'the least recently checked file went first');
    assert.ok(memory.size <= 2.5 * one, `${memory.size} bytes remembered`);
    const again = schemaProblems(diskRef('/virtual/a.xosc'), parseXml(fileText('A')), memory);
    assert.deepEqual(again, first);
    assert.deepEqual(memory.keys(), ['/virtual/c.xosc', '/virtual/a.xosc']);
  });

  it('keeps at most its number of files, however small they are', () => {
    const memory = new SchemaCheckMemory(2);
    for (const name of ['a', 'b', 'c']) schemaProblems(diskRef(`/virtual/${name}.xosc`), parseXml(fileText(name)), memory);
    assert.deepEqual(memory.keys(), ['/virtual/b.xosc', '/virtual/c.xosc']);
  });

  it('a remembered check keeps no parse tree', async () => {
    const memory = new SchemaCheckMemory();
    const tree = (() => {
      const document = parseXml(fileText('A'));
      schemaProblems(diskRef('/virtual/a.xosc'), document, memory);
      assert.ok(document.root);
      return new WeakRef(document.root);
    })();
    await collectGarbage();
    assert.equal(tree.deref(), undefined);
    assert.deepEqual(memory.keys(), ['/virtual/a.xosc']);
  });
});

describe('server: analyses of files not open are bounded like the shared sources', () => {
  it('lets their parse trees go past the bound, and analysing one again gives the same problems', async () => {
    const texts = Object.fromEntries(['a', 'b', 'c'].map((name) => [`${name}.xosc`, scenario(simpleGroup(name.toUpperCase()))]));
    const root = temporaryWorkspace(texts);
    // Room for about one read source (30 bytes a character).
    const workspace = new Workspace(Math.floor(30 * 1.5 * texts['a.xosc'].length));
    workspace.configure([root], DEFAULT_SETTINGS);
    const analyseA = async () => {
      const analysis = await workspace.analyze(diskRef(path.join(root, 'a.xosc')));
      assert.ok(analysis.source.original);
      const topElement = analysis.source.original.document.root;
      assert.ok(topElement);
      return { tree: new WeakRef(topElement), problems: analysis.problems };
    };
    const first = await analyseA();
    assert.ok(first.problems.length > 0);
    for (const name of ['b', 'c']) await workspace.analyze(diskRef(path.join(root, `${name}.xosc`)));
    await collectGarbage();
    assert.equal(first.tree.deref(), undefined, "a's parse tree was let go");
    const again = await analyseA();
    assert.deepEqual(again.problems, first.problems);
  });
});

describe('server: the files an open document reads are kept from its first analysis on', () => {
  it('an open main file importing more than the bound holds keeps every file it read: its next edit reads none again', async () => {
    const simpleNames = ['s0', 's1', 's2', 's3', 's4'];
    const texts: Record<string, string> = Object.fromEntries(
      simpleNames.map((name) => [`${name}.xosc`, scenario(simpleGroup(name.toUpperCase()))]),
    );
    texts['main.xosc'] = scenario(
      outerGroup(
        'Car',
        'car',
        simpleNames.map((name) => ({ file: `${name}.xosc`, groups: [{ name: name.toUpperCase() }] })),
      ),
    );
    const root = temporaryWorkspace(texts);
    // Room for about two of the five files read (30 bytes a character).
    const workspace = new Workspace(Math.floor(30 * 2.5 * texts['s0.xosc'].length));
    workspace.configure([root], DEFAULT_SETTINGS);
    const main = diskRef(path.join(root, 'main.xosc'));
    const uri = `file://${main.disk}`;
    workspace.documents.add(uri, TextDocument.create(uri, 'xml', 1, texts['main.xosc']), Promise.resolve(main));
    workspace.open(uri, main);
    const importedSources = async () => {
      const analysis = await workspace.analyze(main);
      const sources = analysis.source.links.map((link) => link.source);
      assert.equal(sources.length, simpleNames.length);
      return sources;
    };
    const first = await importedSources();
    const opened = workspace.documents.text(uri) as TextDocument;
    const end = opened.positionAt(opened.getText().length);
    const edited = TextDocument.update(opened, [{ range: { start: end, end }, text: '<!-- typed -->' }], 2);
    workspace.documents.setText(uri, edited);
    workspace.update(main);
    const afterEdit = await importedSources();
    assert.deepEqual(
      afterEdit.map((source, index) => (source === first[index] ? 'reused' : `${simpleNames[index]} read again`)),
      simpleNames.map(() => 'reused'),
    );
    // Closed, the files it read count against the bound again: about two of the five stay.
    workspace.close(uri);
    const held: string[] = [];
    for (const [index, name] of simpleNames.entries())
      if ((await workspace.source(diskRef(path.join(root, `${name}.xosc`)))) === afterEdit[index]) held.push(name);
    assert.ok(held.length <= 2, `still held after the document closed: ${held.join(', ')}`);
  });
});
