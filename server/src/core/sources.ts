import * as fs from 'node:fs';
import * as path from 'node:path';
import { decodeScenario, DecodeError } from './encoding';
import { pathsFor, splitDiskPath } from './paths';
import { extractEntry, InflateBudget, readCentralDirectory, ZipEntryRecord } from './zip';
import { parseXml, reparseXml, XmlDocument } from './xml';

/**
 * Where a scenario file lives: a path on disk, then zero or more entry names, each inside the
 * package named before it. `{ disk: '/a/p.mosc', entries: ['inner.mosc', 'main.xosc'] }` is the
 * `main.xosc` of the package `inner.mosc` stored in `/a/p.mosc`.
 */
export interface SourceRef {
  disk: string;
  entries: string[];
}

export function diskRef(filePath: string): SourceRef {
  return { disk: pathsFor(filePath).resolve(filePath), entries: [] };
}

export function childRef(packageRef: SourceRef, entry: string): SourceRef {
  return { disk: packageRef.disk, entries: [...packageRef.entries, entry] };
}

/** A package's `.mosc` file (or an entry holding one) is read as a folder: `/a/p.mosc/inner.mosc/main.xosc`. */
export function refId(ref: SourceRef): string {
  if (ref.entries.length === 0) return ref.disk;
  // Remembered per ref: deep chains of nested packages compare ids often, and each is as long as the chain.
  let id = refIds.get(ref);
  if (id === undefined) {
    id = `${ref.disk}/${ref.entries.join('/')}`;
    refIds.set(ref, id);
  }
  return id;
}

const refIds = new WeakMap<SourceRef, string>();

export function sameRef(a: SourceRef, b: SourceRef): boolean {
  return refId(a) === refId(b);
}

/** A short form for messages: relative to `base` when the file lies below it. */
export function displayRef(ref: SourceRef, base: string = process.cwd()): string {
  const paths = pathsFor(ref.disk);
  // A base of the other platform's form (a POSIX working directory, a Windows file) never contains it.
  const relative = pathsFor(base) === paths ? paths.relative(base, ref.disk) : '';
  const disk = relative && !relative.startsWith('..') && !paths.isAbsolute(relative) ? relative : ref.disk;
  return ref.entries.length === 0 ? disk : `${disk}/${ref.entries.join('/')}`;
}

export function baseName(ref: SourceRef): string {
  const last = ref.entries.length > 0 ? ref.entries[ref.entries.length - 1] : ref.disk;
  return last.split(/[\\/]/).pop() ?? last;
}

export class SourceError extends Error {
  constructor(
    message: string,
    readonly ref: SourceRef,
    readonly hint?: string,
    /** Zero-based line of the problem in the file, when known. */
    readonly line?: number,
  ) {
    super(message);
  }
}

export interface FileSystemHost {
  /**
   * The file's bytes, or undefined when it does not exist. Throws FileReadError for what is not a
   * regular file (a folder, a FIFO, a device) or holds more than `maxBytes`.
   */
  readFile(filePath: string, maxBytes?: number): Promise<Uint8Array | undefined>;
  kind(filePath: string): Promise<'file' | 'directory' | undefined>;
  /** The names in a directory, or undefined when it cannot be listed (catalog directories need it). */
  listDirectory?(directoryPath: string): Promise<string[] | undefined>;
}

export class FileReadError extends Error {}

function describeKind(stat: fs.Stats): string {
  if (stat.isDirectory()) return 'a folder';
  if (stat.isFIFO()) return 'a FIFO';
  if (stat.isCharacterDevice()) return 'a character device';
  if (stat.isBlockDevice()) return 'a block device';
  if (stat.isSocket()) return 'a socket';
  return 'not a regular file';
}

