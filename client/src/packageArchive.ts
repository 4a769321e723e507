import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { writeFileAtomic } from '../../common/src/atomic';
import { DEFAULT_PACKAGE_LIMITS, normalizeEntryName, readPackageBytes } from '../../common/src/packageEntries';
import { entryDate, readCentralDirectory } from '../../common/src/zip';

/**
 * The files inside `.mosc` packages, addressed by paths that read every package as a folder:
 * `/abs/a.mosc/inner.mosc/simple.xosc`. No editor imports, so it is tested without VS Code.
 */

/** Where a package path points: the archive on disk, the nested packages inside it, then an entry. */
export interface PackageLocation {
  disk: string;
  /** Entry names of the nested packages, outermost first. */
  nested: string[];
  /** The entry (or folder of entries) inside the innermost package; '' for the package itself. */
  inner: string;
}

export type EntryKind = 'file' | 'directory';

export interface EntryStat {
  kind: EntryKind;
  size: number;
  /** The archive's modification time on disk, in milliseconds. */
  mtime: number;
}

/** Why a package operation failed; `code` lets the editor pick the right file system error. */
export class PackageError extends Error {
  constructor(
    message: string,
    readonly code: 'not-found' | 'broken' | 'exists' | 'invalid',
  ) {
    super(message);
  }
}

function isPackageName(name: string): boolean {
  return name.toLowerCase().endsWith('.mosc');
}

async function isFile(filePath: string): Promise<boolean> {
  try {
    return (await fs.promises.stat(filePath)).isFile();
  } catch {
    return false;
  }
}

/**
 * A package's entries with the date each carries in the ZIP: an entry's own date is its
 * modification time, so saving one file of a package does not make the others look changed.
 */
class PackageEntries extends Map<string, Uint8Array> {
  readonly dates = new Map<string, Date>();

  /** Sets an entry's content, dated now. */
  put(name: string, bytes: Uint8Array): void {
    this.set(name, bytes);
    this.dates.set(name, new Date());
  }

  remove(name: string): void {
    this.delete(name);
    this.dates.delete(name);
  }
}

async function loadEntries(bytes: Uint8Array, label: string): Promise<PackageEntries> {
  const entries = new PackageEntries();
  try {
    // The core reader checks names, sizes and CRCs; the dates come from a second, cheap read of its central directory.
    for (const [name, content] of (await readPackageBytes(bytes, label)).entries) entries.set(name, content);
    for (const record of readCentralDirectory(bytes, DEFAULT_PACKAGE_LIMITS.maxEntries)) {
      const name = normalizeEntryName(record.name);
      if (name !== undefined && entries.has(name)) entries.dates.set(name, entryDate(record));
    }
  } catch (error) {
    throw new PackageError((error as Error).message, 'broken');
  }
  return entries;
}

/** The chain of packages from the archive on disk to the innermost one, each with its entries. */
interface OpenPackages {
  location: PackageLocation;
  /** levels[0] is the archive on disk; levels[i] is the package stored as entry nested[i - 1] of levels[i - 1]. */
  levels: PackageEntries[];
  mtime: number;
}

/** Splits a package path into its archive on disk, nested packages and entry. */
export async function locate(packagePath: string): Promise<PackageLocation> {
  const segments = path.posix
    .normalize(packagePath.replace(/\\/g, '/'))
    .split('/')
    .filter((segment) => segment !== '');
  for (let split = segments.length; split >= 1; split--) {
    const disk = '/' + segments.slice(0, split).join('/');
    if (!isPackageName(disk) || !(await isFile(disk))) continue;
    const rest = segments.slice(split).join('/');
    const inner = rest === '' ? '' : normalizeEntryName(rest);
    if (inner === undefined) throw new PackageError(`'${packagePath}' points outside its package`, 'invalid');
    return descend({ disk, nested: [], inner }, await open(disk));
  }
  throw new PackageError(`no .mosc package on disk holds '${packagePath}'`, 'not-found');
}

