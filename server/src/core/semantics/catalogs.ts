import * as path from 'node:path';
import { baseName, childRef, diskRef, normalizeEntryName, refId, ScenarioStore, SourceRef } from '../sources';
import { attribute, XmlElement } from '../xml';
import {
  Assignments,
  buildSemanticModel,
  referencedName,
  CatalogLocationInfo,
  CatalogReferenceInfo,
  Evaluator,
  SemanticModel,
} from './model';
import { CORE_MEMOS, coreMemo } from '../memos';

/**
 * Catalogs (ASAM OpenSCENARIO 1.x section 9.4): a `CatalogLocations` `Directory path` is relative to
 * the file that names it; every `.xosc` in that directory whose root holds a `Catalog` of a name is
 * that catalog. Where the directory does not exist beside the file, the SCENARIO_PATH directories (then the
 * store's catalogPath: the road folders a run also hands esmini) are searched as esmini searches its `--path`
 * folders (esmini 3.6 `ScenarioReader::LoadCatalog`): `D/path`, `D` itself, and `D/<last folder of path>`.
 * A run hands esmini the same folders (esmini/run.ts esminiSearchPath), so what is found here esmini finds. Of several
 * files holding a catalog of one name, the catalog is the one esmini loads (`loadedFirst`): entries are looked up there.
 */

export interface CatalogFile {
  ref: SourceRef;
  name: string;
  model: SemanticModel;
  catalog: XmlElement;
  entries: CatalogEntry[];
}

export interface CatalogEntry {
  name: string;
  element: XmlElement;
  file: CatalogFile;
}

/** A directory where catalogs are looked up: on disk, or a folder inside a package. */
export interface CatalogDirectory {
  /** The package holding it, or undefined on disk. */
  packageRef: SourceRef | undefined;
  /** A disk path, or the folder's entry prefix inside the package ('' for its root). */
  directory: string;
  /** How it was found: beside the file (`file`) or through SCENARIO_PATH. */
  via: 'file' | 'scenarioPath';
}

export interface LocationResolution {
  location: CatalogLocationInfo;
  /** The path as evaluated (it may be a `$parameter`). */
  path: string | undefined;
  directories: CatalogDirectory[];
  /**
   * When the directory does not exist beside a file on disk: the first folder of its path that does not (`written`, the
   * path as far as that folder; `folder`, absolute), where several directories of one missing folder are one problem.
   */
  missingFolder?: { written: string; folder: string };
}

export interface CatalogReferenceResolution {
  reference: CatalogReferenceInfo;
  catalogName: string | undefined;
  entryName: string | undefined;
  /**
   * Every catalog file of that name found through the file's locations, the one esmini loads first (`loadedFirst`):
   * the entry is looked up in that one alone.
   */
  catalogs: CatalogFile[];
  /** The entry, in `catalogs[0]`; undefined when that catalog has none of the name. */
  entry: CatalogEntry | undefined;
  /** When `entry` is undefined: the entry of that name in another catalog file of the name, which esmini never loads. */
  shadowedEntry?: CatalogEntry;
  /** Whether any location of the file could be searched; without one, an unknown name is not an error. */
  searched: boolean;
  /**
   * Set when no Catalog has the name but a file `NAME.xosc` holds a Catalog of another name: esmini
   * takes that file (it looks catalogs up by file name), the standard does not.
   */
  foundByFileName: boolean;
  /**
   * Set when the catalog is a Catalog of the name in a file of another name: esmini looks a catalog up as the file
   * `NAME.xosc` alone (ScenarioReader.cpp LoadCatalog) and reads `esminiReads`, a Catalog of another name, or finds none.
   */
  fileNameMismatch?: { esminiReads: CatalogFile | undefined };
}

/** The catalogs a document reaches, resolved. */
export interface CatalogResolution {
  locations: LocationResolution[];
  references: CatalogReferenceResolution[];
  /** Every catalog file read, for dependencies. */
  files: SourceRef[];
}

/**
 * Catalog files modelled so far, per store (a workspace's, a CLI run's), by file and text: an editor makes
 * a loader per edit, and the catalogs it reaches rarely change between edits. Bounded; the oldest entry goes first.
 */
const modelledByStore = coreMemo<ScenarioStore, Map<string, { text: string; file: CatalogFile | undefined }>>('catalogFiles');
const MODELLED_LIMIT = CORE_MEMOS.catalogFiles.bound.entries;