export const nodeFileSystem: FileSystemHost = {
  async readFile(filePath, maxBytes = DEFAULT_LIMITS.maxEntryBytes) {
    let handle: fs.promises.FileHandle;
    try {
      // Non-blocking, so that opening a FIFO returns at once instead of waiting for a writer.
      handle = await fs.promises.open(filePath, fs.constants.O_RDONLY | fs.constants.O_NONBLOCK);
    } catch (error) {
      const code = (error as NodeJS.ErrnoException).code;
      if (code === 'ENOENT' || code === 'ENOTDIR') return undefined;
      throw new FileReadError(`cannot read ${filePath} (${code ?? (error as Error).message})`);
    }
    try {
      const stat = await handle.stat();
      if (!stat.isFile()) throw new FileReadError(`${filePath} is ${describeKind(stat)}, not a file; only regular files are read`);
      if (stat.size > maxBytes) throw new FileReadError(`${filePath} is too large to read (${stat.size} bytes; the limit is ${maxBytes}, raised with --max-file-size)`);
      // Read at most one byte past the bound, in case the file grows while it is read.
      const buffer = Buffer.alloc(Math.min(stat.size, maxBytes) + 1);
      let length = 0;
      for (;;) {
        const { bytesRead } = await handle.read(buffer, length, buffer.length - length, null);
        if (bytesRead === 0) break;
        length += bytesRead;
        if (length === buffer.length) break;
      }
      if (length > maxBytes) throw new FileReadError(`${filePath} is too large to read (more than ${maxBytes} bytes, raised with --max-file-size)`);
      return buffer.subarray(0, length);
    } finally {
      await handle.close();
    }
  },
  async kind(filePath) {
    try {
      const stat = await fs.promises.stat(filePath);
      return stat.isFile() ? 'file' : stat.isDirectory() ? 'directory' : undefined;
    } catch {
      return undefined;
    }
  },
  async listDirectory(directoryPath) {
    try {
      return await fs.promises.readdir(directoryPath);
    } catch {
      return undefined;
    }
  },
};

/** Bounds on what one run (a flatten, a check, an index) may read, unpack and produce. */
export interface Limits {
  maxEntries: number;
  /** Any one scenario file, on disk or unpacked from a package. */
  maxEntryBytes: number;
  /** Bytes unpacked from packages in one run, all packages together. */
  maxTotalBytes: number;
  /** Characters of one flattened result. */
  maxFlattenedChars: number;
  /** Files in one chain of references (nested packages included). */
  maxDepth: number;
}

/** @deprecated the package bounds are part of Limits. */
export type PackageLimits = Pick<Limits, 'maxEntries' | 'maxEntryBytes' | 'maxTotalBytes'>;

export const DEFAULT_LIMITS: Limits = {
  maxEntries: 10_000,
  maxEntryBytes: 32 * 1024 * 1024,
  maxTotalBytes: 128 * 1024 * 1024,
  maxFlattenedChars: 8 * 1024 * 1024,
  maxDepth: 64,
};

export const DEFAULT_PACKAGE_LIMITS: PackageLimits = DEFAULT_LIMITS;

export interface PackageContents {
  /** Entry names (with `/` for sub-folders) to their bytes; folders are not listed. */
  entries: Map<string, Uint8Array>;
}

/** Normalizes a ZIP entry or reference name; undefined when it would leave the package. */
export function normalizeEntryName(name: string): string | undefined {
  const parts: string[] = [];
  for (const part of name.replace(/\\/g, '/').split('/')) {
    if (part === '' || part === '.') continue;
    if (part === '..') return undefined;
    parts.push(part);
  }
  if (/^[A-Za-z]:/.test(name) || name.startsWith('/')) return undefined;
  return parts.length > 0 ? parts.join('/') : undefined;
}

/**
 * Reads a `.mosc` in memory. Nothing is extracted to disk; unsafe or duplicate names, overlapping
 * entries and oversized entries are refused; what is unpacked is charged to `budget`.
 */
