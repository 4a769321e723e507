import { readdirSync, readFileSync, renameSync, rmSync, mkdirSync, statSync, writeFileSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import type { Script } from 'node:vm';
import { DEBUG_CODE_CACHE_ENV } from '../../../common/src/debugState';
import { loadModuleBundle } from '../bundleLoader';

/**
 * V8's code cache of the session's bundle (dist/debugSession.js), written at run time into a folder the editor names
 * (the extension's storage, CODE_CACHE_ENV): V8 takes a cache only from its own build, and VS Code runs the adapter on
 * its own runtime (Electron's Node), so a cache the build wrote would be rejected there. One file per bundle and
 * runtime, named by both; a file whose header does not match its bytes (torn, corrupt) is ignored, as is one V8
 * rejects: the bundle is then compiled as usual, and the cache is written again when the session ends.
 */
export const CODE_CACHE_ENV = DEBUG_CODE_CACHE_ENV;

/** The cache file's header: this magic, then the CRC-32 and the length of V8's data after it (little-endian). */
const MAGIC = Buffer.from('M2SCODE1', 'latin1');
const HEADER_BYTES = MAGIC.length + 8;

/** What one process read of a bundle's cache, and where it writes it. */
export interface CodeCache {
  file: string;
  data: Buffer | undefined;
}

/** The cache file of a bundle for this runtime: the bundle's size and time, V8's version and the machine in its name. */
export function codeCacheFile(folder: string, bundle: string): string {
  const stat = statSync(bundle);
  const runtime = `${process.versions.v8}-${process.arch}`.replace(/[^\w.-]/g, '_');
  return join(folder, `${basename(bundle)}-${stat.size}-${Math.trunc(stat.mtimeMs)}-v8-${runtime}.cache`);
}

/** V8's data of a cache file whose header matches it; undefined when there is none, or it is torn or corrupt. */
export function readCodeCache(file: string): Buffer | undefined {
  let bytes: Buffer;
  try {
    bytes = readFileSync(file);
  } catch {
    return undefined;
  }
  if (bytes.length < HEADER_BYTES || !bytes.subarray(0, MAGIC.length).equals(MAGIC)) return undefined;
  const data = bytes.subarray(HEADER_BYTES);
  const crc = bytes.readUInt32LE(MAGIC.length);
  const length = bytes.readUInt32LE(MAGIC.length + 4);
  return length === data.length && crc32Of(data) === crc ? data : undefined;
}

/** Writes V8's data whole or not at all (a new name, then renamed), and removes this bundle's caches of other builds. */
export function writeCodeCache(file: string, data: Buffer): void {
  const folder = dirname(file);
  mkdirSync(folder, { recursive: true });
  const crc = crc32Of(data);
  if (crc === undefined) return;
  const header = Buffer.alloc(HEADER_BYTES);
  MAGIC.copy(header);
  header.writeUInt32LE(crc, MAGIC.length);
  header.writeUInt32LE(data.length, MAGIC.length + 4);
  const partial = `${file}.${process.pid}.partial`;
  writeFileSync(partial, Buffer.concat([header, data]));
  renameSync(partial, file);
  const bundlePrefix = basename(file).slice(0, basename(file).indexOf('-') + 1);
  for (const name of readdirSync(folder))
    if (name !== basename(file) && name.startsWith(bundlePrefix) && name.endsWith('.cache')) rmSync(join(folder, name), { force: true });
}

/** Node's CRC-32 (Node 20.15 and later; an older runtime, an older Electron, has none and keeps no cache). */
function crc32Of(data: Buffer): number | undefined {
  const { crc32 } = require('node:zlib') as Partial<typeof import('node:zlib')>;
  return typeof crc32 === 'function' ? crc32(data) : undefined;
}

/**
 * Loads a bundle of `folder` with its cache from `cacheFolder`; when there was none, or V8 rejected it, the cache is
 * written as the process exits, after the session, so that it holds the functions the session compiled too. A cache
 * that cannot be written (a read-only storage) is left: the next session compiles as this one did.
 */
export function loadWithCodeCache<Exports>(
  folder: string,
  bundleFile: string,
  requireFn: NodeJS.Require,
  cacheFolder: string,
): { exports: Exports; script: Script; cache: CodeCache } {
  let cache: CodeCache | undefined;
  try {
    const file = codeCacheFile(cacheFolder, join(folder, bundleFile));
    cache = { file, data: readCodeCache(file) };
  } catch {
    // No cache to name (the bundle unreadable here is reported by its load below).
  }
  const { exports, script } = loadModuleBundle<Exports>(folder, requireFn, cache?.data, bundleFile);
  const file = cache?.file;
  if (file && (cache?.data === undefined || script.cachedDataRejected))
    process.once('exit', () => {
      try {
        writeCodeCache(file, script.createCachedData());
      } catch {
        // Not written: the cache only saves time, and the session has ended as it should.
      }
    });
  return { exports, script, cache: cache ?? { file: '', data: undefined } };
}
