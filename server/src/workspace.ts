import * as fs from 'node:fs';
import * as path from 'node:path';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { Flattener, FlatSource, FlattenResult } from './core/flatten';
import { buildModel, ManeuverGroupInfo } from './core/model';
import { FileSystemHost, nodeFileSystem, refId, ScenarioStore, SourceRef, splitScenarioPath, diskRef, childRef } from './core/sources';
import { decodeUtf8, Range } from './core/text';
import { parseXml } from './core/xml';
import { UriResolver, refToUri } from './uris';

export interface ServerSettings {
  /** Directories searched after SCENARIO_PATH. */
  scenarioPath: string[];
  /** Delay between the last edit and new diagnostics, in milliseconds. */
  diagnosticsDelay: number;
  /** Files larger than this are indexed by name only, never parsed for workspace symbols. */
  maxIndexedFileBytes: number;
}

export const DEFAULT_SETTINGS: ServerSettings = { scenarioPath: [], diagnosticsDelay: 15, maxIndexedFileBytes: 8 * 1024 * 1024 };

/** Reads settings sent by a client, keeping defaults for anything missing or of the wrong type. */
export function readSettings(value: unknown): ServerSettings {
  const record = (value && typeof value === 'object' ? value : {}) as Record<string, unknown>;
  const scenarioPath = Array.isArray(record.scenarioPath)
    ? record.scenarioPath.filter((entry): entry is string => typeof entry === 'string' && entry.trim().length > 0)
    : typeof record.scenarioPath === 'string'
      ? splitScenarioPath(record.scenarioPath)
      : [];
  const diagnostics = (record.diagnostics && typeof record.diagnostics === 'object' ? record.diagnostics : {}) as Record<string, unknown>;
  const delay = typeof diagnostics.delay === 'number' && diagnostics.delay >= 0 ? diagnostics.delay : DEFAULT_SETTINGS.diagnosticsDelay;
  return { scenarioPath, diagnosticsDelay: delay, maxIndexedFileBytes: DEFAULT_SETTINGS.maxIndexedFileBytes };
}

/** Keeps file bytes and kinds in memory until a change notification says they are stale. */
export class CachingFileSystem implements FileSystemHost {
  private readonly bytes = new Map<string, Promise<Uint8Array | undefined>>();
  private readonly kinds = new Map<string, Promise<'file' | 'directory' | undefined>>();

  constructor(private readonly inner: FileSystemHost = nodeFileSystem) {}

  readFile(filePath: string): Promise<Uint8Array | undefined> {
    let pending = this.bytes.get(filePath);
    if (!pending) {
      pending = this.inner.readFile(filePath);
      this.bytes.set(filePath, pending);
    }
    return pending;
  }

  kind(filePath: string): Promise<'file' | 'directory' | undefined> {
    let pending = this.kinds.get(filePath);
    if (!pending) {
      pending = this.inner.kind(filePath);
      this.kinds.set(filePath, pending);
    }
    return pending;
  }

  /** Forgets a path and everything below it; kinds are all forgotten since a creation changes folders too. */
  invalidate(filePath: string): void {
    for (const key of [...this.bytes.keys()]) if (key === filePath || key.startsWith(filePath + path.sep)) this.bytes.delete(key);
    this.kinds.clear();
  }

  clear(): void {
    this.bytes.clear();
    this.kinds.clear();
  }
}

export interface IndexedGroup {
  name: string;
  range: Range;
}

/** What the index knows of one scenario file on disk without keeping its parse tree. */
export interface IndexedFile {
  path: string;
  kind: 'xosc' | 'mosc';
  groups: IndexedGroup[];
  /** Whether the file holds ScenarioReferences (and so can refer to other files). */
  modular: boolean;
}

export interface OpenDocument {
  uri: string;
  ref: SourceRef;
  document: TextDocument;
}

const SKIPPED_FOLDERS = new Set(['node_modules', '.git', 'dist', 'out', '.vscode-test']);

/** Every `.xosc` and `.mosc` below the folders, skipping build and dependency folders; never throws. */
export async function listScenarioFiles(folders: string[], limit = 100_000): Promise<string[]> {
  const found: string[] = [];
  const pending = [...folders];
  while (pending.length > 0 && found.length < limit) {
    const folder = pending.pop() as string;
    let entries: fs.Dirent[];
    try {
      entries = await fs.promises.readdir(folder, { withFileTypes: true });
    } catch {
      continue;
    }
    for (const entry of entries) {
      const full = path.join(folder, entry.name);
      if (entry.isDirectory()) {
        if (!SKIPPED_FOLDERS.has(entry.name) && !entry.name.startsWith('.')) pending.push(full);
      } else if (entry.isFile() && /\.(xosc|mosc)$/i.test(entry.name)) {
        found.push(full);
      }
    }
  }
  return found.sort();
}

/**
 * The server's view of the workspace: the store (with unsaved editor text as overlays), the open
 * documents, an index of scenario files and one Flattener per generation of changes.
 */
export class Workspace {
  readonly files = new CachingFileSystem();
  readonly documents = new Map<string, OpenDocument>();
  readonly index = new Map<string, IndexedFile>();
  readonly uris: UriResolver;
  folders: string[] = [];
  settings: ServerSettings = DEFAULT_SETTINGS;
  private storeInstance: ScenarioStore;
  private generation = 0;
  private flattenerGeneration = -1;
  private currentFlattener: Flattener | undefined;
  private readonly flattenResults = new Map<string, { generation: number; result: Promise<FlattenResult> }>();

