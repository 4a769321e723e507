import * as fs from 'node:fs';
import * as path from 'node:path';
import type JSZip from 'jszip';
import { decodeUtf8 } from './text';
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
  return { disk: path.resolve(filePath), entries: [] };
}

export function childRef(packageRef: SourceRef, entry: string): SourceRef {
  return { disk: packageRef.disk, entries: [...packageRef.entries, entry] };
}

/** A package's `.mosc` file (or an entry holding one) is read as a folder: `/a/p.mosc/inner.mosc/main.xosc`. */
export function refId(ref: SourceRef): string {
  return ref.entries.length === 0 ? ref.disk : `${ref.disk}/${ref.entries.join('/')}`;
}

export function sameRef(a: SourceRef, b: SourceRef): boolean {
  return refId(a) === refId(b);
}

/** A short form for messages: relative to `base` when the file lies below it. */
export function displayRef(ref: SourceRef, base: string = process.cwd()): string {
  const relative = path.relative(base, ref.disk);
  const disk = relative && !relative.startsWith('..') && !path.isAbsolute(relative) ? relative : ref.disk;
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
  ) {
    super(message);
  }
}

export interface FileSystemHost {
  /** The file's bytes, or undefined when it does not exist or is not a file. */
  readFile(filePath: string): Promise<Uint8Array | undefined>;
  kind(filePath: string): Promise<'file' | 'directory' | undefined>;
  /** The names in a directory, or undefined when it cannot be listed (catalog directories need it). */
  listDirectory?(directoryPath: string): Promise<string[] | undefined>;
}

