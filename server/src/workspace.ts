import * as path from 'node:path';
import { AnalysisResult, Flattener, FlatSource } from './core/flatten';
import {
  FileSystemHost,
  KindCache,
  nodeFileSystem,
  refId,
  ScenarioStore,
  SizedCache,
  SourceRef,
  splitScenarioPath,
  diskRef,
  childRef,
} from './core/sources';
import { OpenDocument, OpenDocuments } from './documents';
import { libraryFolders } from './libraries';
import { roadFolders } from './core/semantics/roadFiles';
import { UriResolver, refToUri } from './uris';
import { DEFAULT_SETTINGS, ServerSettings } from './settings';
import { SHARED_SOURCE_BYTES } from './sharedSources';
import { AnalysisDatabase } from './analysisDatabase';
import { decodeOrUndefined, IndexedFile, isIndexedFolder, mainOf, scanScenario, WorkspaceIndex } from './workspaceIndex';
import { SERVER_MEMOS } from './database';

export { IndexedFile, IndexedGroup, listScenarioFiles, mainOf, scanScenario } from './workspaceIndex';

/** A file read as a catalog may take problems from any main file whose catalog locations name its folder. */
const MAY_BE_CATALOG = /<Catalog\b/;

/** Bytes of files and of unpacked packages that the server keeps, each; the rest is read again on demand. */
export const SERVER_CACHE_BYTES: number = SERVER_MEMOS.fileBytes.bound.bytes;

/**
 * Keeps file bytes (up to a total size, least recently used first out) and kinds in memory until a
 * change notification says they are stale.
 */
export class CachingFileSystem implements FileSystemHost {
  private readonly bytes: SizedCache<Uint8Array | undefined>;
  private readonly pending = new Map<string, Promise<Uint8Array | undefined>>();
  /** The one cache of kinds: the store built on this host shares it. */
  readonly kinds: KindCache;

  constructor(
    private readonly inner: FileSystemHost = nodeFileSystem,
    maxBytes = SERVER_CACHE_BYTES,
  ) {
    this.bytes = new SizedCache(maxBytes);
    this.kinds = new KindCache(inner);
  }

  /** Bytes held. */
  get size(): number {
    return this.bytes.size;
  }

  readFile(filePath: string, maxBytes?: number): Promise<Uint8Array | undefined> {
    const cached = this.bytes.get(filePath);
    if (cached) return Promise.resolve(cached);
    let pending = this.pending.get(filePath);
    if (!pending) {
      const reading = this.inner.readFile(filePath, maxBytes);
      pending = reading;
      this.pending.set(filePath, reading);
      const settle = () => {
        if (this.pending.get(filePath) === reading) this.pending.delete(filePath);
      };
      reading.then((bytes) => {
        if (this.pending.get(filePath) === reading && bytes) this.bytes.set(filePath, bytes, bytes.length);
        settle();
      }, settle);
    }
    return pending;
  }

  /** The bytes held, or read without keeping them: for a reader that needs them once (the index's scan). */
  readOnce(filePath: string, maxBytes?: number): Promise<Uint8Array | undefined> {
    return this.bytes.get(filePath) !== undefined || this.pending.has(filePath)
      ? this.readFile(filePath, maxBytes)
      : this.inner.readFile(filePath, maxBytes);
  }

  kind(filePath: string): Promise<'file' | 'directory' | undefined> {
    return this.kinds.kind(filePath);
  }

  listDirectory(directoryPath: string): Promise<string[] | undefined> {
    return this.inner.listDirectory?.(directoryPath) ?? Promise.resolve(undefined);
  }

  /** Forgets a path and everything below it; kinds are all forgotten since a creation changes folders too. */
  invalidate(filePath: string): void {
    const below = (key: string) => key === filePath || key.startsWith(filePath + path.sep);
    this.bytes.deleteWhere(below);
    for (const key of [...this.pending.keys()]) if (below(key)) this.pending.delete(key);
    this.kinds.clear();
  }

  clear(): void {
    this.bytes.clear();
    this.pending.clear();
    this.kinds.clear();
  }
}

/**
 * The server's view of the workspace: the store (with unsaved editor text as overlays), the open
 * documents, an index of scenario files and one Flattener per generation of changes.
 */
