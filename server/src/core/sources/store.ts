import { normalizeEntryName, PackageContents } from '../../../../common/src/packageEntries';
import { splitScenarioPath } from '../../../../common/src/scenarioPath';
import { decodeScenario, DecodeError } from '../encoding';
import { pathsFor, splitDiskPath } from '../paths';
import { closestMatch } from '../text';
import { XmlDocument } from '../xml';
import { FileKind, FileSystemHost, KindCache, nodeFileSystem } from './host';
import { DEFAULT_LIMITS, Limits } from './limits';
import { Overlays } from './overlays';
import { PackageCache } from './packages';
import { childRef, diskRef, displayRef, refId, SourceError, SourceRef } from './ref';
import { CORE_MEMOS } from '../memos';
import { FolderOptions, isWithinFolder, LIBRARY_PREFIX, LibraryFolder, libraryFileName, LookupPlace, Resolution } from './resolution';

export interface StoreOptions {
  /** Directories searched after the package itself: SCENARIO_PATH first, then the editor's setting. */
  scenarioPath?: string[];
  /**
   * Folders a run hands esmini as `--path` besides the scenario path (`run --road-path`, the
   * `modular2simple.esmini.roadPath` setting): esmini finds catalogs there too, so catalog directories are looked for in
   * them after the scenario path. Not searched for scenario files.
   */
  catalogPath?: string[];
  /** The caller's environment; its SCENARIO_PATH is the scenario path when `scenarioPath` is not given. */
  environment?: Readonly<Record<string, string | undefined>>;
  /**
   * The caller's working directory: messages show paths relative to it, and it ends the upward
   * search when no `root` is given. Without it paths are shown whole and there is no upward search.
   */
  workingDirectory?: string;
  /** The folder where the upward search of unpacked folders stops (workspace folder or working directory). */
  root?: string;
  /**
   * Workspace folders: a file inside one searches upward to it (not to `root`) and uses its own
   * scenario path instead of `scenarioPath` (an editor's per-folder setting).
   */
  folders?: FolderOptions[];
  /** The scenario libraries `library:NAME` is looked up in, in order: the first holding NAME wins. */
  libraries?: LibraryFolder[];
  host?: FileSystemHost;
  limits?: Partial<Limits>;
  /** Bytes of unpacked packages kept for reuse; the least recently used are read again when needed. */
  packageCacheBytes?: number;
}

/** Reads scenario files from disk and packages, and resolves `scenarioFileName`s (SPEC 3). */
export class ScenarioStore {
  readonly host: FileSystemHost;
  readonly scenarioPath: string[];
  readonly catalogPath: string[];
  readonly root: string | undefined;
  readonly folders: FolderOptions[];
  readonly libraries: LibraryFolder[];
  readonly limits: Limits;
  /** Relative to it messages show paths, and the upward search stops there when no folder or root holds a file. */
  readonly workingDirectory: string | undefined;
  private readonly packages: PackageCache;
  private readonly overlays = new Overlays();
  private readonly kinds: KindCache;
  /** Names found, by the file writing them, while the kinds they were found from hold (`resolutions` of core/memos.ts). */
  private readonly resolutions = new Map<string, Map<string, Resolution>>();
  /** The names in `resolutions`, all files together (its bound). */
  private resolutionCount = 0;
  private resolutionsGeneration = 0;

  constructor(options: StoreOptions = {}) {
    this.host = options.host ?? nodeFileSystem;
    this.kinds = this.host.kinds ?? new KindCache(this.host);
    this.scenarioPath = options.scenarioPath ?? splitScenarioPath(options.environment?.SCENARIO_PATH);
    this.catalogPath = options.catalogPath ?? [];
    this.workingDirectory = options.workingDirectory;
    this.root = options.root ? pathsFor(options.root).resolve(options.root) : undefined;
    // Innermost first, so a folder nested in another is found before it.
    this.folders = (options.folders ?? [])
      .map((entry) => ({ ...entry, folder: pathsFor(entry.folder).resolve(entry.folder) }))
      .sort((a, b) => b.folder.length - a.folder.length);
    this.libraries = (options.libraries ?? []).map((entry) => ({ ...entry, folder: pathsFor(entry.folder).resolve(entry.folder) }));
    this.limits = { ...DEFAULT_LIMITS, ...options.limits };
    this.packages = new PackageCache(
      this.limits,
      options.packageCacheBytes ?? Infinity,
      (ref) => this.readBytes(ref),
      (ref) => this.display(ref),
    );
  }

  /** Starts a new run: what it may unpack is counted from zero (packages still cached cost nothing). */
  resetBudget(): void {
    this.packages.resetBudget();
  }

  /** Bytes of unpacked packages held for reuse. */
  get cachedPackageBytes(): number {
    return this.packages.size;
  }

  /** Text that replaces a file's stored content, as an editor's unsaved buffer does. */
  setOverlay(ref: SourceRef, text: string | undefined): void {
    this.overlays.set(ref, text);
  }