  constructor() {
    this.storeInstance = this.createStore();
    this.uris = new UriResolver(() => this.storeInstance);
  }

  get store(): ScenarioStore {
    return this.storeInstance;
  }

  private createStore(): ScenarioStore {
    const fromEnvironment = splitScenarioPath(process.env.SCENARIO_PATH);
    const fromSettings = this.settings.scenarioPath.map((entry) => path.resolve(this.folders[0] ?? process.cwd(), entry));
    const store = new ScenarioStore({ scenarioPath: [...fromEnvironment, ...fromSettings], root: this.folders[0], host: this.files });
    for (const open of this.documents.values()) store.setOverlay(open.ref, open.document.getText());
    return store;
  }

  configure(folders: string[], settings: ServerSettings): void {
    this.folders = folders.map((folder) => path.resolve(folder));
    this.settings = settings;
    this.storeInstance = this.createStore();
    this.changed();
  }

  /** Marks every analysis stale; the next request flattens again (reading unchanged files from memory). */
  changed(): void {
    this.generation++;
  }

  flattener(): Flattener {
    if (!this.currentFlattener || this.flattenerGeneration !== this.generation) {
      this.currentFlattener = new Flattener(this.storeInstance);
      this.flattenerGeneration = this.generation;
    }
    return this.currentFlattener;
  }

  /** The file read and flattened as the current generation sees it. */
  source(ref: SourceRef): Promise<FlatSource> {
    return this.flattener().source(ref, []);
  }

  /** The file flattened as a main file (with the checks only a main file gets), cached per generation. */
  flatten(ref: SourceRef): Promise<FlattenResult> {
    const id = refId(ref);
    const cached = this.flattenResults.get(id);
    if (cached && cached.generation === this.generation) return cached.result;
    const result = this.flattener().flatten(ref);
    this.flattenResults.set(id, { generation: this.generation, result });
    if (this.flattenResults.size > 200) for (const [key, entry] of this.flattenResults) if (entry.generation !== this.generation) this.flattenResults.delete(key);
    return result;
  }

  open(uri: string, ref: SourceRef, document: TextDocument): void {
    this.uris.remember(uri, ref);
    this.documents.set(refId(ref), { uri, ref, document });
    this.storeInstance.setOverlay(ref, document.getText());
    this.changed();
  }

  update(ref: SourceRef, document: TextDocument): void {
    const open = this.documents.get(refId(ref));
    if (open) open.document = document;
    this.storeInstance.setOverlay(ref, document.getText());
    this.changed();
  }

  close(ref: SourceRef): void {
    const open = this.documents.get(refId(ref));
    this.documents.delete(refId(ref));
    if (open) this.uris.forget(open.uri);
    this.storeInstance.setOverlay(ref, undefined);
    this.changed();
  }

  /** The URI to send for a file: the client's own spelling when the file is open. */
  uriOf(ref: SourceRef): string {
    return this.documents.get(refId(ref))?.uri ?? refToUri(ref);
  }

  /** The text of a file as the editor sees it (unsaved text first); undefined when unreadable. */
  async text(ref: SourceRef): Promise<string | undefined> {
    return this.storeInstance.readText(ref).catch(() => undefined);
  }

  /** A file on disk changed, appeared or vanished. */
  fileChanged(filePath: string): void {
    const resolved = path.resolve(filePath);
    this.files.invalidate(resolved);
    this.storeInstance.invalidate(resolved);
    this.index.delete(resolved);
    this.changed();
  }

  /** Reads one file into the index; files that vanish or cannot be parsed are indexed without groups. */
  async indexFile(filePath: string): Promise<IndexedFile> {
    const kind: IndexedFile['kind'] = filePath.toLowerCase().endsWith('.mosc') ? 'mosc' : 'xosc';
    const entry: IndexedFile = { path: filePath, kind, groups: [], modular: false };
    if (kind === 'xosc') {
      const bytes = await this.files.readFile(filePath);
      if (bytes && bytes.length <= this.settings.maxIndexedFileBytes) {
        const open = this.documents.get(refId(diskRef(filePath)));
        const text = open ? open.document.getText() : decodeUtf8(bytes);
        const model = buildModel(parseXml(text));
        entry.groups = model.groups.map((group: ManeuverGroupInfo) => ({
          name: group.name,
          range: model.document.lines.range(group.element.start, group.element.startTagEnd),
        }));
        entry.modular = model.references.length > 0;
      }
    } else {
      entry.modular = true;
    }
    this.index.set(filePath, entry);
    return entry;
  }

  /** Indexes every scenario file of the workspace folders, reporting progress as a fraction done. */
  async indexAll(progress?: (done: number, total: number) => void): Promise<number> {
    const filePaths = await listScenarioFiles(this.folders);
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
    const known = await listScenarioFiles(this.folders);
    const result: IndexedFile[] = [];
    for (const filePath of known) {
      const entry = this.index.get(filePath) ?? (await this.indexFile(filePath).catch(() => undefined));
      if (entry) result.push(entry);
    }
    return result;
  }

  /** The main files whose references may reach another file: every modular file of the workspace, and the open ones. */
  async referringFiles(): Promise<SourceRef[]> {
    const refs = new Map<string, SourceRef>();
    for (const entry of await this.indexedFiles()) {
      if (entry.kind === 'xosc' && entry.modular) refs.set(entry.path, diskRef(entry.path));
      if (entry.kind === 'mosc') refs.set(entry.path, childRef(diskRef(entry.path), 'main.xosc'));
    }
    for (const open of this.documents.values()) refs.set(refId(open.ref), open.ref);
    return [...refs.values()];
  }
}
