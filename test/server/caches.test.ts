import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { FlatSource } from '../../server/src/core/flatten';
import { CachingFileSystem, SharedSources } from '../../server/src/workspace';
import { packageOf, scenario, simpleGroup } from '../support/fixtures';
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
});