export class Workspace {
  readonly files = new CachingFileSystem();
  readonly documents = new OpenDocuments();
  readonly index = new WorkspaceIndex();
  readonly uris: UriResolver;
  folders: string[] = [];
  settings: ServerSettings = DEFAULT_SETTINGS;
  /** Each folder's own `scenarioPath` setting, by folder path. */
  private folderScenarioPaths = new Map<string, string[]>();
  /** Whether the client opens and saves files inside packages (`mosc:` URIs), so edits may reach them. */
  editablePackages = false;
  private storeInstance: ScenarioStore;
  /** The folders of every `scenarioPath` the store searches (the environment's, the window's, each folder's). */
  private searchFolders: string[] = [];
  /** The owner of everything derived from the inputs above: sources, analyses, schema checks, the generation. */
  readonly database: AnalysisDatabase;

  /** `sharedSourceBytes`: the bound of the read sources kept beyond those open documents read. */
  constructor(sharedSourceBytes = SHARED_SOURCE_BYTES) {
    this.database = new AnalysisDatabase(
      { store: () => this.storeInstance, settings: () => this.settings, documents: this.documents },
      sharedSourceBytes,
    );
    this.storeInstance = this.createStore();
    this.uris = new UriResolver(() => this.storeInstance);
  }

  get store(): ScenarioStore {
    return this.storeInstance;
  }

  /**
   * Folders already watched: the workspace folders (the server's registration), the searched and road folders (the
   * client's, client/src/scenarioPathWatchers.ts), and the libraries (shipped, not edited).
   */
  get watchedRoots(): string[] {
    const store = this.storeInstance;
    return [...this.folders, ...this.searchFolders, ...store.catalogPath, ...store.libraries.map((library) => library.folder)];
  }

  /** Grows with every change that can alter an analysis: equal versions give equal diagnostics. */
  get version(): number {
    return this.database.version;
  }

  private createStore(): ScenarioStore {
    const fromEnvironment = splitScenarioPath(process.env.SCENARIO_PATH);
    const fromSettings = this.settings.scenarioPath.map((entry) => path.resolve(this.folders[0] ?? process.cwd(), entry));
    // Each folder searches its own setting (resource-scoped), relative entries taken from that folder.
    const folders = this.folders.map((folder) => ({
      folder,
      scenarioPath: [
        ...fromEnvironment,
        ...(this.folderScenarioPaths.get(folder) ?? this.settings.scenarioPath).map((entry) => path.resolve(folder, entry)),
      ],
    }));
    this.searchFolders = [...fromEnvironment, ...fromSettings, ...folders.flatMap((folder) => folder.scenarioPath)];
    const store = new ScenarioStore({
      scenarioPath: [...fromEnvironment, ...fromSettings],
      // Run in esmini hands esmini these folders as --path, where it finds catalogs too: so do the checks.
      catalogPath: roadFolders(this.settings.roadPath, this.folders[0] ?? process.cwd()),
      root: this.folders[0],
      folders,
      // Relative library folders are taken from the first workspace folder, as the window's scenarioPath is.
      libraries: libraryFolders(this.settings.libraryFolders.map((entry) => path.resolve(this.folders[0] ?? process.cwd(), entry))),
      host: this.files,
      packageCacheBytes: SERVER_CACHE_BYTES,
      workingDirectory: process.cwd(),
    });
    for (const open of this.documents.values()) store.setOverlay(open.ref, open.document.getText());
    return store;
  }

  /**
   * Sets the workspace folders and the settings: those of the window, and each folder's own
   * `scenarioPath` where the client gave one (folders not in the map use the window's).
   */
  configure(folders: string[], settings: ServerSettings, folderScenarioPaths = new Map<string, string[]>()): void {
    this.folders = folders.map((folder) => path.resolve(folder));
    this.settings = settings;
    this.folderScenarioPaths = new Map([...folderScenarioPaths].map(([folder, entries]) => [path.resolve(folder), entries]));
    this.storeInstance = this.createStore();
    this.changed();
  }

  /**
   * Marks analyses stale: those depending on the given files (ids, or disk paths of files and
   * folders), or every one when no file is named (settings, or a file appearing or vanishing,
   * which can change how any name resolves).
   */
  changed(changedIds?: string[]): void {
    // Each change starts a new run: what the next analyses may unpack is counted afresh.
    this.storeInstance.resetBudget();
    this.database.changed(changedIds);
  }

  flattener(): Flattener {
    return this.database.flattener();
  }

  /** The file read and flattened as the current generation sees it. */
  source(ref: SourceRef): Promise<FlatSource> {
    return this.database.source(ref);
  }