export async function readPackageBytes(
  bytes: Uint8Array,
  label: string,
  limits: PackageLimits = DEFAULT_LIMITS,
  budget: InflateBudget = { remaining: limits.maxTotalBytes, limit: limits.maxTotalBytes },
): Promise<PackageContents> {
  let records: ZipEntryRecord[];
  try {
    records = readCentralDirectory(bytes, limits.maxEntries);
  } catch (error) {
    throw new Error(`${label} is not a readable ZIP archive (${(error as Error).message}); a .mosc must be a ZIP file`);
  }
  const entries = new Map<string, Uint8Array>();
  const stored = new Map<string, string>();
  for (const record of records) {
    if (record.name.endsWith('/') || record.name.endsWith('\\')) continue;
    const name = normalizeEntryName(record.name);
    if (name === undefined) throw new Error(`${label} holds an entry named '${record.name}' that points outside the package; it was refused`);
    const first = stored.get(name);
    if (first !== undefined) {
      throw new Error(`${label} holds the entry '${name}' twice` + (first === record.name ? '' : ` (as '${first}' and '${record.name}')`) + '; it was refused');
    }
    stored.set(name, record.name);
  }
  for (const record of records) {
    const name = normalizeEntryName(record.name);
    if (name === undefined || record.name.endsWith('/') || record.name.endsWith('\\')) continue;
    try {
      entries.set(name, extractEntry(bytes, record, limits.maxEntryBytes, budget, `${label}/${name}`));
    } catch (error) {
      throw new Error((error as Error).message);
    }
  }
  return { entries };
}

/** Keeps values up to a total size, forgetting the least recently used first. */
export class SizedCache<T> {
  private readonly entries = new Map<string, { value: T; size: number }>();
  private total = 0;

  constructor(readonly maxBytes: number) {}

  get size(): number {
    return this.total;
  }

  get(key: string): T | undefined {
    const entry = this.entries.get(key);
    if (!entry) return undefined;
    this.entries.delete(key);
    this.entries.set(key, entry);
    return entry.value;
  }

  set(key: string, value: T, size: number): void {
    this.delete(key);
    if (size > this.maxBytes) return;
    this.entries.set(key, { value, size });
    this.total += size;
    for (const [oldest, entry] of this.entries) {
      if (this.total <= this.maxBytes) break;
      this.entries.delete(oldest);
      this.total -= entry.size;
    }
  }

  delete(key: string): void {
    const entry = this.entries.get(key);
    if (!entry) return;
    this.entries.delete(key);
    this.total -= entry.size;
  }

  /** Forgets every key for which `test` holds. */
  deleteWhere(test: (key: string) => boolean): void {
    for (const key of [...this.entries.keys()]) if (test(key)) this.delete(key);
  }

  clear(): void {
    this.entries.clear();
    this.total = 0;
  }
}

function contentsSize(contents: PackageContents): number {
  let size = 0;
  for (const bytes of contents.entries.values()) size += bytes.length;
  return size;
}

export type Resolution =
  | { kind: 'scenario'; ref: SourceRef; via: LookupPlace['via'] }
  | {
      kind: 'package';
      /** The `.mosc` file (or entry), or the folder standing for it. */
      packageRef: SourceRef;
      main: SourceRef;
      folder: boolean;
      via: LookupPlace['via'];
      /** Set when a `NAME.xosc` was found only as the package `NAME.mosc`. */
      fallbackFrom?: string;
    }
  | { kind: 'missing'; searched: string[]; hint?: string }
  | { kind: 'invalid'; message: string }
  /** The package that should hold the name cannot be read (a broken archive, a bound exceeded). */
  | { kind: 'unreadable'; message: string; hint?: string };

interface LookupPlace {
  /** A folder on disk, or a folder inside a package. */
  packageRef: SourceRef | undefined;
  directory: string;
  via: 'package' | 'folder' | 'scenarioPath' | 'parent';
}

export interface FolderOptions {
  folder: string;
  scenarioPath: string[];
}