  /** Parses a file's text; a file being edited is re-parsed from its previous parse where it can be. */
  parse(ref: SourceRef, text: string): XmlDocument {
    return this.overlays.parse(ref, text);
  }

  /** The parse `parse` last gave of a file being edited, when it is of `text` (nothing is parsed); undefined otherwise. */
  lastParse(ref: SourceRef, text: string): XmlDocument | undefined {
    return this.overlays.lastParse(ref, text);
  }

  /**
   * Parses the flattened text of a file being edited, from its previous flattened parse where it
   * can be: an edit inside one value of the file changes one value of its flattened text too.
   */
  parseFlattened(ref: SourceRef, text: string): XmlDocument {
    return this.overlays.parseFlattened(ref, text);
  }

  /** Forgets what was read of a file on disk (a package is read again on next use). */
  invalidate(diskPath: string): void {
    const paths = pathsFor(diskPath);
    const resolved = paths.resolve(diskPath);
    this.kinds.clear();
    // Entries of a package follow its path after `/`; files of a folder after the platform's separator.
    const below = (key: string) => key === resolved || key.startsWith(resolved + '/') || key.startsWith(resolved + paths.sep);
    this.packages.invalidate(below);
  }

  /** Whether a path is a file or a folder; remembered until the next invalidate. */
  kindOf(filePath: string): Promise<FileKind> {
    return this.kinds.kind(filePath);
  }

  /** A reference as messages show it: relative to the working directory when it lies below it (whole without one). */
  display(ref: SourceRef): string {
    return displayRef(ref, this.workingDirectory);
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
    if (!bytes)
      throw new SourceError(
        `${this.display(parent)} holds no entry '${ref.entries[ref.entries.length - 1]}'`,
        ref,
        undefined,
        undefined,
        'bad-package',
      );
    return bytes;
  }

  async readText(ref: SourceRef): Promise<string> {
    const overlay = this.overlays.get(ref);
    if (overlay !== undefined) return overlay;
    const bytes = await this.readBytes(ref);
    try {
      return decodeScenario(bytes);
    } catch (error) {
      if (!(error instanceof DecodeError)) throw error;
      throw new SourceError(`${this.display(ref)}: ${error.message}`, ref, undefined, error.line);
    }
  }

