/**
 * Where a scenario's road file (`RoadNetwork/LogicFile`) is: one answer for every reader, so that
 * the bird's-eye view draws the file that Run in esmini loads.
 */
import * as path from 'node:path';
import { CARLA_TOWNS } from '../profiles/scenarioRunner';
import {
  childRef,
  displayRef,
  FileReadError,
  FileSystemHost,
  normalizeEntryName,
  refId,
  ScenarioStore,
  SourceError,
  SourceRef,
} from '../sources';
import { attribute, descendants, XmlAttribute, XmlDocument, XmlElement } from '../xml';
// The model module, not the semantics index: the index runs the checks, whose road rules read road files through this one.
import { Evaluator, semanticModelOf } from './model';

export interface LogicFile {
  /** As the scenario says, `$parameters` and `${...}` evaluated. */
  filepath: string;
  element: XmlElement;
}

/** The document's `RoadNetwork/LogicFile` element and its `filepath` attribute, as written. */
function logicFileElement(document: XmlDocument): { element: XmlElement; written: XmlAttribute } | undefined {
  const network = document.root?.children.find((child) => child.name === 'RoadNetwork');
  const element = network?.children.find((child) => child.name === 'LogicFile');
  const written = element?.attributes.find((attribute) => attribute.name === 'filepath');
  return element && written ? { element, written } : undefined;
}

/** The document's `RoadNetwork/LogicFile` and its filepath as evaluated; undefined when it names none. */
export function logicFileOf(document: XmlDocument, evaluator?: Evaluator): LogicFile | undefined {
  const found = logicFileElement(document);
  if (!found) return undefined;
  const { element, written } = found;
  const filepath = (evaluator ?? new Evaluator(semanticModelOf(document))).textOf(element, written) ?? written.value;
  return filepath.trim() ? { filepath, element } : undefined;
}

/** The folder a scenario's relative file names start from: the file's folder, or for a file inside a package the package's. */
export function scenarioFolderOf(ref: SourceRef): string {
  return path.dirname(ref.disk);
}

/** Road folders (a setting, a request's field) as absolute paths: a relative one starts at `base` (the workspace folder, or the working directory). */
export function roadFolders(roadPath: readonly unknown[] | undefined, base: string): string[] {
  return (roadPath ?? [])
    .filter((folder): folder is string => typeof folder === 'string' && folder.trim() !== '')
    .map((folder) => path.resolve(base, folder));
}

/**
 * The paths a LogicFile's filepath is looked for at, in order: beside the scenario (the path as
 * written, relative to the scenario's folder, then its file name there), then the same in each road
 * folder. The order per folder is esmini's (its `LocateFile`: the path, then the file name).
 */
export function roadFileCandidates(filepath: string, scenarioFolder: string, roadFolderList: readonly string[]): string[] {
  const name = path.basename(filepath.replace(/\\/g, '/'));
  const candidates: string[] = [];
  for (const folder of [scenarioFolder, ...roadFolderList.map((entry) => path.resolve(scenarioFolder, entry))]) {
    candidates.push(path.resolve(folder, filepath), path.resolve(folder, name));
  }
  return [...new Set(candidates)];
}

/** A scenario's road file looked for where a run has esmini look for it (`locateRoadFile`). */
export interface RoadFileLookup {
  /** The LogicFile, its filepath evaluated. */
  logic: LogicFile;
  attribute: XmlAttribute;
  /** The first candidate that is a file, absolute; undefined when none is, or when the scenario's package holds the road (`packaged`). */
  resolved?: string;
  /**
   * The road as an entry of the package that holds the scenario (a self-contained package's road), looked at before the disk as
   * flattening does (flatten/rebase.ts): a flattened output and a run get its copy beside them, the bird's-eye view reads it there.
   */
  packaged?: SourceRef;
  /** The folders looked in, in order: the scenario's, the road folders, the catalog folders. */
  folders: string[];
  /** Every path looked at, in order (`roadFileCandidates`). */
  candidates: string[];
  /** The filepath is the name of a CARLA map (profiles/scenarioRunner.ts CARLA_TOWNS), which ScenarioRunner loads by name. */
  carlaTown: boolean;
  /**
   * When the road was found nowhere: entries of the packages (`.mosc`) the scenario's ScenarioReferences name that hold
   * a file at that path or of that name, which esmini does not look inside for a file outside them.
   */
  heldByReferencedPackages?: HeldRoad[];
  /**
   * When the road was found nowhere: the packages the scenario's ScenarioReferences name that could not be read (not a ZIP
   * archive, unreadable), so that whether they hold it is not known; `reference` is the first ScenarioReference naming each.
   */
  unreadReferencedPackages?: UnreadPackage[];
}