/** Whether `directory` is `folder` or lies below it. */
function isWithinFolder(directory: string, folder: string): boolean {
  const separator = pathsFor(folder).sep;
  return directory === folder || directory.startsWith(folder.endsWith(separator) ? folder : folder + separator);
}

export interface StoreOptions {
  /** Directories searched after the package itself: SCENARIO_PATH first, then the editor's setting. */
  scenarioPath?: string[];
  /** The folder where the upward search of unpacked folders stops (workspace folder or working directory). */
  root?: string;
  /**
   * Workspace folders: a file inside one searches upward to it (not to `root`) and uses its own
   * scenario path instead of `scenarioPath` (an editor's per-folder setting).
   */
  folders?: FolderOptions[];
  host?: FileSystemHost;
  limits?: Partial<Limits>;
  /** Bytes of unpacked packages kept for reuse; the least recently used are read again when needed. */
  packageCacheBytes?: number;
}

/** Splits SCENARIO_PATH on `;` and on the platform's delimiter (the original split on `;` only). */
export function splitScenarioPath(value: string | undefined): string[] {
  if (!value) return [];
  return value
    .split(new RegExp(`[;${path.delimiter === ';' ? '' : path.delimiter}]`))
    .map((entry) => entry.trim())
    .filter((entry) => entry.length > 0)
    .map((entry) => pathsFor(entry).resolve(entry));
}

/** Reads scenario files from disk and packages, and resolves `scenarioFileName`s (SPEC 3). */
export class ScenarioStore {
  readonly host: FileSystemHost;
  readonly scenarioPath: string[];
  readonly root: string | undefined;
  readonly folders: FolderOptions[];
  readonly limits: Limits;
  /** What one run may still unpack; see resetBudget. */
  private budget: InflateBudget;
  private readonly packages: SizedCache<PackageContents>;
  private readonly pendingPackages = new Map<string, Promise<PackageContents>>();
  private readonly failedPackages = new Map<string, Promise<PackageContents>>();
  private readonly overlays = new Map<string, string>();
  /** The last parse of each file being edited, from which the next edit is re-parsed. */
  private readonly editedParses = new Map<string, XmlDocument>();
  /** The last parse of the flattened text of each file being edited (see parseFlattened). */
  private readonly flattenedParses = new Map<string, XmlDocument>();
  private readonly kinds = new Map<string, Promise<'file' | 'directory' | undefined>>();

  constructor(options: StoreOptions = {}) {
    this.host = options.host ?? nodeFileSystem;
    this.scenarioPath = options.scenarioPath ?? splitScenarioPath(process.env.SCENARIO_PATH);
    this.root = options.root ? pathsFor(options.root).resolve(options.root) : undefined;
    // Innermost first, so a folder nested in another is found before it.
    this.folders = (options.folders ?? []).map((entry) => ({ ...entry, folder: pathsFor(entry.folder).resolve(entry.folder) })).sort((a, b) => b.folder.length - a.folder.length);
    this.limits = { ...DEFAULT_LIMITS, ...options.limits };
    this.budget = { remaining: this.limits.maxTotalBytes, limit: this.limits.maxTotalBytes };
    this.packages = new SizedCache(options.packageCacheBytes ?? Infinity);
  }

  /** Starts a new run: what it may unpack is counted from zero (packages still cached cost nothing). */
  resetBudget(): void {
    this.budget = { remaining: this.limits.maxTotalBytes, limit: this.limits.maxTotalBytes };
    this.failedPackages.clear();
  }

  /** Bytes of unpacked packages held for reuse. */
  get cachedPackageBytes(): number {
    return this.packages.size;
  }

  /** Text that replaces a file's stored content, as an editor's unsaved buffer does. */
  setOverlay(ref: SourceRef, text: string | undefined): void {
    if (text === undefined) {
      this.overlays.delete(refId(ref));
      this.editedParses.delete(refId(ref));
      this.flattenedParses.delete(refId(ref));
    } else {
      this.overlays.set(refId(ref), text);
    }
  }

