import * as path from 'node:path';
import { AnalysisResult, Flattener, FlatSource } from './core/flatten';
import { SchemaCheckMemory } from './core/schema/problems';
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
import { Problem } from './core/problems';
import { OpenDocument, OpenDocuments } from './documents';
import { UriResolver, refToUri } from './uris';
import { DEFAULT_SETTINGS, ServerSettings } from './settings';
import { ReusingFlattener, SHARED_SOURCE_BYTES, SharedSources } from './sharedSources';
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

/** An analysis of one generation: whole while pending or for an open document, else its problems only. */
interface CachedAnalysis {
  generation: number;
  result: Promise<AnalysisResult> | undefined;
  problems: Problem[];
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
  private generation = 0;
  private flattenerGeneration = -1;
  private currentFlattener: Flattener | undefined;
  /** Sources read so far, kept across generations until a file they depend on changes. */
  private readonly sharedSources: SharedSources;
  private readonly sourceDependencies = new Map<string, string[]>();
  /**
   * The files each open document's source read, as last known (kept in memory while it is open): the
   * dependencies of its last read (`from`), and the files a read still running has asked for since.
   */
  private readonly openDocumentReads = new Map<string, { ids: Set<string>; from: string[] | undefined }>();
  /** The last schema check of each file, shared by every generation's flattener. */
  private readonly schemaChecks = new SchemaCheckMemory();
  /** Analyses of the current generation; one of a file not open keeps only its problems, its source staying in the shared sources. */
  private readonly analysisResults = new Map<string, CachedAnalysis>();

  /** `sharedSourceBytes`: the bound of the read sources kept beyond those open documents read. */
  constructor(sharedSourceBytes = SHARED_SOURCE_BYTES) {
    this.sharedSources = new SharedSources(sharedSourceBytes, () => this.keptSources());
    this.storeInstance = this.createStore();
    this.uris = new UriResolver(() => this.storeInstance);
  }

  get store(): ScenarioStore {
    return this.storeInstance;
  }

  /** Grows with every change that can alter an analysis: equal versions give equal diagnostics. */
  get version(): number {
    return this.generation;
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
      root: this.folders[0],
      folders,
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
    this.generation++;
    // Each change starts a new run: what the next analyses may unpack is counted afresh.
    this.storeInstance.resetBudget();
    // Remembers what open documents read before their dependencies are forgotten below.
    this.keptSources();
    if (!changedIds) {
      this.analysisResults.clear();
      this.sharedSources.clear();
      this.sourceDependencies.clear();
      return;
    }
    const touches = (id: string) => changedIds.some((changed) => id === changed || id.startsWith(changed + '/'));
    for (const id of [...this.analysisResults.keys()]) if (touches(id)) this.analysisResults.delete(id);
    for (const id of this.sharedSources.keys()) {
      const dependencies = this.sourceDependencies.get(id);
      // A source still being read has unknown dependencies, so it goes too.
      if (!dependencies || touches(id) || dependencies.some(touches)) {
        this.sharedSources.delete(id);
        this.sourceDependencies.delete(id);
      }
    }
  }

  /** Open documents and every file their sources read: what each edit of an open file reads again. */
  private keptSources(): Set<string> {
    const kept = new Set<string>();
    const open = new Set<string>();
    for (const document of this.documents.values()) {
      const id = refId(document.ref);
      open.add(id);
      kept.add(id);
      // An edit forgets the file's dependencies until it is read again: what it read last time stays meanwhile.
      const known = this.sourceDependencies.get(id);
      let reads = this.openDocumentReads.get(id);
      if (!reads || (known && reads.from !== known)) {
        reads = { ids: new Set(known), from: known };
        this.openDocumentReads.set(id, reads);
      }
      for (const dependency of reads.ids) kept.add(dependency);
    }
    for (const id of [...this.openDocumentReads.keys()]) if (!open.has(id)) this.openDocumentReads.delete(id);
    return kept;
  }

  /**
   * A file read for an open document's analysis is kept from the moment it is read: counted against
   * the bound until that analysis ends, the files read first were let go while it read the others,
   * and the next edit read them all again (144 of 400 for a main file with 400 references).
   */
  private noteRead(reader: string, id: string): void {
    if (!this.documents.get(reader) || this.sourceDependencies.has(reader)) return;
    const reads = this.openDocumentReads.get(reader);
    if (reads) reads.ids.add(id);
    else this.openDocumentReads.set(reader, { ids: new Set([id]), from: undefined });
  }

  flattener(): Flattener {
    if (!this.currentFlattener || this.flattenerGeneration !== this.generation) {
      this.currentFlattener = new ReusingFlattener(
        this.storeInstance,
        this.sharedSources,
        this.sourceDependencies,
        this.settings.simulator,
        { version: this.settings.schemaVersion },
        this.schemaChecks,
        (reader, id) => this.noteRead(reader, id),
        this.settings.carlaRelease,
      );
      this.flattenerGeneration = this.generation;
    }
    return this.currentFlattener;
  }

  /** The file read and flattened as the current generation sees it. */
  source(ref: SourceRef): Promise<FlatSource> {
    return this.flattener().source(ref, []);
  }

  /** The file analysed as a main file (with the checks only a main file gets), cached per generation. */
  analyze(ref: SourceRef): Promise<AnalysisResult> {
    const id = refId(ref);
    const cached = this.analysisResults.get(id);
    if (cached && cached.generation === this.generation) {
      if (cached.result) return cached.result;
      const problems = cached.problems;
      // The source as the shared sources still hold it, or read again: the same text gives the same source.
      return this.source(ref).then((source) => ({ problems, source }));
    }
    const result = this.flattener().analyze(ref);
    const fresh: CachedAnalysis = { generation: this.generation, result, problems: [] };
    this.analysisResults.set(id, fresh);
    // A file not open must not keep its parse tree past the bound of the shared sources.
    if (!this.documents.get(id))
      result.then(
        (analysis) => {
          if (this.analysisResults.get(id) !== fresh || this.documents.get(id)) return;
          fresh.problems = analysis.problems;
          fresh.result = undefined;
        },
        () => undefined,
      );
    if (this.analysisResults.size > SERVER_MEMOS.analyses.bound.entries)
      for (const [key, entry] of this.analysisResults) if (entry.generation !== this.generation) this.analysisResults.delete(key);
    return result;
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
    // What the document kept (the files it read) counts against the bound again.
    this.sharedSources.trim();
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