/** Reads catalog files once per instance (one instance per analysis generation). */
export class CatalogLoader {
  private readonly files = new Map<string, Promise<CatalogFile | undefined>>();
  private readonly listings = new Map<string, Promise<string[]>>();

  constructor(readonly store: ScenarioStore) {}

  /** The directories a `Directory path` written in `from` stands for, those that exist, in search order. */
  async directories(from: SourceRef, written: string): Promise<CatalogDirectory[]> {
    const found: CatalogDirectory[] = [];
    // An empty path is relative to the file like any other: its own folder, as `.` is (esmini 3.6 ignores the entry, ScenarioReader.cpp RegisterCatalogDirectory).
    const pathText = written.trim().replace(/\\/g, '/') || '.';
    if (from.entries.length > 0) {
      const packageRef: SourceRef = { disk: from.disk, entries: from.entries.slice(0, -1) };
      const entry = from.entries[from.entries.length - 1];
      const folder = entry.includes('/') ? entry.slice(0, entry.lastIndexOf('/')) : '';
      const written = folder ? `${folder}/${pathText}` : pathText;
      // `.` (or `./`) at the package's root names the root itself, which normalizes to no name at all.
      const joined = normalizeEntryName(written) ?? (/^[./]+$/.test(written) && !written.includes('..') ? '' : undefined);
      if (joined !== undefined && (await this.listing({ packageRef, directory: joined, via: 'file' })).length > 0)
        found.push({ packageRef, directory: joined, via: 'file' });
      // A package's paths to files outside it are written relative to the package's folder (SPEC 11.6).
      const beside = path.resolve(path.dirname(from.disk), pathText);
      if (found.length === 0 && (await this.store.kindOf(beside)) === 'directory')
        found.push({ packageRef: undefined, directory: beside, via: 'file' });
    } else {
      const candidate = path.resolve(path.dirname(from.disk), pathText);
      if ((await this.store.kindOf(candidate)) === 'directory') found.push({ packageRef: undefined, directory: candidate, via: 'file' });
    }
    if (found.length > 0) return found;
    for (const base of new Set([...this.store.scenarioPathFor(from), ...this.store.catalogPath])) {
      for (const candidate of [path.resolve(base, pathText), base, path.join(base, path.basename(pathText))]) {
        if (found.some((known) => known.directory === candidate)) continue;
        if ((await this.store.kindOf(candidate)) === 'directory')
          found.push({ packageRef: undefined, directory: candidate, via: 'scenarioPath' });
      }
    }
    return found;
  }

  /** The first folder of `written` (a path from a file on disk) that does not exist, and the path as far as it. */
  private async missingFolder(from: SourceRef, written: string): Promise<{ written: string; folder: string } | undefined> {
    const segments = (written.trim().replace(/\\/g, '/') || '.').split('/');
    let folder = path.isAbsolute(written.trim()) ? path.parse(path.resolve(written.trim())).root : path.dirname(from.disk);
    for (let index = 0; index < segments.length; index++) {
      if (segments[index] === '' || segments[index] === '.') continue;
      folder = path.resolve(folder, segments[index]);
      if ((await this.store.kindOf(folder)) !== 'directory') return { written: segments.slice(0, index + 1).join('/'), folder };
    }
    return undefined;
  }

  /** The `.xosc` files of a directory (refs), sorted by name. */
  private listing(directory: CatalogDirectory): Promise<string[]> {
    const key = `${directory.packageRef ? refId(directory.packageRef) : ''}|${directory.directory}`;
    let pending = this.listings.get(key);
    if (!pending) {
      pending = (async () => {
        if (directory.packageRef) {
          const contents = await this.store.readPackage(directory.packageRef).catch(() => undefined);
          if (!contents) return [];
          const prefix = directory.directory ? `${directory.directory}/` : '';
          return [...contents.entries.keys()]
            .filter((name) => name.startsWith(prefix) && !name.slice(prefix.length).includes('/') && name.toLowerCase().endsWith('.xosc'))
            .sort();
        }
        const names = (await this.store.host.listDirectory?.(directory.directory)) ?? [];
        return names
          .filter((name) => name.toLowerCase().endsWith('.xosc'))
          .sort()
          .map((name) => path.join(directory.directory, name));
      })();
      this.listings.set(key, pending);
    }
    return pending;
  }

