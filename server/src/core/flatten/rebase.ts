import * as path from 'node:path';
import { Evaluator, semanticModelOf } from '../semantics';
import { ScenarioModel } from '../model';
import { Problem, ZERO_RANGE } from '../problems';
import type { Range } from '../text';
import { coreMemo } from '../memos';
import { ProblemWording } from '../diagnostics';
import {
  catalogControllerFileWording,
  importedControllerFileWording,
  packagedPathOnStandardOutputWording,
  unrebasedPathWording,
} from '../diagnostics/filePath';
import type { FileKind } from '../sources/host';
import { displayRef, normalizeEntryName, ScenarioStore, SourceRef } from '../sources';
import { escapeAttributeValue, parseXml, selfAndDescendants, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import type { TextEdit } from './edits';
import { originOf } from './origin';
import type { FlatSource, FlattenOptions, PackagedFile } from './types';

/**
 * Rebasing the file paths of a written scenario (SPEC 11.6): each path the schema types as a file or a
 * directory is written relative to the folder of the file it came from; an output written elsewhere
 * must name the same file relative to its own folder (or absolutely, on standard output).
 */

/**
 * The elements whose attribute the ASAM schemas (1.0 to 1.3) type as a file path: every element of
 * type `File` (attribute `filepath`) or `Directory` (attribute `path`), by the name of their parent element.
 * test/core/rebase.test.ts checks this table against the compiled schema model.
 */
export const FILE_PATH_ELEMENTS: readonly { parent: string; element: string; attribute: string; kind: 'file' | 'directory' }[] = [
  { parent: 'RoadNetwork', element: 'LogicFile', attribute: 'filepath', kind: 'file' },
  { parent: 'RoadNetwork', element: 'SceneGraphFile', attribute: 'filepath', kind: 'file' },
  { parent: 'ParameterValueDistribution', element: 'ScenarioFile', attribute: 'filepath', kind: 'file' },
  { parent: 'Properties', element: 'File', attribute: 'filepath', kind: 'file' },
  { parent: 'AnimationFile', element: 'File', attribute: 'filepath', kind: 'file' },
  { parent: 'DomeImage', element: 'DomeFile', attribute: 'filepath', kind: 'file' },
  ...['Controller', 'Environment', 'Maneuver', 'MiscObject', 'Pedestrian', 'Route', 'Sensor', 'Trajectory', 'Vehicle'].map((kind) => ({
    parent: `${kind}Catalog`,
    element: 'Directory',
    attribute: 'path',
    kind: 'directory' as const,
  })),
];

const SITE_BY_ELEMENT = new Map(FILE_PATH_ELEMENTS.map((entry) => [`${entry.parent}/${entry.element}`, entry]));
/** The element names of SITE_BY_ELEMENT: most elements are passed over without building a key. */
const SITE_ELEMENT_NAMES = new Set(FILE_PATH_ELEMENTS.map((entry) => entry.element));

/** One attribute of a document that holds a file path. */
export interface FilePathSite {
  element: XmlElement;
  attribute: XmlAttribute;
  kind: 'file' | 'directory';
}

/** Every file path written in a document, in document order. */
export function filePathSites(root: XmlElement | undefined): FilePathSite[] {
  if (!root) return [];
  const sites: FilePathSite[] = [];
  const elements = selfAndDescendants(root);
  for (let i = 0; i < elements.length; i++) {
    const element = elements[i];
    const entry =
      element.parent && SITE_ELEMENT_NAMES.has(element.name) ? SITE_BY_ELEMENT.get(`${element.parent.name}/${element.name}`) : undefined;
    const attribute = entry ? element.attributes.find((candidate) => candidate.name === entry.attribute) : undefined;
    if (entry && attribute) sites.push({ element, attribute, kind: entry.kind });
  }
  return sites;
}

/** Whether `element` is a controller's `Properties/File`, which esmini looks up from the scenario's folder. */
function isControllerFile(element: XmlElement): boolean {
  return element.name === 'File' && element.parent?.name === 'Properties' && element.parent.parent?.name === 'Controller';
}

/** A path of the document that names a file or folder on disk. */
export interface ResolvedPath {
  site: FilePathSite;
  /** The path as the attribute's value resolves (the parameter's value for a `$parameter`). */
  written: string;
  /** The folder it was resolved from. */
  base: string;
  /** The absolute file or folder it names. */
  disk: string;
  kind: 'file' | 'directory';
  /** True when the attribute names a parameter or expression (such a path is never rewritten). */
  viaParameter: boolean;
  /** The text the attribute gets, when it changes. */
  rewritten: string | undefined;
}

/** A path left as written that reaches another file once the output lies elsewhere. */
export interface RebaseFinding {
  site: FilePathSite;
  severity: 'warning';
  message: string;
}

export interface RebaseRequest {
  document: XmlDocument;
  /** The folder an element's paths resolve from (that of the file it was written in); undefined leaves them as written. */
  baseOf: (element: XmlElement) => string | undefined;
  /** The folder the output is written to; undefined writes absolute paths (standard output). */
  outputDirectory: string | undefined;
  kindOf: (diskPath: string) => Promise<FileKind>;
  /** How a resolved path is written instead of relative to the output's folder (a self-contained package's own entries); undefined: the default. */
  place?: (resolved: ResolvedPath) => string | undefined;
}

export interface PathRebase {
  /** Edits of `document.text` (attribute values only): none when nothing needs to change. */
  edits: TextEdit[];
  /** Every path that names a file or folder on disk, rewritten or not. */
  resolved: ResolvedPath[];
  /** Paths that do not resolve from their file's folder (a CARLA town, a file on the simulator's search path): left as written. */
  unresolved: FilePathSite[];
  findings: RebaseFinding[];
}

/** A path as written in an output: forward slashes, a trailing slash kept when the original had one. */
export function written(relativeOrAbsolute: string, like: string): string {
  let text = relativeOrAbsolute.split(path.sep).join('/') || '.';
  if (/[\\/]$/.test(like) && !text.endsWith('/')) text += '/';
  return text;
}

function namesParameter(value: string): boolean {
  return value.trimStart().startsWith('$');
}

/**
 * The edits that make every file path of `request.document` name, from the output's folder, the same
 * file it names from its own file's folder. A path that does not resolve from there is left as written;
 * so is one naming a `$parameter`, which is reported when its value is a relative path that resolves and
 * the output lies elsewhere. Nothing changes for an output written beside the files it came from.
 */
export async function rebasePaths(request: RebaseRequest): Promise<PathRebase> {
  const result: PathRebase = { edits: [], resolved: [], unresolved: [], findings: [] };
  const output = request.outputDirectory === undefined ? undefined : path.resolve(request.outputDirectory);
  let evaluator: Evaluator | undefined;
  for (const site of filePathSites(request.document.root)) {
    const base = request.baseOf(site.element);
    if (base === undefined) continue;
    const viaParameter = namesParameter(site.attribute.value);
    let value = site.attribute.value;
    if (viaParameter) {
      evaluator ??= new Evaluator(semanticModelOf(request.document));
      const evaluated = evaluator.textOf(site.element, site.attribute);
      if (evaluated === undefined) continue;
      value = evaluated;
    }
    if (value.trim() === '') {
      result.unresolved.push(site);
      continue;
    }
    const disk = path.resolve(base, value);
    const kind = await request.kindOf(disk);
    if (kind === undefined) {
      result.unresolved.push(site);
      continue;
    }
    const resolved: ResolvedPath = { site, written: value, base: path.resolve(base), disk, kind, viaParameter, rewritten: undefined };
    result.resolved.push(resolved);
    if (viaParameter) {
      if (!path.isAbsolute(value) && (output === undefined || output !== resolved.base)) {
        result.findings.push({
          site,
          severity: 'warning',
          message:
            `'${site.attribute.value}' gives the relative path '${value}', which names ${disk} from ${resolved.base}; ` +
            `a path that names a parameter is left as written, so ${output === undefined ? 'the output on standard output' : `the output in ${output}`} may reach another file or none`,
        });
      }
      continue;
    }
    const placed = request.place?.(resolved);
    let text: string | undefined;
    if (placed !== undefined) text = placed;
    else if (output === undefined) text = path.isAbsolute(value) ? undefined : written(disk, value);
    else if (!path.isAbsolute(value) && output !== resolved.base) text = written(path.relative(output, disk), value);
    if (text === undefined || text === value) continue;
    resolved.rewritten = text;
    result.edits.push({
      start: site.attribute.valueStart,
      end: site.attribute.valueEnd,
      text: escapeAttributeValue(text, site.attribute.quote),
    });
  }
  return result;
}

/** A CatalogReference, where it was written, to a Controller entry whose File is a relative path (as written and as evaluated). */
interface ControllerFileUse {
  /** The file that wrote the CatalogReference. */
  origin: FlatSource;
  entry: string;
  /** The File's path quoted as messages name it: as written, with the value a parameter gives it. */
  named: string;
  value: string;
  range: Range;
}

/**
 * The controller File a CatalogReference (`origin`, where it was written) uses, when it is a relative path written as it
 * stands or through the entry's parameter (the value the reference assigns, else the entry's default).
 */
function controllerFileUse(origin: { source: FlatSource; element: XmlElement }): ControllerFileUse | undefined {
  const semantics = origin.source.semantics;
  const resolution = semantics?.catalogs.references.find((each) => each.reference.element === origin.element);
  const entry = resolution?.entry;
  if (!semantics || !resolution || entry?.element.name !== 'Controller') return undefined;
  const reference = resolution.reference;
  const file = entry.element.children.find((child) => child.name === 'Properties')?.children.find((child) => child.name === 'File');
  const written = file?.attributes.find((each) => each.name === 'filepath')?.value.trim();
  const parameter = written ? /^\$([A-Za-z_][\w.]*)$/.exec(written)?.[1] : undefined;
  const assignment = reference.assignments.find((each) => each.parameterRef?.value.replace(/^\$/, '') === parameter);
  const value =
    parameter === undefined
      ? written
      : assignment
        ? semantics.evaluator.textOf(assignment.element, assignment.valueAttribute)?.trim()
        : declaredValue(entry.element, parameter);
  if (!written || !value || value.includes('$') || path.isAbsolute(value)) return undefined;
  const at = reference.entryNameAttribute;
  return {
    origin: origin.source,
    entry: entry.name,
    named: value === written ? `'${written}'` : `'${written}' ('${value}')`,
    value,
    range: at ? semantics.model.document.lines.range(at.valueStart, at.valueEnd) : ZERO_RANGE,
  };
}

/**
 * The controller entries the output's CatalogReferences use (the main's own and those of the groups it imports, each found
 * where it was written) whose File is a relative path: esmini looks it up from the folder of the scenario it runs
 * (ScenarioReader.cpp parseOSCObjectController), never the catalog's, and the output written elsewhere keeps the
 * reference, not the entry, so a file the path names from the main's folder (where the output beside the main, and a run,
 * reach it) is warned of at the reference, unless a run hands it (`handed`: esmini/controllerFiles.ts). A file the path
 * names only from the folder of an imported file is the analysis's warning (`importedControllerFileProblems`).
 */
async function catalogControllerFileProblems(
  source: FlatSource,
  model: ScenarioModel,
  originFor: (element: XmlElement) => { source: FlatSource; element: XmlElement },
  outputDirectory: string | undefined,
  store: ScenarioStore,
  handed: boolean,
): Promise<Problem[]> {
  const base = path.resolve(pathBaseOf(source.ref));
  if (!model.document.root || handed || outputDirectory === base) return [];
  const problems: Problem[] = [];
  // A group imported twice is copied twice: its reference is warned of once.
  const seen = new Set<XmlElement>();
  for (const element of selfAndDescendants(model.document.root)) {
    if (element.name !== 'CatalogReference') continue;
    const origin = originFor(element);
    if (seen.has(origin.element)) continue;
    seen.add(origin.element);
    const use = controllerFileUse(origin);
    if (!use) continue;
    const disk = path.resolve(base, use.value);
    if ((await store.kindOf(disk)) !== 'file') continue;
    // A group imported from another file: its reference is where to change it, the main's folder where the path is read from.
    const from = origin.source === source ? undefined : displayRef(source.ref, undefined);
    problems.push({
      source: use.origin.ref,
      range: use.range,
      ...catalogControllerFileWording(use.entry, use.named, disk, outputDirectory, from),
    });
  }
  return problems;
}

/** The controller File uses of the CatalogReferences inside an imported group (its copies of nested imports found where they were written). */
const controllerFileUses = coreMemo<XmlElement, ControllerFileUse[]>('controllerFileUses');

function controllerFileUsesIn(source: FlatSource, group: XmlElement): ControllerFileUse[] {
  let uses = controllerFileUses.get(group);
  if (!uses) {
    uses = [];
    for (const element of selfAndDescendants(group)) {
      if (element.name !== 'CatalogReference') continue;
      const use = controllerFileUse(originOf(source, element));
      if (use) uses.push(use);
    }
    controllerFileUses.set(group, uses);
  }
  return uses;
}

/**
 * A catalog controller entry's relative File used from a group that `source` (the main) imports from a file in another
 * folder or package: esmini reads it from the working folder, then from the main's folder, so a File that lies only beside
 * the imported file (or inside its package) is never found and the flattened scenario runs without it, whatever the output.
 * Warned of at the group's CatalogReference, by every analysis (the editor's too), without rendering the main. `lookedUp`:
 * each path whose existence decides a warning, for the editor to watch. Existence is asked of the store, which remembers
 * kinds until a file event (`fileBytes`).
 */
export async function importedControllerFileProblems(
  source: FlatSource,
  store: ScenarioStore,
): Promise<{ problems: Problem[]; lookedUp: string[] }> {
  const base = path.resolve(pathBaseOf(source.ref));
  const problems: Problem[] = [];
  const lookedUp: string[] = [];
  // A group imported twice is looked at once, and so is a reference copied into two groups.
  const seen = new Set<ControllerFileUse>();
  const groups = new Set<XmlElement>();
  for (const link of source.links) {
    if (!link.source) continue;
    for (const group of link.groups) {
      if (!group.target || groups.has(group.target.element)) continue;
      groups.add(group.target.element);
      for (const use of controllerFileUsesIn(link.source, group.target.element)) {
        if (seen.has(use) || use.origin === source) continue;
        seen.add(use);
        const disk = path.resolve(base, use.value);
        lookedUp.push(disk);
        if (use.origin.ref.entries.length === 0) lookedUp.push(path.resolve(pathBaseOf(use.origin.ref), use.value));
        if ((await store.kindOf(disk)) === 'file') continue;
        const beside = await besideImportingFile(store, use.origin.ref, use.value);
        if (beside === undefined) continue;
        problems.push({
          source: use.origin.ref,
          range: use.range,
          ...importedControllerFileWording(use.entry, use.named, displayRef(source.ref, undefined), disk, beside),
        });
      }
    }
  }
  return { problems, lookedUp: [...new Set(lookedUp)] };
}

/** The file a relative path names from the folder of `ref` (inside its package, for a packaged file), when one lies there. */
async function besideImportingFile(store: ScenarioStore, ref: SourceRef, value: string): Promise<string | undefined> {
  if (ref.entries.length > 0) {
    const packaged = await packagedEntries(store, ref, value);
    const own = packaged?.files.find(([name]) => name === packaged.name);
    return own ? displayRef({ disk: ref.disk, entries: [...ref.entries.slice(0, -1), own[0]] }, undefined) : undefined;
  }
  const file = path.resolve(pathBaseOf(ref), value);
  return (await store.kindOf(file)) === 'file' ? file : undefined;
}

/** The value an element's own ParameterDeclaration of `name` gives, as written. */
function declaredValue(element: XmlElement, name: string): string | undefined {
  const declarations = element.children.find((child) => child.name === 'ParameterDeclarations');
  const declaration = declarations?.children.find(
    (child) => child.name === 'ParameterDeclaration' && child.attributes.some((each) => each.name === 'name' && each.value === name),
  );
  return declaration?.attributes.find((each) => each.name === 'value')?.value.trim();
}

/** The folder beside an output (`flat.files` for `flat.xosc`) that the copies of the package files it names are written to. */
export function packagedFilesFolder(outputPath: string): string {
  return `${path.basename(outputPath).replace(/\.xosc$/i, '')}.files`;
}

/** The folder the relative paths of a file resolve from: its own folder, or for a packaged file the package's folder on disk. */
export function pathBaseOf(ref: SourceRef): string {
  return path.dirname(ref.disk);
}

/** The package files a path written in a packaged file names: the entry itself, or a folder's direct files. */
async function packagedEntries(
  store: ScenarioStore,
  ref: SourceRef,
  value: string,
): Promise<{ name: string; files: [string, Uint8Array][] } | undefined> {
  if (ref.entries.length === 0 || path.isAbsolute(value) || namesParameter(value)) return undefined;
  const packageRef: SourceRef = { disk: ref.disk, entries: ref.entries.slice(0, -1) };
  const entry = ref.entries[ref.entries.length - 1];
  const folder = entry.includes('/') ? entry.slice(0, entry.lastIndexOf('/')) : '';
  const joined = folder ? `${folder}/${value}` : value;
  // `.` at the package's root names the root itself (''), which normalizes to no name at all.
  const name = normalizeEntryName(joined) ?? (/^[./]+$/.test(joined) && !joined.includes('..') ? '' : undefined);
  if (name === undefined) return undefined;
  const contents = await store.readPackage(packageRef).catch(() => undefined);
  if (!contents) return undefined;
  const own = name ? contents.entries.get(name) : undefined;
  if (own) return { name, files: [[name, own]] };
  const prefix = name ? `${name}/` : '';
  const files = [...contents.entries].filter(
    ([candidate]) => candidate.startsWith(prefix) && !candidate.slice(prefix.length).includes('/'),
  );
  return files.length > 0 ? { name, files } : undefined;
}

/** The copies of `packaged` that a `$parameter` path (`namedBy`, as written) names at `target`: the file, or the folder whose direct files they are. */
function placedCopies(packaged: { name: string; files: [string, Uint8Array][] }, target: string, namedBy: string): PackagedFile[] {
  return packaged.files.map(([entry, bytes]) => ({
    path: entry === packaged.name ? target : path.join(target, entry.slice(entry.lastIndexOf('/') + 1)),
    bytes,
    namedBy,
  }));
}

/**
 * The package files that the `$parameter` paths of a plain scenario `text` name through their values, looked up in the
 * package of `main` (the packaged file the text was flattened from), each placed where its value names it from
 * `outputDirectory`. For a concrete scenario of a packaged ScenarioFile, whose values (a varied road) may differ from
 * those its flattening carried.
 */
export async function parameterPackagedFiles(
  text: string,
  main: SourceRef,
  outputDirectory: string,
  store: ScenarioStore,
): Promise<PackagedFile[]> {
  if (main.entries.length === 0) return [];
  const document = parseXml(text);
  let evaluator: Evaluator | undefined;
  const files: PackagedFile[] = [];
  for (const site of filePathSites(document.root)) {
    if (!namesParameter(site.attribute.value)) continue;
    evaluator ??= new Evaluator(semanticModelOf(document));
    const value = evaluator.textOf(site.element, site.attribute);
    const packaged = value === undefined ? undefined : await packagedEntries(store, main, value);
    if (packaged) files.push(...placedCopies(packaged, path.resolve(outputDirectory, value as string), site.attribute.value));
  }
  return files;
}

/**
 * The rebasing of a flattened output (`model`: the rendered text of `source`): each element's paths
 * resolve from the folder of the file it was written in (carried catalog locations are written
 * relative to the main file's folder), and are rewritten for the output at `outputPath` (absolute when
 * undefined: standard output). A path of a packaged file that names a file of its package (a
 * self-contained package's road or catalog) names its copy in `<output name>.files/`, returned in
 * `files` for the writer. Findings come back as problems at the place each path was written.
 */
export async function rebaseFlattened(
  source: FlatSource,
  model: ScenarioModel,
  outputPath: string | undefined,
  store: ScenarioStore,
  handed: Pick<FlattenOptions, 'roadHanded' | 'controllerFilesHanded'> = {},
): Promise<{ edits: TextEdit[]; resolved: ResolvedPath[]; problems: Problem[]; files: PackagedFile[] }> {
  const flattenedHere = model === source.model;
  const originFor = (element: XmlElement) => (flattenedHere ? originOf(source, element) : { source, element });
  const problemAtOrigin = (element: XmlElement, attributeName: string, wording: ProblemWording<'file-path'>): Problem => {
    const origin = originFor(element);
    const document = (origin.source.original ?? origin.source.model)?.document;
    const written = origin.element.attributes.find((candidate) => candidate.name === attributeName);
    return {
      source: origin.source.ref,
      range: document && written ? document.lines.range(written.valueStart, written.valueEnd) : ZERO_RANGE,
      ...wording,
    };
  };
  const outputDirectory = outputPath === undefined ? undefined : path.dirname(path.resolve(outputPath));
  const problems: Problem[] = [];
  const edits: TextEdit[] = [];
  const files = new Map<string, Uint8Array>();
  const namedBy = new Map<string, string>();
  // Paths into the package a file was read from: its copies beside the output.
  const inPackage = new Set<XmlElement>();
  let evaluator: Evaluator | undefined;
  for (const site of filePathSites(model.document.root)) {
    const ref = originFor(site.element).source.ref;
    let packaged = await packagedEntries(store, ref, site.attribute.value);
    // A `$parameter` path is left as written (SPEC 11.6): the package file its value names is copied where that value names it from the output.
    let parameterValue: string | undefined;
    if (!packaged && ref.entries.length > 0 && namesParameter(site.attribute.value)) {
      evaluator ??= new Evaluator(semanticModelOf(model.document));
      parameterValue = evaluator.textOf(site.element, site.attribute);
      packaged = parameterValue === undefined ? undefined : await packagedEntries(store, ref, parameterValue);
    }
    if (!packaged) continue;
    inPackage.add(site.element);
    if (outputPath === undefined || outputDirectory === undefined) {
      problems.push(
        problemAtOrigin(site.element, site.attribute.name, packagedPathOnStandardOutputWording(site.attribute.value, packaged.name)),
      );
      continue;
    }
    if (parameterValue !== undefined) {
      for (const copy of placedCopies(packaged, path.resolve(outputDirectory, parameterValue), site.attribute.value)) {
        namedBy.set(copy.path, site.attribute.value);
        files.set(copy.path, copy.bytes);
      }
      continue;
    }
    const folder = packagedFilesFolder(outputPath);
    for (const [entry, bytes] of packaged.files) files.set(path.join(outputDirectory, folder, ...entry.split('/')), bytes);
    const text = written(packaged.name ? `${folder}/${packaged.name}` : folder, site.attribute.value);
    if (text !== site.attribute.value)
      edits.push({
        start: site.attribute.valueStart,
        end: site.attribute.valueEnd,
        text: escapeAttributeValue(text, site.attribute.quote),
      });
  }
  const rebase = await rebasePaths({
    document: model.document,
    baseOf: (element) => (inPackage.has(element) ? undefined : pathBaseOf(originFor(element).source.ref)),
    outputDirectory,
    kindOf: (diskPath) => store.kindOf(diskPath),
  });
  for (const finding of rebase.findings) {
    if (handed.roadHanded && finding.site.element.name === 'LogicFile') continue;
    if (
      handed.controllerFilesHanded &&
      isControllerFile(finding.site.element) &&
      pathBaseOf(originFor(finding.site.element).source.ref) === pathBaseOf(source.ref)
    )
      continue;
    problems.push(problemAtOrigin(finding.site.element, finding.site.attribute.name, unrebasedPathWording(finding.message)));
  }
  problems.push(
    ...(await catalogControllerFileProblems(source, model, originFor, outputDirectory, store, handed.controllerFilesHanded === true)),
  );
  return {
    edits: [...edits, ...rebase.edits],
    resolved: rebase.resolved,
    problems,
    files: [...files].map(([filePath, bytes]) => {
      const by = namedBy.get(filePath);
      return by === undefined ? { path: filePath, bytes } : { path: filePath, bytes, namedBy: by };
    }),
  };
}