  /** The entries of the package stored at `ref` (a `.mosc` on disk or inside another package). */
  readPackage(ref: SourceRef): Promise<PackageContents> {
    return this.packages.read(ref);
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

  /** Where the upward search from `directory` stops: its workspace folder, else the root, else the working directory (else `directory` itself: no upward search). */
  rootOf(directory: string): string {
    return this.folderOf(directory)?.folder ?? this.root ?? this.workingDirectory ?? directory;
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
        return {
          kind: 'package',
          packageRef: diskRef(folder),
          main: diskRef(paths.join(folder, 'main.xosc')),
          folder: true,
          via: place.via,
        };
      }
    }
    return undefined;
  }

  /** A place as a message names it: an absolute folder (a relative one, say '.', leaves the reader guessing which). */
  private describePlace(place: LookupPlace): string {
    if (place.packageRef)
      return [place.packageRef.disk, ...place.packageRef.entries, ...(place.directory ? [place.directory] : [])].join('/');
    const label = place.via === 'scenarioPath' ? ' (SCENARIO_PATH)' : place.via === 'parent' ? ' (parent folder)' : '';
    return `${place.directory}${label}`;
  }

  /** The scenario and package names that exist in the places searched, written as `name` would be (its folder part kept). */
  private async namesIn(places: LookupPlace[], name: string): Promise<string[]> {
    const folderPart = name.slice(0, Math.max(name.lastIndexOf('/'), name.lastIndexOf('\\')) + 1);
    const names = new Set<string>();
    const isScenarioName = (entry: string) => /\.(xosc|mosc)$/i.test(entry);
    for (const place of places) {
      if (place.packageRef) {
        // normalizeEntryName takes a file's entry name: that of a placeholder file gives the folder's, with its '/'.
        const folder = normalizeEntryName(place.directory ? `${place.directory}/${folderPart}x` : `${folderPart}x`)?.slice(0, -1);
        if (folder === undefined) continue;
        const contents = await this.readPackage(place.packageRef).catch(() => undefined);
        for (const entry of contents?.entries.keys() ?? []) {
          const rest = entry.startsWith(folder) ? entry.slice(folder.length) : undefined;
          if (rest && !rest.includes('/') && isScenarioName(rest)) names.add(`${folderPart}${rest}`);
        }
        continue;
      }
      const listed = (await this.host.listDirectory?.(pathsFor(place.directory).resolve(place.directory, folderPart || '.'))) ?? [];
      for (const entry of listed) if (isScenarioName(entry)) names.add(`${folderPart}${entry}`);
    }
    return [...names];
  }

  /**
   * Resolves `library:NAME`: `NAME.xosc` (or NAME, when it ends in .xosc or .mosc) in each library folder in
   * order, the first that holds it winning; the others holding it are `shadowed`.
   */
  async resolveInLibraries(moduleName: string): Promise<Resolution> {
    const fileName = libraryFileName(moduleName.trim());
    if (!moduleName.trim() || /[\\/]/.test(moduleName) || moduleName.includes('..'))
      return { kind: 'invalid', message: `'${LIBRARY_PREFIX}${moduleName}' must name a module of a library: ${LIBRARY_PREFIX}NAME` };
    const isPackage = fileName.toLowerCase().endsWith('.mosc');
    const found: Resolution[] = [];
    for (const library of this.libraries) {
      const place: LookupPlace = { packageRef: undefined, directory: library.folder, via: 'library' };
      const resolution = await this.findIn(place, fileName, isPackage);
      if (resolution) found.push(resolution);
    }
    if (found.length > 0) {
      const shadowed = found
        .slice(1)
        .flatMap((other) => (other.kind === 'scenario' ? [other.ref.disk] : other.kind === 'package' ? [other.packageRef.disk] : []));
      return shadowed.length > 0 && (found[0].kind === 'scenario' || found[0].kind === 'package') ? { ...found[0], shadowed } : found[0];
    }
    const names: string[] = [];
    for (const library of this.libraries) {
      const listed = (await this.host.listDirectory?.(library.folder)) ?? [];
      for (const entry of listed) if (/\.xosc$/i.test(entry)) names.push(entry.slice(0, -'.xosc'.length));
    }
    const suggestion = closestMatch(moduleName.trim().replace(/\.xosc$/i, ''), names);
    return {
      kind: 'missing',
      searched: this.libraries.map((library) => `${library.folder} (${library.label} library)`),
      hint:
        this.libraries.length === 0
          ? 'no scenario library is known here: name a folder in SCENARIO_LIBRARY_PATH or the modular2simple.library.folders setting'
          : 'modular2simple library list names every module',
      ...(suggestion ? { suggestion: `${LIBRARY_PREFIX}${suggestion}` } : {}),
    };
  }

  /** The resolution `resolve` would give now without looking again: a file found while no kind changed; otherwise undefined. */
  knownResolution(name: string, from: SourceRef): Resolution | undefined {
    // A file found is found again while no kind changed (a package's contents change only with an invalidate, which clears the kinds).
    const generation = this.kinds.generation;
    if (generation !== this.resolutionsGeneration) {
      this.clearResolutions();
      this.resolutionsGeneration = generation;
    }
    // By file, then name: no key string is made for each of a main file's references on each edit.
    return this.resolutions.get(refId(from))?.get(name);
  }

  private clearResolutions(): void {
    this.resolutions.clear();
    this.resolutionCount = 0;
  }

  /** Resolves a `scenarioFileName` written in the file `from` (SPEC 3). */
  async resolve(name: string, from: SourceRef): Promise<Resolution> {
    const known = this.knownResolution(name, from);
    if (known) return known;
    const generation = this.kinds.generation;
    const resolution = await this.resolveAgain(name, from);
    if ((resolution.kind === 'scenario' || resolution.kind === 'package') && this.kinds.generation === generation) {
      if (this.resolutionCount >= CORE_MEMOS.resolutions.bound.entries) this.clearResolutions();
      const fromId = refId(from);
      let names = this.resolutions.get(fromId);
      if (!names) this.resolutions.set(fromId, (names = new Map()));
      if (!names.has(name)) this.resolutionCount++;
      names.set(name, resolution);
    }
    return resolution;
  }

  private async resolveAgain(name: string, from: SourceRef): Promise<Resolution> {
    const trimmed = name.trim();
    if (!trimmed) return { kind: 'invalid', message: 'scenarioFileName is empty' };
    if (trimmed.startsWith(LIBRARY_PREFIX)) return this.resolveInLibraries(trimmed.slice(LIBRARY_PREFIX.length));
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
    // Never the referencing file itself (a package's main.xosc is no 'simple_1.xosc'), and names compared without their
    // extension, which every candidate shares and which made 'main.xosc' close enough to 'simple_1.xosc'.
    const ownName = from.entries.length > 0 ? from.entries[from.entries.length - 1] : pathsFor(from.disk).basename(from.disk);
    const stem = (file: string) => file.replace(/\.(xosc|mosc)$/i, '');
    const candidates = (await this.namesIn(places, trimmed)).filter((candidate) => candidate !== trimmed && candidate !== ownName);
    const closest = closestMatch(stem(trimmed), candidates.map(stem));
    const suggestion = closest === undefined ? undefined : candidates.find((candidate) => stem(candidate) === closest);
    return {
      kind: 'missing',
      searched,
      hint:
        this.scenarioPath.length === 0
          ? 'set SCENARIO_PATH (--scenario-path, the modular2simple.scenarioPath setting) to the folder that holds it'
          : undefined,
      ...(suggestion ? { suggestion } : {}),
    };
  }
}