  /** Parses a file's text; a file being edited is re-parsed from its previous parse where it can be. */
  parse(ref: SourceRef, text: string): XmlDocument {
    return this.parseEdited(this.editedParses, ref, text);
  }

  /**
   * Parses the flattened text of a file being edited, from its previous flattened parse where it
   * can be: an edit inside one value of the file changes one value of its flattened text too.
   */
  parseFlattened(ref: SourceRef, text: string): XmlDocument {
    return this.parseEdited(this.flattenedParses, ref, text);
  }

  private parseEdited(previousParses: Map<string, XmlDocument>, ref: SourceRef, text: string): XmlDocument {
    const id = refId(ref);
    if (!this.overlays.has(id)) return parseXml(text);
    const previous = previousParses.get(id);
    const document = previous ? reparseXml(previous, text) : parseXml(text);
    previousParses.set(id, document);
    return document;
  }

  /** Forgets what was read of a file on disk (a package is read again on next use). */
  invalidate(diskPath: string): void {
    const paths = pathsFor(diskPath);
    const resolved = paths.resolve(diskPath);
    this.kinds.clear();
    // Entries of a package follow its path after `/`; files of a folder after the platform's separator.
    const below = (key: string) => key === resolved || key.startsWith(resolved + '/') || key.startsWith(resolved + paths.sep);
    this.packages.deleteWhere(below);
    for (const key of [...this.pendingPackages.keys()]) if (below(key)) this.pendingPackages.delete(key);
    for (const key of [...this.failedPackages.keys()]) if (below(key)) this.failedPackages.delete(key);
  }

  /** Whether a path is a file or a folder; remembered until the next invalidate. */
  kindOf(filePath: string): Promise<'file' | 'directory' | undefined> {
    let pending = this.kinds.get(filePath);
    if (!pending) {
      pending = this.host.kind(filePath);
      this.kinds.set(filePath, pending);
    }
    return pending;
  }

  async readBytes(ref: SourceRef): Promise<Uint8Array> {
    if (ref.entries.length === 0) {
      let bytes: Uint8Array | undefined;
      try {
        bytes = await this.host.readFile(ref.disk, this.limits.maxEntryBytes);
      } catch (error) {
        throw new SourceError((error as Error).message, ref);
      }
      if (!bytes) throw new SourceError(`cannot read ${ref.disk}: no such file`, ref);
      return bytes;
    }
    const parent: SourceRef = { disk: ref.disk, entries: ref.entries.slice(0, -1) };
    const contents = await this.readPackage(parent);
    const bytes = contents.entries.get(ref.entries[ref.entries.length - 1]);
    if (!bytes) throw new SourceError(`${displayRef(parent)} holds no entry '${ref.entries[ref.entries.length - 1]}'`, ref);
    return bytes;
  }

  async readText(ref: SourceRef): Promise<string> {
    const overlay = this.overlays.get(refId(ref));
    if (overlay !== undefined) return overlay;
    const bytes = await this.readBytes(ref);
    try {
      return decodeScenario(bytes);
    } catch (error) {
      if (!(error instanceof DecodeError)) throw error;
      throw new SourceError(`${displayRef(ref)}: ${error.message}`, ref, undefined, error.line);
    }
  }

  /** The entries of the package stored at `ref` (a `.mosc` on disk or inside another package). */
  readPackage(ref: SourceRef): Promise<PackageContents> {
    const id = refId(ref);
    const cached = this.packages.get(id);
    if (cached) return Promise.resolve(cached);
    let pending = this.pendingPackages.get(id) ?? this.failedPackages.get(id);
    if (!pending) {
      const reading = (async () => {
        const bytes = await this.readBytes(ref);
        try {
          return await readPackageBytes(bytes, displayRef(ref), this.limits, this.budget);
        } catch (error) {
          throw new SourceError((error as Error).message, ref, 'rebuild the package with `modular2simple pack`');
        }
      })();
      pending = reading;
      this.pendingPackages.set(id, reading);
      reading.then(
        (contents) => {
          if (this.pendingPackages.get(id) !== reading) return;
          this.pendingPackages.delete(id);
          this.packages.set(id, contents, contentsSize(contents));
        },
        () => {
          if (this.pendingPackages.get(id) !== reading) return;
          this.pendingPackages.delete(id);
          this.failedPackages.set(id, reading);
        },
      );
    }
    return pending;
  }