/** Moves every leading part of `inner` that names a nested package entry into `nested`. */
async function descend(location: PackageLocation, packages: OpenPackages): Promise<PackageLocation> {
  let entries = packages.levels[0];
  const nested: string[] = [];
  let remaining = location.inner.split('/').filter((part) => part !== '');
  let label = location.disk;
  for (let cut = 1; cut <= remaining.length; cut++) {
    const candidate = remaining.slice(0, cut).join('/');
    const bytes = entries.get(candidate);
    if (bytes && isPackageName(candidate)) {
      label = `${label}/${candidate}`;
      entries = await loadEntries(bytes, label);
      nested.push(candidate);
      remaining = remaining.slice(cut);
      cut = 0;
    }
  }
  return { disk: location.disk, nested, inner: remaining.join('/') };
}

async function open(disk: string, nested: string[] = []): Promise<OpenPackages> {
  let bytes: Uint8Array;
  let mtime: number;
  try {
    bytes = await fs.promises.readFile(disk);
    mtime = (await fs.promises.stat(disk)).mtimeMs;
  } catch (error) {
    throw new PackageError(`cannot read ${disk} (${(error as NodeJS.ErrnoException).code ?? (error as Error).message})`, 'not-found');
  }
  const levels = [await loadEntries(bytes, disk)];
  let label = disk;
  for (const entry of nested) {
    const inner = levels[levels.length - 1].get(entry);
    if (!inner) throw new PackageError(`${label} holds no package '${entry}'`, 'not-found');
    label = `${label}/${entry}`;
    levels.push(await loadEntries(inner, label));
  }
  return { location: { disk, nested, inner: '' }, levels, mtime };
}

async function openLocation(location: PackageLocation): Promise<PackageEntries[]> {
  return (await open(location.disk, location.nested)).levels;
}

function innermost(levels: PackageEntries[]): PackageEntries {
  return levels[levels.length - 1];
}

function hasFolder(entries: Map<string, Uint8Array>, folder: string): boolean {
  if (folder === '') return true;
  for (const name of entries.keys()) if (name.startsWith(folder + '/')) return true;
  return false;
}

export async function stat(location: PackageLocation): Promise<EntryStat> {
  const packages = await open(location.disk, location.nested);
  const entries = innermost(packages.levels);
  const bytes = location.inner === '' ? undefined : entries.get(location.inner);
  if (bytes) return { kind: 'file', size: bytes.length, mtime: entries.dates.get(location.inner)?.getTime() ?? packages.mtime };
  if (hasFolder(entries, location.inner)) return { kind: 'directory', size: 0, mtime: packages.mtime };
  throw new PackageError(`${describe(location)} does not exist`, 'not-found');
}

export async function readEntry(location: PackageLocation): Promise<Uint8Array> {
  const bytes = innermost(await openLocation(location)).get(location.inner);
  if (!bytes) throw new PackageError(`${describe(location)} does not exist`, 'not-found');
  return bytes;
}

/** The names directly inside a folder of a package; nested packages count as folders. */
export async function listFolder(location: PackageLocation): Promise<[string, EntryKind][]> {
  const entries = innermost(await openLocation(location));
  if (!hasFolder(entries, location.inner)) throw new PackageError(`${describe(location)} is not a folder of the package`, 'not-found');
  const prefix = location.inner === '' ? '' : location.inner + '/';
  const children = new Map<string, EntryKind>();
  for (const name of entries.keys()) {
    if (!name.startsWith(prefix)) continue;
    const rest = name.slice(prefix.length);
    const slash = rest.indexOf('/');
    const child = slash === -1 ? rest : rest.slice(0, slash);
    children.set(child, slash === -1 && !isPackageName(child) ? 'file' : 'directory');
  }
  return [...children.entries()].sort(([a], [b]) => a.localeCompare(b));
}

/** Every entry of a package as a path relative to it, nested packages listed through. */
export async function listAll(location: PackageLocation): Promise<string[]> {
  const result: string[] = [];
  const walk = async (entries: Map<string, Uint8Array>, prefix: string, label: string): Promise<void> => {
    for (const [name, bytes] of entries) {
      result.push(prefix + name);
      if (isPackageName(name)) {
        const nested = await loadEntries(bytes, `${label}/${name}`).catch(() => undefined);
        if (nested) await walk(nested, `${prefix}${name}/`, `${label}/${name}`);
      }
    }
  };
  await walk(innermost(await openLocation(location)), '', describe(location));
  return result;
}