/** A package entry holding the road (RoadFileLookup.heldByReferencedPackages), in the package a ScenarioReference names or one stored in it. */
export interface HeldRoad {
  held: SourceRef;
  /** How many of `held.entries` name the package referenced (0: the package on disk itself); the ones after it, before the file, are packages stored in it. */
  referencedEntries: number;
}

/** A package a ScenarioReference names that could not be read (RoadFileLookup.unreadReferencedPackages). */
export interface UnreadPackage {
  reference: XmlElement;
  /** The package on disk, or the name as written when it could not be resolved. */
  packageFile: string;
  reason: string;
}

/** Whether `error` is a file or package that cannot be read (said on the reference), not a fault of the program (thrown on). */
function isReadFailure(error: unknown): error is Error {
  const errno = error instanceof Error && 'code' in error && typeof error.code === 'string' && /^E[A-Z]+$/.test(error.code);
  return error instanceof SourceError || error instanceof FileReadError || errno;
}

/**
 * The entries of the `.mosc` packages `document`'s ScenarioReferences name (literal names only) that hold `filepath`: at
 * that path from the package's root, else a file of that name anywhere in it.
 */
async function inReferencedPackages(
  store: ScenarioStore,
  ref: SourceRef,
  document: XmlDocument,
  filepath: string,
): Promise<{ held: HeldRoad[]; unread: UnreadPackage[] }> {
  const wanted = normalizeEntryName(filepath.replace(/\\/g, '/'));
  const name = path.basename(filepath.replace(/\\/g, '/'));
  const found: HeldRoad[] = [];
  const unread: UnreadPackage[] = [];
  const references = new Map<string, XmlElement>();
  for (const element of document.root ? descendants(document.root) : []) {
    const fileName = element.name === 'ScenarioReference' ? (attribute(element, 'scenarioFileName')?.value ?? '') : '';
    if (fileName.trim() !== '' && !fileName.includes('$') && !references.has(fileName)) references.set(fileName, element);
  }
  // A package that cannot be read may hold the road: said, never taken for one that holds nothing; any other failure is thrown.
  const failed = (reference: XmlElement, packageFile: string) => (error: unknown) => {
    if (!isReadFailure(error)) throw error;
    unread.push({ reference, packageFile, reason: error.message });
    return undefined;
  };
  for (const [fileName, reference] of references) {
    const resolution = await store.resolve(fileName, ref).catch(failed(reference, fileName));
    if (resolution?.kind !== 'package' || resolution.folder) continue;
    // The package referenced, then the packages stored in it (a few levels down), until one holds the road.
    let level = [resolution.packageRef];
    for (let depth = 0; depth <= NESTED_PACKAGE_DEPTH && level.length > 0; depth++) {
      const inner: SourceRef[] = [];
      let held: SourceRef | undefined;
      for (const packageRef of level) {
        const contents = await store.readPackage(packageRef).catch(failed(reference, displayRef(packageRef, undefined)));
        if (!contents) continue;
        const entries = [...contents.entries.keys()];
        const entry =
          (wanted !== undefined && contents.entries.has(wanted) ? wanted : undefined) ??
          entries.find((candidate) => candidate.slice(candidate.lastIndexOf('/') + 1) === name);
        if (entry !== undefined) {
          held = childRef(packageRef, entry);
          break;
        }
        for (const candidate of entries) if (candidate.toLowerCase().endsWith('.mosc')) inner.push(childRef(packageRef, candidate));
      }
      if (held) {
        if (!found.some((known) => refId(known.held) === refId(held as SourceRef)))
          found.push({ held, referencedEntries: resolution.packageRef.entries.length });
        break;
      }
      level = inner;
    }
  }
  return { held: found, unread };
}

/** How many levels of packages stored inside a referenced package are looked in for a road. */
const NESTED_PACKAGE_DEPTH = 3;