  /** The file analysed as a main file (with the checks only a main file gets), cached per generation. */
  analyze(ref: SourceRef): Promise<AnalysisResult> {
    return this.database.analyze(ref);
  }

  /** Attaches a document the client opened to its file: its text now overrides the disk. */
  open(uri: string, ref: SourceRef): OpenDocument | undefined {
    const open = this.documents.resolve(uri, ref);
    if (!open) return undefined;
    this.uris.remember(uri, ref);
    this.storeInstance.setOverlay(ref, open.document.getText());
    this.changed([refId(ref)]);
    return open;
  }

  /** The open document's text changed (the registry already holds the new text). */
  update(ref: SourceRef): void {
    const open = this.documents.get(refId(ref));
    if (!open) return;
    this.storeInstance.setOverlay(ref, open.document.getText());
    // The index is read again on its next use, from the unsaved text.
    if (ref.entries.length === 0) this.index.delete(ref.disk);
    this.changed([refId(ref)]);
  }

  /** The client closed a URI; returns the file it stood for, whose disk text counts again. */
  close(uri: string): OpenDocument | undefined {
    const open = this.documents.remove(uri)?.resolved;
    if (!open) return undefined;
    this.uris.forget(uri);
    this.storeInstance.setOverlay(open.ref, undefined);
    this.changed([refId(open.ref)]);
    this.database.documentClosed();
    return open;
  }

  /** The URI to send for a file: the client's own spelling when the file is open. */
  uriOf(ref: SourceRef): string {
    return this.documents.get(refId(ref))?.uri ?? refToUri(ref);
  }

  /** The text of a file as the editor sees it (unsaved text first); undefined when unreadable. */
  async text(ref: SourceRef): Promise<string | undefined> {
    return this.storeInstance.readText(ref).catch(() => undefined);
  }

  /** A file on disk changed (`existence` false), or appeared or vanished (true: names may resolve differently). */
  fileChanged(filePath: string, existence = true): void {
    const resolved = path.resolve(filePath);
    this.files.invalidate(resolved);
    this.storeInstance.invalidate(resolved);
    this.index.delete(resolved);
    if (existence) this.index.forgetListing();
    this.changed(existence ? undefined : [resolved]);
  }

  /** Reads one file into the index; files that vanish or cannot be parsed are indexed without groups. */
  async indexFile(filePath: string): Promise<IndexedFile> {
    const kind: IndexedFile['kind'] = filePath.toLowerCase().endsWith('.mosc') ? 'mosc' : 'xosc';
    const entry: IndexedFile = { path: filePath, kind, groups: [], modular: false, catalogReferences: [], scenarioNames: [] };
    if (kind === 'xosc') {
      // The scan needs the bytes once; the files an analysis reads are kept when it reads them.
      const bytes = await this.files.readOnce(filePath);
      if (bytes) {
        const open = this.documents.get(refId(diskRef(filePath)));
        const text =
          bytes.length > this.settings.maxIndexedFileBytes ? undefined : open ? open.document.getText() : decodeOrUndefined(bytes);
        if (text !== undefined) Object.assign(entry, scanScenario(text, diskRef(filePath)));
        else {
          entry.catalogReferences.push({ ref: diskRef(filePath), entryNames: undefined });
          entry.scenarioNames = undefined;
        }
      }
    } else {
      entry.modular = true;
      // The scenarios stored at the root of a package (nested packages are left to their own readers).
      const packageRef = diskRef(filePath);
      const contents = await this.storeInstance.readPackage(packageRef).catch(() => undefined);
      const scenarioNames: string[] = [];
      let scanned = true;
      for (const [name, bytes] of contents?.entries ?? []) {
        // A nested package's references are not scanned: the package may reach any file.
        if (name.toLowerCase().endsWith('.mosc')) scanned = false;
        if (!name.toLowerCase().endsWith('.xosc')) continue;
        const text = bytes.length <= this.settings.maxIndexedFileBytes ? decodeOrUndefined(bytes) : undefined;
        if (text === undefined) {
          entry.catalogReferences.push({ ref: childRef(packageRef, name), entryNames: undefined });
          scanned = false;
          continue;
        }
        const scan = scanScenario(text, childRef(packageRef, name));
        entry.groups.push(...scan.groups);
        entry.catalogReferences.push(...scan.catalogReferences);
        if (scan.scenarioNames) scenarioNames.push(...scan.scenarioNames);
        else scanned = false;
      }
      entry.scenarioNames = scanned ? scenarioNames : undefined;
    }
    this.index.set(filePath, entry);
    return entry;
  }