  /**
   * Reads a path such as `/abs/pkg.mosc/inner.mosc/main.xosc` or `C:\abs\pkg.mosc\main.xosc` (the path of a `mosc:` URI): the
   * longest prefix that is a file on disk is the package, the rest names entries, descending into
   * nested packages at each entry that is itself a package.
   */
  async refFromPackagePath(packagePath: string): Promise<SourceRef | undefined> {
    const { root, names: segments } = splitDiskPath(packagePath);
    const paths = pathsFor(root);
    for (let split = segments.length - 1; split >= 1; split--) {
      const disk = paths.join(root, ...segments.slice(0, split));
      if (!disk.toLowerCase().endsWith('.mosc') || (await this.host.kind(disk)) !== 'file') continue;
      let current: SourceRef = { disk, entries: [] };
      let pending: string[] = [];
      for (const segment of segments.slice(split)) {
        pending.push(segment);
        const entry = pending.join('/');
        if (entry.toLowerCase().endsWith('.mosc') && pending.length > 0) {
          const contents = await this.readPackage(current).catch(() => undefined);
          if (contents?.entries.has(entry)) {
            current = childRef(current, entry);
            pending = [];
          }
        }
      }
      return pending.length > 0 ? childRef(current, pending.join('/')) : current;
    }
    return undefined;
  }

  /** The workspace folder holding a path, if any. */
  private folderOf(filePath: string): FolderOptions | undefined {
    return this.folders.find((entry) => isWithinFolder(filePath, entry.folder));
  }

  /** Where the upward search from `directory` stops: its workspace folder, else the root (or working directory). */
  rootOf(directory: string): string {
    return this.folderOf(directory)?.folder ?? this.root ?? process.cwd();
  }

  /** The folders searched after the package for a name written in `from`. */
  scenarioPathFor(from: SourceRef): string[] {
    return this.folderOf(from.disk)?.scenarioPath ?? this.scenarioPath;
  }

  /** Places searched for a name referenced from `from`, in order (SPEC 3). */
  lookupPlaces(from: SourceRef): LookupPlace[] {
    const places: LookupPlace[] = [];
    const scenarioPath = this.scenarioPathFor(from);
    if (from.entries.length === 0) {
      const paths = pathsFor(from.disk);
      const directory = paths.dirname(from.disk);
      places.push({ packageRef: undefined, directory, via: 'folder' });
      for (const entry of scenarioPath) places.push({ packageRef: undefined, directory: entry, via: 'scenarioPath' });
      const root = this.rootOf(directory);
      if (isWithinFolder(directory, root)) {
        for (let parent = paths.dirname(directory); ; parent = paths.dirname(parent)) {
          if (!isWithinFolder(parent, root)) break;
          places.push({ packageRef: undefined, directory: parent, via: 'parent' });
          if (parent === root || parent === paths.dirname(parent)) break;
        }
      }
    } else {
      const packageRef: SourceRef = { disk: from.disk, entries: from.entries.slice(0, -1) };
      const entry = from.entries[from.entries.length - 1];
      const directory = entry.includes('/') ? entry.slice(0, entry.lastIndexOf('/')) : '';
      places.push({ packageRef, directory, via: 'package' });
      if (directory !== '') places.push({ packageRef, directory: '', via: 'package' });
      for (const entryDirectory of scenarioPath) places.push({ packageRef: undefined, directory: entryDirectory, via: 'scenarioPath' });
    }
    return places;
  }