  private refIn(directory: CatalogDirectory, name: string): SourceRef {
    return directory.packageRef ? childRef(directory.packageRef, name) : diskRef(name);
  }

  /** A catalog file, read and modelled once; undefined when unreadable or not a catalog. */
  file(ref: SourceRef): Promise<CatalogFile | undefined> {
    const id = refId(ref);
    let pending = this.files.get(id);
    if (!pending) {
      pending = (async () => {
        const text = await this.store.readText(ref).catch(() => undefined);
        if (text === undefined || !/<Catalog[\s>]/.test(text)) return undefined;
        let modelled = modelledByStore.get(this.store);
        if (!modelled) modelledByStore.set(this.store, (modelled = new Map()));
        const known = modelled.get(id);
        if (known && known.text === text) return known.file;
        const model = buildSemanticModel(this.store.parse(ref, text));
        const catalog = model.catalog;
        let file: CatalogFile | undefined;
        if (catalog) {
          file = { ref, name: attribute(catalog, 'name')?.value.trim() ?? '', model, catalog, entries: [] };
          for (const child of catalog.children) {
            const name = attribute(child, 'name')?.value.trim();
            if (name !== undefined) file.entries.push({ name, element: child, file });
          }
        }
        modelled.delete(id);
        modelled.set(id, { text, file });
        if (modelled.size > MODELLED_LIMIT) modelled.delete(modelled.keys().next().value as string);
        return file;
      })();
      this.files.set(id, pending);
    }
    return pending;
  }

  /** The catalogs named `name` in a directory: `name.xosc` first (as esmini looks), then every other file. */
  async catalogsIn(directory: CatalogDirectory, name: string): Promise<CatalogFile[]> {
    const listing = await this.listing(directory);
    const preferred = listing.filter((entry) => path.basename(entry) === `${name}.xosc`);
    const ordered = [...preferred, ...listing.filter((entry) => !preferred.includes(entry))];
    const result: CatalogFile[] = [];
    for (const entry of ordered) {
      const file = await this.file(this.refIn(directory, entry));
      if (file && file.name === name) result.push(file);
    }
    return result;
  }

  /** The first catalog file `name.xosc` of the directories, whatever its Catalog is named: the one esmini reads as `name`. */
  private async fileNamed(directories: readonly CatalogDirectory[], name: string): Promise<CatalogFile | undefined> {
    for (const directory of directories) {
      const named = (await this.listing(directory)).find((entry) => path.basename(entry) === `${name}.xosc`);
      const file = named ? await this.file(this.refIn(directory, named)) : undefined;
      if (file) return file;
    }
    return undefined;
  }

  /** Every catalog file in a directory (for completion of catalog names). */
  async allCatalogsIn(directory: CatalogDirectory): Promise<CatalogFile[]> {
    const files = await Promise.all((await this.listing(directory)).map((entry) => this.file(this.refIn(directory, entry))));
    return files.filter((file): file is CatalogFile => file !== undefined);
  }

