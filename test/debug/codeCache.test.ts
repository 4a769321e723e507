import { DebugClient } from '@vscode/debugadapter-testsupport';
import * as assert from 'node:assert/strict';
import { ChildProcess } from 'node:child_process';
import { once } from 'node:events';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { DEBUG_CODE_CACHE_ENV } from '../../common/src/debugState';
import { codeCacheFile, readCodeCache, writeCodeCache } from '../../server/src/debug/codeCache';
import { esminiCatalogs, esminiRoads } from '../support/esmini';
import { requireEsminiLibrary } from '../support/esminiBinaries';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const dist = path.join(repoRoot, 'dist');
const cutIn = path.join(openscenarioDir, 'esmini', 'cut-in.xosc');

describe("debug adapter: V8's code cache of the session's bundle, kept in the editor's storage", function () {
  this.timeout(120_000);

  it('reads back what it wrote, and nothing from a missing, torn, corrupt or foreign file', () => {
    const folder = temporaryFolder();
    const bundle = path.join(folder, 'debugSession.js');
    fs.writeFileSync(bundle, 'exports.x = 1;\n');
    const file = codeCacheFile(path.join(folder, 'cache'), bundle);
    assert.equal(readCodeCache(file), undefined, 'none yet');
    const data = Buffer.from('V8 code cache bytes '.repeat(50));
    writeCodeCache(file, data);
    assert.deepEqual(readCodeCache(file), data);
    const written = fs.readFileSync(file);
    fs.writeFileSync(file, written.subarray(0, written.length - 7));
    assert.equal(readCodeCache(file), undefined, 'torn');
    const flipped = Buffer.from(written);
    flipped[flipped.length - 3] ^= 0x20;
    fs.writeFileSync(file, flipped);
    assert.equal(readCodeCache(file), undefined, 'a byte changed');
    fs.writeFileSync(file, Buffer.concat([Buffer.from('NOTOURS!'), written.subarray(8)]));
    assert.equal(readCodeCache(file), undefined, 'another header');
    // Another build of the bundle (another size or time) has another file; writing it removes this bundle's others.
    writeCodeCache(file, data);
    fs.appendFileSync(bundle, '// rebuilt\n');
    const rebuilt = codeCacheFile(path.join(folder, 'cache'), bundle);
    assert.notEqual(rebuilt, file);
    assert.equal(readCodeCache(rebuilt), undefined);
    writeCodeCache(rebuilt, data);
    assert.deepEqual(fs.readdirSync(path.join(folder, 'cache')), [path.basename(rebuilt)]);
  });

  describe('sessions of the built adapter (dist/debugAdapter.js) with a cache folder', () => {
    before(function () {
      requireEsminiLibrary(this);
      if (!fs.existsSync(path.join(dist, 'debugSession.js')) || !fs.existsSync(cutIn)) {
        console.log('    (skipped: npm run build first, and the corpus cut-in.xosc)');
        this.skip();
      }
    });

    /** One session of cut-in.xosc run to its end, as the editor starts it with the cache folder: the adapter's stderr. */
    async function session(cacheFolder: string): Promise<string> {
      const client = new DebugClient(process.execPath, path.join(dist, 'debugAdapter.js'), 'modular2simple', {
        env: { ...process.env, [DEBUG_CODE_CACHE_ENV]: cacheFolder },
        stdio: ['pipe', 'pipe', 'pipe'],
      });
      client.defaultTimeout = 60_000;
      await client.start();
      const adapter = (client as unknown as { _adapterProcess?: ChildProcess })._adapterProcess;
      assert.ok(adapter);
      const closed = once(adapter, 'close');
      let stderr = '';
      adapter.stderr?.on('data', (chunk: Buffer) => (stderr += chunk.toString()));
      const terminated = client.waitForEvent('terminated');
      const roadPath = [esminiRoads, path.join(esminiCatalogs, 'Vehicles')];
      const launched = client.launch({ type: 'modular2simple', request: 'launch', program: cutIn, roadPath });
      await client.waitForEvent('initialized');
      await client.configurationDoneRequest();
      await launched;
      await terminated;
      await client.stop();
      // The session writes its cache as its process exits; the adapter's process ends after it.
      await closed;
      return stderr;
    }

    it('the first session writes it, the next one reads it (V8 takes it: not written again), a corrupt one is written anew', async () => {
      const cacheFolder = path.join(temporaryFolder(), 'debug-code-cache');
      const file = codeCacheFile(cacheFolder, path.join(dist, 'debugSession.js'));
      assert.equal(await session(cacheFolder), '');
      const first = fs.statSync(file);
      assert.ok(readCodeCache(file), 'a whole cache after the first session');
      assert.equal(await session(cacheFolder), '');
      assert.equal(fs.statSync(file).ino, first.ino, 'the second session took the cache and left it');
      // A cache whose bytes changed is ignored: the session runs as without one, and writes it whole again.
      const corrupt = fs.readFileSync(file);
      corrupt[corrupt.length >> 1] ^= 0xff;
      fs.writeFileSync(file, corrupt);
      assert.equal(await session(cacheFolder), '');
      assert.ok(readCodeCache(file), 'written anew');
      assert.deepEqual(fs.readdirSync(cacheFolder), [path.basename(file)]);
    });
  });
});