  /** Indexes every scenario file of the workspace folders, reporting progress as a fraction done. */
  async indexAll(progress?: (done: number, total: number) => void): Promise<number> {
    this.storeInstance.resetBudget();
    const filePaths = await this.index.walk(this.folders);
    let done = 0;
    for (const filePath of filePaths) {
      try {
        await this.indexFile(filePath);
      } catch {
        // A file that vanished or cannot be read is simply left out of the index.
      }
      done++;
      if (progress && (done % 50 === 0 || done === filePaths.length)) progress(done, filePaths.length);
    }
    return filePaths.length;
  }

  /**
   * The distribution files of the workspace whose ScenarioFile is the scenario `ref` (a plain file, or the unpacked
   * folder or package whose main.xosc it is), from the index.
   */
  async distributionsOf(ref: SourceRef): Promise<string[]> {
    const named = new Set<string>();
    if (ref.entries.length === 0) {
      named.add(path.resolve(ref.disk));
      if (path.basename(ref.disk) === 'main.xosc') named.add(path.dirname(path.resolve(ref.disk)));
    } else if (ref.entries.length === 1 && ref.entries[0] === 'main.xosc') named.add(path.resolve(ref.disk));
    const found: string[] = [];
    for (const entry of await this.indexedFiles()) {
      if (entry.distributionOf === undefined) continue;
      const scenario = path.resolve(path.dirname(entry.path), entry.distributionOf);
      if (named.has(scenario) || named.has(scenario.replace(/[\\/]+$/, ''))) found.push(entry.path);
    }
    return found;
  }

  /** Index entries, reading again any file that changed since it was indexed. */
  async indexedFiles(): Promise<IndexedFile[]> {
    return this.entriesOf(await this.index.walk(this.folders));
  }

  private async entriesOf(known: string[]): Promise<IndexedFile[]> {
    const result: IndexedFile[] = [];
    for (const filePath of known) {
      const entry = this.index.get(filePath) ?? (await this.indexFile(filePath).catch(() => undefined));
      if (entry) result.push(entry);
    }
    return result;
  }

  /**
   * The scenarios that may name catalog entry `entryName` (undefined: any) in a CatalogReference: from
   * the index's reverse index (no other file is read), and the open documents (their text in memory).
   */
  async catalogReferrers(entryName?: string): Promise<SourceRef[]> {
    const refs = new Map<string, SourceRef>();
    const entries = await this.entriesOf(await this.index.paths(this.folders));
    for (const ref of WorkspaceIndex.catalogReferrers(entries, entryName)) {
      // A folder that vanished is not reported file by file: a candidate of the kept list is checked to exist.
      if ((await this.files.kind(ref.disk)) === 'file') refs.set(refId(ref), ref);
    }
    for (const open of this.documents.values()) refs.set(refId(open.ref), open.ref);
    return [...refs.values()];
  }

  /**
   * The main files whose references may reach another file: every modular file of the workspace, and the
   * open ones. With a `target`, only those that may reach it (`WorkspaceIndex.referrersOf`, from the
   * index's scan of their `scenarioFileName`s; no other file is read), unless names may resolve outside
   * the index (a `scenarioPath` folder it does not hold) or the target may be read as a catalog.
   */
  async referringFiles(target?: SourceRef): Promise<SourceRef[]> {
    const refs = new Map<string, SourceRef>();
    const entries = await this.entriesOf(await this.index.paths(this.folders));
    const narrowed =
      target !== undefined &&
      this.searchFolders.every((folder) => isIndexedFolder(folder, this.folders)) &&
      !MAY_BE_CATALOG.test((await this.text(target)) ?? '<Catalog ');
    const mains = narrowed
      ? WorkspaceIndex.referrersOf(entries, target)
      : entries.filter((entry) => entry.kind === 'mosc' || entry.modular).map((entry) => mainOf(entry.path, entry.kind));
    // A folder that vanished is not reported file by file: a main of the kept list is checked to exist.
    for (const main of mains) if ((await this.files.kind(main.disk)) === 'file') refs.set(refId(main), main);
    for (const open of this.documents.values()) refs.set(refId(open.ref), open.ref);
    return [...refs.values()];
  }
}