/** The entry of the package holding the file `ref` that `filepath`, written in that file, names; undefined when it names none. */
async function inOwnPackage(store: ScenarioStore, ref: SourceRef, filepath: string): Promise<SourceRef | undefined> {
  if (ref.entries.length === 0 || path.isAbsolute(filepath)) return undefined;
  const entry = ref.entries[ref.entries.length - 1];
  const folder = entry.includes('/') ? entry.slice(0, entry.lastIndexOf('/') + 1) : '';
  const name = normalizeEntryName(`${folder}${filepath.replace(/\\/g, '/')}`);
  if (!name) return undefined;
  const packageRef: SourceRef = { disk: ref.disk, entries: ref.entries.slice(0, -1) };
  const contents = await store.readPackage(packageRef).catch(() => undefined);
  return contents?.entries.has(name) ? childRef(packageRef, name) : undefined;
}

/** The road a lookup found as messages name it: the file, or the package entry (`/w/pkg.mosc/road.xodr`); undefined when none was found. */
export function foundRoadName(road: Pick<RoadFileLookup, 'resolved' | 'packaged'>): string | undefined {
  return road.resolved ?? (road.packaged ? displayRef(road.packaged, undefined) : undefined);
}

/**
 * The bytes of the road a lookup found, read afresh (a road file may change), at most `maxBytes + 1` so that the caller can
 * tell a file too large; undefined when none was found. A file on disk is read through `files` (the bird's-eye view reads
 * the disk, not the store's cache); a package entry through the store. Throws when the file cannot be read.
 */
export async function readFoundRoad(
  store: ScenarioStore,
  road: Pick<RoadFileLookup, 'resolved' | 'packaged'>,
  maxBytes: number,
  files: Pick<FileSystemHost, 'readFile'> = store.host,
): Promise<Uint8Array | undefined> {
  if (road.resolved) return files.readFile(road.resolved, maxBytes + 1);
  return road.packaged ? store.readBytes(road.packaged) : undefined;
}

/**
 * The road file of a scenario, looked for as a run makes esmini 3.6 look for it (CommonMini.cpp `LocateFile`, called by
 * ScenarioEngine.cpp with the scenario's folder): the path and its file name in the scenario's folder, then in each road
 * folder (the store's catalogPath: `--road-path`, the `modular2simple.esmini.roadPath` setting), then in each catalog
 * folder of the scenario, all of which a run hands esmini as `--path` (esmini/run.ts esminiSearchPath). esmini's own
 * `<bin>/../resources/xodr` is not looked in: the esmini this project builds has none. Undefined when the document
 * names no LogicFile, or its filepath names a parameter whose value is not known.
 */
export async function locateRoadFile(
  store: ScenarioStore,
  ref: SourceRef,
  document: XmlDocument,
  evaluator: Evaluator,
  catalogFolders: readonly string[],
  // A run and the bird's-eye view read the disk afresh (nodeFileSystem): road folders outside the workspace are not watched.
  files: Pick<FileSystemHost, 'kind'> = { kind: (filePath) => store.kindOf(filePath) },
): Promise<RoadFileLookup | undefined> {
  const found = logicFileElement(document);
  if (!found) return undefined;
  const filepath = evaluator.textOf(found.element, found.written);
  if (filepath === undefined || !filepath.trim()) return undefined;
  const scenarioFolder = scenarioFolderOf(ref);
  const folders = [...new Set([scenarioFolder, ...store.catalogPath, ...catalogFolders])];
  const candidates = roadFileCandidates(filepath, scenarioFolder, folders.slice(1));
  const packaged = await inOwnPackage(store, ref, filepath);
  let resolved: string | undefined;
  for (const candidate of packaged ? [] : candidates) {
    if ((await files.kind(candidate)) !== 'file') continue;
    resolved = candidate;
    break;
  }
  const { held, unread } = resolved || packaged ? { held: [], unread: [] } : await inReferencedPackages(store, ref, document, filepath);
  return {
    logic: { filepath, element: found.element },
    attribute: found.written,
    resolved,
    ...(packaged ? { packaged } : {}),
    folders,
    candidates,
    carlaTown: CARLA_TOWNS.includes(filepath.trim()),
    ...(held.length > 0 ? { heldByReferencedPackages: held } : {}),
    ...(unread.length > 0 ? { unreadReferencedPackages: unread } : {}),
  };
}