  /** Resolves every location and CatalogReference of a document. */
  async resolve(ref: SourceRef, model: SemanticModel, evaluator = new Evaluator(model)): Promise<CatalogResolution> {
    const locations: LocationResolution[] = [];
    for (const location of model.catalogLocations) {
      const written = evaluator.textOf(location.directory, location.pathAttribute);
      const directories = written === undefined ? [] : await this.directories(ref, written);
      const missingFolder =
        written !== undefined && ref.entries.length === 0 && !directories.some((directory) => directory.via === 'file')
          ? await this.missingFolder(ref, written)
          : undefined;
      locations.push({ location, path: written, directories, ...(missingFolder ? { missingFolder } : {}) });
    }
    const directories = locations.flatMap((location) => location.directories);
    const references: CatalogReferenceResolution[] = [];
    const files = new Map<string, SourceRef>();
    // One file per catalog name, as esmini keeps the first it loads (Catalogs.hpp FindCatalogByName).
    const loadedByName = new Map<string, CatalogFile>();
    for (const reference of model.catalogReferences) {
      const catalogName = evaluator.textOf(reference.element, reference.catalogNameAttribute)?.trim();
      const entryName = evaluator.textOf(reference.element, reference.entryNameAttribute)?.trim();
      const found: FoundCatalog[] = [];
      if (catalogName) {
        for (const directory of directories) {
          for (const file of await this.catalogsIn(directory, catalogName)) {
            if (!found.some((known) => refId(known.file.ref) === refId(file.ref))) found.push({ file, via: directory.via });
          }
        }
      }
      const catalogs = loadedFirst(found, catalogName ?? '', entryName, loadedByName);
      let foundByFileName = false;
      let fileNameMismatch: CatalogReferenceResolution['fileNameMismatch'];
      if (catalogName && catalogs.length === 0) {
        const file = await this.fileNamed(directories, catalogName);
        if (file) {
          catalogs.push(file);
          foundByFileName = true;
        }
      } else if (catalogName && baseName(catalogs[0].ref) !== `${catalogName}.xosc`) {
        fileNameMismatch = { esminiReads: await this.fileNamed(directories, catalogName) };
      }
      for (const file of catalogs) files.set(refId(file.ref), file.ref);
      const entryNamed = (file: CatalogFile | undefined) => file?.entries.find((candidate) => candidate.name === entryName);
      const entry = entryName === undefined ? undefined : entryNamed(catalogs[0]);
      const shadowedEntry =
        entryName === undefined || entry
          ? undefined
          : catalogs
              .slice(1)
              .map(entryNamed)
              .find((each) => each);
      references.push({
        reference,
        catalogName,
        entryName,
        catalogs,
        entry,
        ...(shadowedEntry ? { shadowedEntry } : {}),
        searched: directories.length > 0,
        foundByFileName,
        ...(fileNameMismatch ? { fileNameMismatch } : {}),
      });
    }
    return { locations, references, files: [...files.values()] };
  }
}

/** A catalog file of the name a reference asks for, and how the directory it lies in was found. */
interface FoundCatalog {
  file: CatalogFile;
  via: CatalogDirectory['via'];
}

/**
 * The catalog files of a name, the one esmini 3.6 loads first: the entries of every reference to the name are looked up
 * in it alone. esmini looks a catalog up by file name only, `NAME.xosc`, in its `--path` folders and then in each
 * CatalogLocations directory in the order the file writes them, whatever their kind (ScenarioReader.cpp `LoadCatalog`,
 * CommonMini.cpp `LocateFile`); it loads the first it finds, keeps it as the catalog of that name (Catalogs.hpp
 * `FindCatalogByName`) and looks every entry up in it (`FindCatalogEntry`), never in another file. So:
 * - beside the file (`via: 'file'`), the first `NAME.xosc` of its directories in the file's order: esmini searches them
 *   itself, and a run hands them in that order;
 * - else, among folders found through SCENARIO_PATH or the road folders, which esmini searches only as the `--path`
 *   folders a run hands it, the first `NAME.xosc` holding the entry the first reference to the name asks for: a run
 *   hands that folder first (esmini/run.ts resolvedCatalogFolders), so it is the one esmini loads;
 * - a catalog of the name in a file of another name, which esmini never finds, only where no `NAME.xosc` holds one (the
 *   standard finds catalogs by their name).
 * `loadedByName` keeps the choice for the document's later references to the name.
 */
function loadedFirst(
  found: FoundCatalog[],
  name: string,
  entryName: string | undefined,
  loadedByName: Map<string, CatalogFile>,
): CatalogFile[] {
  const files = found.map((each) => each.file);
  const byFileName = found.filter((each) => baseName(each.file.ref) === `${name}.xosc`);
  const chosen =
    loadedByName.get(name) ??
    byFileName.find((each) => each.via === 'file')?.file ??
    byFileName.find((each) => each.file.entries.some((entry) => entry.name === entryName))?.file ??
    byFileName[0]?.file;
  if (!chosen) return files;
  loadedByName.set(name, chosen);
  return [chosen, ...files.filter((file) => file !== chosen)];
}

/** The values a CatalogReference's assignments give to its entry's parameters, evaluated in the referencing file. */
export function assignmentsOf(reference: CatalogReferenceInfo, evaluator: Evaluator): Assignments {
  const result: Assignments = new Map();
  for (const assignment of reference.assignments) {
    const name = assignment.parameterRef ? referencedName(assignment.parameterRef).name : undefined;
    if (!name || !assignment.valueAttribute) continue;
    const value = evaluator.attributeValue(assignment.element, assignment.valueAttribute);
    result.set(name, { value: value.ok ? { value: value.value, type: value.type } : undefined, assignment });
  }
  return result;
}