  private async findIn(place: LookupPlace, name: string, wantPackage: boolean): Promise<Resolution | undefined> {
    if (place.packageRef) {
      const joined = normalizeEntryName(place.directory ? `${place.directory}/${name}` : name);
      if (!joined) return undefined;
      let contents: PackageContents;
      try {
        contents = await this.readPackage(place.packageRef);
      } catch (error) {
        return { kind: 'unreadable', message: (error as Error).message, hint: error instanceof SourceError ? error.hint : undefined };
      }
      if (contents.entries.has(joined)) {
        const ref = childRef(place.packageRef, joined);
        if (!wantPackage) return { kind: 'scenario', ref, via: place.via };
        return { kind: 'package', packageRef: ref, main: childRef(ref, 'main.xosc'), folder: false, via: place.via };
      }
      if (wantPackage) {
        const folderMain = `${joined.slice(0, -'.mosc'.length)}/main.xosc`;
        if (contents.entries.has(folderMain)) {
          const folderRef = childRef(place.packageRef, joined.slice(0, -'.mosc'.length));
          return { kind: 'package', packageRef: folderRef, main: childRef(place.packageRef, folderMain), folder: true, via: place.via };
        }
      }
      return undefined;
    }
    const paths = pathsFor(place.directory);
    const candidate = paths.resolve(place.directory, name);
    if ((await this.kindOf(candidate)) === 'file') {
      const ref = diskRef(candidate);
      if (!wantPackage) return { kind: 'scenario', ref, via: place.via };
      return { kind: 'package', packageRef: ref, main: childRef(ref, 'main.xosc'), folder: false, via: place.via };
    }
    if (wantPackage) {
      const folder = candidate.slice(0, -'.mosc'.length);
      if ((await this.kindOf(paths.join(folder, 'main.xosc'))) === 'file') {
        return { kind: 'package', packageRef: diskRef(folder), main: diskRef(paths.join(folder, 'main.xosc')), folder: true, via: place.via };
      }
    }
    return undefined;
  }

  private describePlace(place: LookupPlace): string {
    if (place.packageRef) return place.directory ? `${displayRef(place.packageRef)}/${place.directory}` : displayRef(place.packageRef);
    const label = place.via === 'scenarioPath' ? ' (SCENARIO_PATH)' : place.via === 'parent' ? ' (parent folder)' : '';
    const paths = pathsFor(place.directory);
    const shown = pathsFor(process.cwd()) === paths ? paths.relative(process.cwd(), place.directory) || '.' : place.directory;
    return `${shown}${label}`;
  }

  /** Resolves a `scenarioFileName` written in the file `from` (SPEC 3). */
  async resolve(name: string, from: SourceRef): Promise<Resolution> {
    const trimmed = name.trim();
    if (!trimmed) return { kind: 'invalid', message: 'scenarioFileName is empty' };
    const lower = trimmed.toLowerCase();
    const isPackage = lower.endsWith('.mosc');
    if (!isPackage && !lower.endsWith('.xosc')) {
      return { kind: 'invalid', message: `'${trimmed}' must name a .xosc scenario or a .mosc package` };
    }
    if (from.entries.length > 0 && normalizeEntryName(trimmed) === undefined) {
      return { kind: 'invalid', message: `'${trimmed}' points outside its package` };
    }
    const places = this.lookupPlaces(from);
    for (const place of places) {
      const found = await this.findIn(place, trimmed, isPackage);
      if (found) return found;
    }
    if (!isPackage) {
      const packageName = `${trimmed.slice(0, -'.xosc'.length)}.mosc`;
      for (const place of places) {
        const found = await this.findIn(place, packageName, true);
        if (found && found.kind === 'package') return { ...found, fallbackFrom: trimmed };
      }
    }
    const searched = places.map((place) => this.describePlace(place));
    return {
      kind: 'missing',
      searched,
      hint: this.scenarioPath.length === 0 ? 'set SCENARIO_PATH (or the modular2simple.scenarioPath setting) to the folder that holds it' : undefined,
    };
  }
}

