import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import * as archive from '../../client/src/packageArchive';
import { entryDate, readCentralDirectory } from '../../common/src/zip';
import { waitUntil } from '../support/wait';
import { temporaryFolder } from '../support/temporaryDirectory';

async function zip(entries: Record<string, string | Uint8Array>): Promise<Uint8Array> {
  const file = new JSZip();
  for (const [name, content] of Object.entries(entries)) file.file(name, content);
  return file.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
}

async function entriesOf(bytes: Uint8Array): Promise<Record<string, string>> {
  const file = await JSZip.loadAsync(bytes);
  const result: Record<string, string> = {};
  for (const entry of Object.values(file.files)) if (!entry.dir) result[entry.name] = await entry.async('string');
  return result;
}

describe('client: files inside .mosc packages (the mosc: file system)', () => {
  let folder: string;
  let outer: string;

  beforeEach(async () => {
    folder = temporaryFolder('m2s-archive-');
    outer = path.join(folder, 'outer.mosc');
    const inner = await zip({ 'main.xosc': '<inner-main/>', 'simple.xosc': '<inner-simple/>' });
    fs.writeFileSync(outer, await zip({ 'main.xosc': '<outer-main/>', 'inner.mosc': inner, 'lib/shared.xosc': '<shared/>' }));
  });

  afterEach(() => fs.rmSync(folder, { recursive: true, force: true }));

  it('locates the archive on disk, the nested packages and the entry of a package path', async () => {
    assert.deepEqual(await archive.locate(`${outer}/inner.mosc/simple.xosc`), {
      disk: outer,
      nested: ['inner.mosc'],
      inner: 'simple.xosc',
    });
    assert.deepEqual(await archive.locate(`${outer}/lib/shared.xosc`), { disk: outer, nested: [], inner: 'lib/shared.xosc' });
    assert.deepEqual(await archive.locate(outer), { disk: outer, nested: [], inner: '' });
    await assert.rejects(archive.locate(path.join(folder, 'none.mosc', 'main.xosc')), { code: 'not-found' });
  });

  it('reads, stats and lists entries, nested packages as folders', async () => {
    assert.equal(
      Buffer.from(await archive.readEntry(await archive.locate(`${outer}/inner.mosc/simple.xosc`))).toString(),
      '<inner-simple/>',
    );
    assert.deepEqual(await archive.listFolder(await archive.locate(outer)), [
      ['inner.mosc', 'directory'],
      ['lib', 'directory'],
      ['main.xosc', 'file'],
    ]);
    assert.equal((await archive.stat(await archive.locate(`${outer}/lib`))).kind, 'directory');
    assert.equal((await archive.stat(await archive.locate(`${outer}/main.xosc`))).size, '<outer-main/>'.length);
    await assert.rejects(archive.stat(await archive.locate(`${outer}/missing.xosc`)), { code: 'not-found' });
    assert.deepEqual(await archive.listAll(await archive.locate(outer)), [
      'main.xosc',
      'inner.mosc',
      'inner.mosc/main.xosc',
      'inner.mosc/simple.xosc',
      'lib/shared.xosc',
    ]);
  });

  it('saves an entry two packages deep and keeps every other entry', async () => {
    await archive.writeEntry(await archive.locate(`${outer}/inner.mosc/simple.xosc`), Buffer.from('<changed/>'), {
      create: false,
      overwrite: true,
    });
    const top = await entriesOf(fs.readFileSync(outer));
    assert.equal(top['main.xosc'], '<outer-main/>');
    assert.equal(top['lib/shared.xosc'], '<shared/>');
    const inner = await entriesOf(await (await JSZip.loadAsync(fs.readFileSync(outer))).file('inner.mosc')!.async('uint8array'));
    assert.deepEqual(inner, { 'main.xosc': '<inner-main/>', 'simple.xosc': '<changed/>' });
    assert.deepEqual(fs.readdirSync(folder), ['outer.mosc'], 'a temporary file was left behind');
  });

  it('keeps every change when several entries of one archive are saved at once (Save All)', async () => {
    const saves = ['main.xosc', 'lib/shared.xosc', 'inner.mosc/main.xosc', 'inner.mosc/simple.xosc'].map(async (entry, index) =>
      archive.writeEntry(await archive.locate(`${outer}/${entry}`), Buffer.from(`<saved-${index}/>`), { create: false, overwrite: true }),
    );
    await Promise.all(saves);
    const top = await entriesOf(fs.readFileSync(outer));
    assert.equal(top['main.xosc'], '<saved-0/>');
    assert.equal(top['lib/shared.xosc'], '<saved-1/>');
    const inner = await entriesOf(await (await JSZip.loadAsync(fs.readFileSync(outer))).file('inner.mosc')!.async('uint8array'));
    assert.deepEqual(inner, { 'main.xosc': '<saved-2/>', 'simple.xosc': '<saved-3/>' });
  });

  it('dates each entry on its own, so saving one file leaves the others unchanged', async function () {
    // ZIP dates have a resolution of two seconds.
    const simple = await archive.locate(`${outer}/inner.mosc/simple.xosc`);
    const shared = await archive.locate(`${outer}/lib/shared.xosc`);
    const [simpleBefore, sharedBefore] = [await archive.stat(simple), await archive.stat(shared)];
    const step = Math.floor(Date.now() / 2000);
    await waitUntil(() => Math.floor(Date.now() / 2000) > step, 'the clock to reach the next two-second ZIP date', 2100);
    await archive.writeEntry(shared, Buffer.from('<shared changed="yes"/>'), { create: false, overwrite: true });
    assert.equal((await archive.stat(simple)).mtime, simpleBefore.mtime);
    assert.ok((await archive.stat(shared)).mtime > sharedBefore.mtime, 'the saved entry keeps its old date');
  });

  it("reads each entry's date with the package reader exactly as JSZip, which writes the packages, dates it", async () => {
    const dates = [
      new Date(Date.UTC(2024, 2, 5, 13, 47, 58)),
      new Date(Date.UTC(1999, 11, 31, 23, 59, 58)),
      new Date(Date.UTC(2107, 0, 1, 0, 0, 0)),
    ];
    const file = new JSZip();
    dates.forEach((date, index) => file.file(`entry${index}.xosc`, '<x/>', { date }));
    const bytes = await file.generateAsync({ type: 'uint8array' });
    const read = readCentralDirectory(bytes, 10).map(entryDate);
    assert.deepEqual(read, dates);
    assert.deepEqual(
      read,
      Object.values((await JSZip.loadAsync(bytes)).files).map((entry) => entry.date),
    );
  });

  it('creates, renames and deletes entries, and refuses what would lose data', async () => {
    const created = await archive.locate(`${outer}/new.xosc`);
    await assert.rejects(archive.writeEntry(created, Buffer.from('x'), { create: false, overwrite: true }), { code: 'not-found' });
    await archive.writeEntry(created, Buffer.from('<new/>'), { create: true, overwrite: false });
    await assert.rejects(archive.writeEntry(created, Buffer.from('y'), { create: true, overwrite: false }), { code: 'exists' });
    await archive.renameEntry(created, await archive.locate(`${outer}/renamed.xosc`), false);
    await assert.rejects(
      archive.renameEntry(await archive.locate(`${outer}/renamed.xosc`), await archive.locate(`${outer}/main.xosc`), false),
      { code: 'exists' },
    );
    await archive.deleteEntry(await archive.locate(`${outer}/lib`));
    assert.deepEqual(Object.keys(await entriesOf(fs.readFileSync(outer))).sort(), ['inner.mosc', 'main.xosc', 'renamed.xosc']);
  });

  it('reports a broken archive and never overwrites it', async () => {
    const broken = path.join(folder, 'broken.mosc');
    const bytes = Buffer.concat([Buffer.from('PK\x03\x04'), Buffer.alloc(64, 7)]);
    fs.writeFileSync(broken, bytes);
    await assert.rejects(
      archive.locate(`${broken}/main.xosc`),
      (error: archive.PackageError) => error.code === 'broken' && /ZIP/.test(error.message),
    );
    const location: archive.PackageLocation = { disk: broken, nested: [], inner: 'main.xosc' };
    await assert.rejects(archive.writeEntry(location, Buffer.from('<x/>'), { create: true, overwrite: true }), { code: 'broken' });
    assert.deepEqual(fs.readFileSync(broken), bytes);
  });

  it('never reads a path that climbs out of its package', async () => {
    await assert.rejects(archive.locate(`${outer}/../outside.xosc`), { code: 'not-found' });
    await assert.rejects(archive.locate(`${outer}/inner.mosc/../../x.xosc`), { code: 'not-found' });
  });
});