async function zip(entries: PackageEntries): Promise<Uint8Array> {
  const archive = new JSZip();
  for (const [name, bytes] of entries) archive.file(name, bytes, { date: entries.dates.get(name) ?? new Date(), createFolders: false });
  return archive.generateAsync({ type: 'uint8array', compression: 'DEFLATE', compressionOptions: { level: 6 } });
}

/** The last pending rewrite of each archive on disk: rewrites of one archive run one after another. */
const pendingRewrites = new Map<string, Promise<void>>();

/**
 * Applies `change` to the innermost package and writes the whole archive again, atomically. Two
 * saves of one archive (Save All) would otherwise both read it first and the later write would drop
 * the earlier change, so each waits for the one before.
 */
function rewrite(location: PackageLocation, change: (entries: PackageEntries) => void): Promise<void> {
  const previous = pendingRewrites.get(location.disk) ?? Promise.resolve();
  const next = previous.catch(() => undefined).then(() => rewriteNow(location, change));
  pendingRewrites.set(location.disk, next);
  void next
    .finally(() => {
      if (pendingRewrites.get(location.disk) === next) pendingRewrites.delete(location.disk);
    })
    .catch(() => undefined);
  return next;
}

async function rewriteNow(location: PackageLocation, change: (entries: PackageEntries) => void): Promise<void> {
  // Read again at save time, so that what others changed in the archive meanwhile is kept.
  const levels = await openLocation(location);
  change(innermost(levels));
  let bytes = await zip(innermost(levels));
  for (let level = levels.length - 2; level >= 0; level--) {
    levels[level].put(location.nested[level], bytes);
    bytes = await zip(levels[level]);
  }
  await writeFileAtomic(location.disk, bytes);
}

export async function writeEntry(
  location: PackageLocation,
  content: Uint8Array,
  options: { create: boolean; overwrite: boolean },
): Promise<void> {
  if (location.inner === '') throw new PackageError(`${describe(location)} is a package, not a file inside one`, 'invalid');
  await rewrite(location, (entries) => {
    const exists = entries.has(location.inner);
    if (!exists && !options.create) throw new PackageError(`${describe(location)} does not exist`, 'not-found');
    if (exists && !options.overwrite) throw new PackageError(`${describe(location)} already exists`, 'exists');
    if (!exists && hasFolder(entries, location.inner)) throw new PackageError(`${describe(location)} is a folder`, 'exists');
    entries.put(location.inner, content);
  });
}

export async function deleteEntry(location: PackageLocation): Promise<void> {
  if (location.inner === '') throw new PackageError(`${describe(location)} is a whole package; delete the .mosc file instead`, 'invalid');
  await rewrite(location, (entries) => {
    const names = [...entries.keys()].filter((name) => name === location.inner || name.startsWith(location.inner + '/'));
    if (names.length === 0) throw new PackageError(`${describe(location)} does not exist`, 'not-found');
    for (const name of names) entries.remove(name);
  });
}

/** Renames an entry within one package (moving between packages is a copy and a delete). */
export async function renameEntry(from: PackageLocation, to: PackageLocation, overwrite: boolean): Promise<void> {
  if (from.disk !== to.disk || from.nested.join('/') !== to.nested.join('/') || from.inner === '' || to.inner === '') {
    throw new PackageError('an entry can only be renamed inside its own package', 'invalid');
  }
  await rewrite(from, (entries) => {
    const bytes = entries.get(from.inner);
    if (!bytes) throw new PackageError(`${describe(from)} does not exist`, 'not-found');
    if (entries.has(to.inner) && !overwrite) throw new PackageError(`${describe(to)} already exists`, 'exists');
    entries.remove(from.inner);
    entries.put(to.inner, bytes);
  });
}

export function describe(location: PackageLocation): string {
  return [location.disk, ...location.nested, ...(location.inner ? [location.inner] : [])].join('/');
}

/** The package path of an entry: the path part of its `mosc:` URI. */
export function packagePathOf(location: PackageLocation): string {
  return describe(location);
}