export const nodeFileSystem: FileSystemHost = {
  async readFile(filePath) {
    try {
      return await fs.promises.readFile(filePath);
    } catch {
      return undefined;
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

export interface PackageLimits {
  maxEntries: number;
  maxEntryBytes: number;
  maxTotalBytes: number;
}

export const DEFAULT_PACKAGE_LIMITS: PackageLimits = {
  maxEntries: 10_000,
  maxEntryBytes: 64 * 1024 * 1024,
  maxTotalBytes: 256 * 1024 * 1024,
};

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

/** Reads a `.mosc` in memory. Nothing is extracted to disk; unsafe names and oversized entries are refused. */
export async function readPackageBytes(
  bytes: Uint8Array,
  label: string,
  limits: PackageLimits = DEFAULT_PACKAGE_LIMITS,
): Promise<PackageContents> {
  let zip: JSZip;
  try {
    // Loaded on first use, so that commands that read no package start faster.
    const { default: loader } = await import('jszip');
    zip = await loader.loadAsync(bytes, { checkCRC32: true });
  } catch (error) {
    throw new Error(`${label} is not a readable ZIP archive (${(error as Error).message}); a .mosc must be a ZIP file`);
  }
  const files = Object.values(zip.files).filter((file) => !file.dir);
  if (files.length > limits.maxEntries) throw new Error(`${label} holds ${files.length} entries, more than the ${limits.maxEntries} allowed`);
  const entries = new Map<string, Uint8Array>();
  let total = 0;
  for (const file of files) {
    // JSZip quietly strips '../' from names; the name as stored is what an unzip tool would use.
    const stored = (file as JSZip.JSZipObject & { unsafeOriginalName?: string }).unsafeOriginalName ?? file.name;
    const name = normalizeEntryName(stored);
    if (name === undefined) throw new Error(`${label} holds an entry named '${stored}' that points outside the package; it was refused`);
    if (entries.has(name)) throw new Error(`${label} holds the entry '${name}' twice`);
    const content = await readEntryBounded(file, limits.maxEntryBytes, `${label}/${name}`);
    total += content.length;
    if (total > limits.maxTotalBytes) throw new Error(`${label} unpacks to more than ${limits.maxTotalBytes} bytes; it was refused`);
    entries.set(name, content);
  }
  return { entries };
}

/** JSZip's streaming reader; present at run time, missing from its type declarations. */
interface StreamingZipObject {
  internalStream(type: 'uint8array'): ZipStream;
}
interface ZipStream {
  on(event: 'data', listener: (chunk: Uint8Array) => void): ZipStream;
  on(event: 'error', listener: (error: Error) => void): ZipStream;
  on(event: 'end', listener: () => void): ZipStream;
  pause(): ZipStream;
  resume(): ZipStream;
}

function readEntryBounded(file: JSZip.JSZipObject, maxBytes: number, label: string): Promise<Uint8Array> {
  // Decompress as a stream so that a ZIP bomb is stopped at the bound, not after it filled memory.
  return new Promise((resolve, reject) => {
    const chunks: Uint8Array[] = [];
    let size = 0;
    let settled = false;
    const stream = (file as unknown as StreamingZipObject).internalStream('uint8array');
    stream
      .on('data', (chunk: Uint8Array) => {
        if (settled) return;
        size += chunk.length;
        if (size > maxBytes) {
          settled = true;
          stream.pause();
          reject(new Error(`${label} unpacks to more than ${maxBytes} bytes; it was refused`));
          return;
        }
        chunks.push(chunk);
      })
      .on('error', (error: Error) => {
        if (settled) return;
        settled = true;
        reject(new Error(`${label} cannot be unpacked (${error.message})`));
      })
      .on('end', () => {
        if (settled) return;
        settled = true;
        const out = new Uint8Array(size);
        let offset = 0;
        for (const chunk of chunks) {
          out.set(chunk, offset);
          offset += chunk.length;
        }
        resolve(out);
      })
      .resume();
  });
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
  | { kind: 'invalid'; message: string };

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
  return directory === folder || directory.startsWith(folder.endsWith(path.sep) ? folder : folder + path.sep);
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
  limits?: PackageLimits;
}

/** Splits SCENARIO_PATH on `;` and on the platform's delimiter (the original split on `;` only). */
export function splitScenarioPath(value: string | undefined): string[] {
  if (!value) return [];
  return value
    .split(new RegExp(`[;${path.delimiter === ';' ? '' : path.delimiter}]`))
    .map((entry) => entry.trim())
    .filter((entry) => entry.length > 0)
    .map((entry) => path.resolve(entry));
}

/** Reads scenario files from disk and packages, and resolves `scenarioFileName`s (SPEC 3). */
export class ScenarioStore {
  readonly host: FileSystemHost;
  readonly scenarioPath: string[];
  readonly root: string | undefined;
  readonly folders: FolderOptions[];
  private readonly limits: PackageLimits;
  private readonly packages = new Map<string, Promise<PackageContents>>();
  private readonly overlays = new Map<string, string>();
  /** The last parse of each file being edited, from which the next edit is re-parsed. */
  private readonly editedParses = new Map<string, XmlDocument>();
  /** The last parse of the flattened text of each file being edited (see parseFlattened). */
  private readonly flattenedParses = new Map<string, XmlDocument>();
  private readonly kinds = new Map<string, Promise<'file' | 'directory' | undefined>>();

  constructor(options: StoreOptions = {}) {
    this.host = options.host ?? nodeFileSystem;
    this.scenarioPath = options.scenarioPath ?? splitScenarioPath(process.env.SCENARIO_PATH);
    this.root = options.root ? path.resolve(options.root) : undefined;
    // Innermost first, so a folder nested in another is found before it.
    this.folders = (options.folders ?? []).map((entry) => ({ ...entry, folder: path.resolve(entry.folder) })).sort((a, b) => b.folder.length - a.folder.length);
    this.limits = options.limits ?? DEFAULT_PACKAGE_LIMITS;
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
    const resolved = path.resolve(diskPath);
    this.kinds.clear();
    for (const key of [...this.packages.keys()]) {
      if (key === resolved || key.startsWith(resolved + '/')) this.packages.delete(key);
    }
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
      const bytes = await this.host.readFile(ref.disk);
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
    return decodeUtf8(await this.readBytes(ref));
  }

  /** The entries of the package stored at `ref` (a `.mosc` on disk or inside another package). */
  readPackage(ref: SourceRef): Promise<PackageContents> {
    const id = refId(ref);
    let pending = this.packages.get(id);
    if (!pending) {
      pending = (async () => {
        const bytes = await this.readBytes(ref);
        try {
          return await readPackageBytes(bytes, displayRef(ref), this.limits);
        } catch (error) {
          throw new SourceError((error as Error).message, ref, 'rebuild the package with `modular2simple pack`');
        }
      })();
      this.packages.set(id, pending);
    }
    return pending;
  }

  /**
   * Reads a path such as `/abs/pkg.mosc/inner.mosc/main.xosc` (the path of a `mosc:` URI): the
   * longest prefix that is a file on disk is the package, the rest names entries, descending into
   * nested packages at each entry that is itself a package.
   */
  async refFromPackagePath(packagePath: string): Promise<SourceRef | undefined> {
    const segments = path.resolve(packagePath).split('/').filter((segment) => segment.length > 0);
    for (let split = segments.length - 1; split >= 1; split--) {
      const disk = '/' + segments.slice(0, split).join('/');
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
  private lookupPlaces(from: SourceRef): LookupPlace[] {
    const places: LookupPlace[] = [];
    const scenarioPath = this.scenarioPathFor(from);
    if (from.entries.length === 0) {
      const directory = path.dirname(from.disk);
      places.push({ packageRef: undefined, directory, via: 'folder' });
      for (const entry of scenarioPath) places.push({ packageRef: undefined, directory: entry, via: 'scenarioPath' });
      const root = this.rootOf(directory);
      if (isWithinFolder(directory, root)) {
        for (let parent = path.dirname(directory); ; parent = path.dirname(parent)) {
          if (!isWithinFolder(parent, root)) break;
          places.push({ packageRef: undefined, directory: parent, via: 'parent' });
          if (parent === root || parent === path.dirname(parent)) break;
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
      } catch {
        return undefined;
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
    const candidate = path.resolve(place.directory, name);
    if ((await this.kindOf(candidate)) === 'file') {
      const ref = diskRef(candidate);
      if (!wantPackage) return { kind: 'scenario', ref, via: place.via };
      return { kind: 'package', packageRef: ref, main: childRef(ref, 'main.xosc'), folder: false, via: place.via };
    }
    if (wantPackage) {
      const folder = candidate.slice(0, -'.mosc'.length);
      if ((await this.kindOf(path.join(folder, 'main.xosc'))) === 'file') {
        return { kind: 'package', packageRef: diskRef(folder), main: diskRef(path.join(folder, 'main.xosc')), folder: true, via: place.via };
      }
    }
    return undefined;
  }

  private describePlace(place: LookupPlace): string {
    if (place.packageRef) return place.directory ? `${displayRef(place.packageRef)}/${place.directory}` : displayRef(place.packageRef);
    const label = place.via === 'scenarioPath' ? ' (SCENARIO_PATH)' : place.via === 'parent' ? ' (parent folder)' : '';
    return `${path.relative(process.cwd(), place.directory) || '.'}${label}`;
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

