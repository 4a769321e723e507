import * as path from 'node:path';
import JSZip from 'jszip';
import { rebasePaths, ResolvedPath } from './flatten/rebase';
import { ProblemWording } from './diagnostics';
import { badPackageWording } from './diagnostics/badPackage';
import { reachesOutsidePackageWording } from './diagnostics/filePath';
import {
  duplicateInputWording,
  entryClashWording,
  invalidReferenceWording,
  mainCountWording,
  notPackableWording,
  outsidePackageWording,
} from './diagnostics/invalidReference';
import { ioWording, notUnpackedPackageWording, packFolderWording } from './diagnostics/io';
import { xmlWording } from './diagnostics/xml';
import { packageCycleWording } from './diagnostics/cycle';
import { leftOutOfPackageWording, missingFileWording } from './diagnostics/missingFile';
import { fallbackPackageName, xoscFallbackWording } from './diagnostics/xoscFallback';
import { applyEdits } from './flatten/edits';
import { declareUtf8 } from './encoding';
import { buildModel } from './model';
import { Problem, ProblemCode, ZERO_RANGE } from './problems';
import { decodeScenario } from './encoding';
import {
  DEFAULT_LIMITS,
  diskRef,
  displayRef,
  Limits,
  nodeFileSystem,
  normalizeEntryName,
  refId,
  ScenarioStore,
  SourceRef,
} from './sources';
import { isWellFormed, parseXml } from './xml';

export interface PackResult {
  /** The archive; undefined when an error prevents a complete package. */
  bytes: Uint8Array | undefined;
  /** Entry names in the order they were added; nested packages as `inner.mosc`. */
  entries: string[];
  problems: Problem[];
  /** Every file read or resolved to while packing: an output may be none of them. */
  inputs: SourceRef[];
}

export interface PackOptions {
  /** Where the package will be written: the file paths of its scenarios are rebased onto its folder (SPEC 11.6); the current folder by default. */
  outputPath?: string;
  /** Store the road networks, catalogs and other files the scenarios name inside the package, with package-relative paths. */
  selfContained?: boolean;
  /** Messages show files relative to it (the working directory, a workspace folder); whole without it. A folder's pack takes its store's. */
  workingDirectory?: string;
}

export interface PackFolderOptions extends PackOptions {
  /** Also store files found through SCENARIO_PATH (by default they stay outside, found there when flattening). */
  includeScenarioPath?: boolean;
}

/** What one package (an outer one or a nested one) is being built with. */
interface PackPlace {
  zip: JSZip;
  entries: string[];
  /** Folder of the package's files on disk (an unpacked folder), when there is one: files below it keep their layout. */
  folder: string | undefined;
  /** Files carried into the package (self-contained): disk path to entry name. */
  carried: Map<string, string>;
  options: PackOptions;
  problems: Problem[];
}

function posixRelative(from: string, to: string): string {
  return path.posix.relative(from, to) || '.';
}

/** The entry name a carried file gets: its place below the package's folder ('' for that folder itself), else `files/` and its name (told apart when taken). */
function carriedEntryName(place: PackPlace, disk: string): string {
  const below = place.folder ? path.relative(place.folder, disk) : '..';
  const taken = new Set([...place.entries, ...place.carried.values()]);
  if (!below.startsWith('..') && !path.isAbsolute(below)) return below.split(path.sep).join('/');
  const base = path.basename(disk);
  let name = `files/${base}`;
  for (let index = 2; taken.has(name) || [...taken].some((known) => known.startsWith(`${name}/`)); index++) name = `files/${index}/${base}`;
  return name;
}

/** Stores a file or a folder's files (not its subfolders) in the package once, as `name` unless carried before; the entry name it has there. */
async function carryIntoPackage(
  place: PackPlace,
  resolved: ResolvedPath,
  name = carriedEntryName(place, resolved.disk),
): Promise<string | undefined> {
  const known = place.carried.get(resolved.disk);
  if (known !== undefined) return known;
  const files: { entry: string; disk: string }[] = [];
  if (resolved.kind === 'file') files.push({ entry: name, disk: resolved.disk });
  else {
    const listed = (await nodeFileSystem.listDirectory?.(resolved.disk)) ?? [];
    for (const child of [...listed].sort()) {
      const disk = path.join(resolved.disk, child);
      if ((await nodeFileSystem.kind(disk)) === 'file') files.push({ entry: name ? `${name}/${child}` : child, disk });
    }
  }
  place.carried.set(resolved.disk, name);
  for (const file of files) {
    if (place.entries.includes(file.entry)) continue;
    try {
      const bytes = await nodeFileSystem.readFile(file.disk, DEFAULT_LIMITS.maxEntryBytes);
      if (!bytes) continue;
      place.zip.file(file.entry, bytes, { date: ENTRY_DATE, createFolders: false });
      place.entries.push(file.entry);
    } catch (error) {
      place.problems.push(fileProblem(diskRef(file.disk), ioWording((error as Error).message)));
    }
  }
  return name;
}

/**
 * The bytes a scenario is stored with: its file paths rebased onto the package's folder, or (self-contained)
 * onto the files carried into the package; unchanged when no path needs it. Warns at each path that
 * reaches outside the package.
 */
async function rebasedForPackage(
  place: PackPlace,
  ref: SourceRef,
  bytes: Uint8Array,
  text: string,
  document: ReturnType<typeof parseXml>,
  entryName: string,
): Promise<Uint8Array> {
  if (ref.entries.length > 0) return bytes;
  const outputDirectory = path.dirname(path.resolve(place.options.outputPath ?? 'package.mosc'));
  const entryFolder = path.posix.dirname(entryName);
  const carried = new Map<ResolvedPath, string>();
  if (place.options.selfContained) {
    const probe = await rebasePaths({
      document,
      baseOf: () => path.dirname(ref.disk),
      outputDirectory,
      kindOf: (diskPath) => nodeFileSystem.kind(diskPath),
    });
    for (const resolved of probe.resolved) {
      if (resolved.viaParameter) {
        // Left as written (SPEC 11.6): carried only where its value names it from inside the package, so that it still reaches it.
        const wanted = normalizeEntryName(path.posix.join(entryFolder, resolved.written.replace(/\\/g, '/')));
        const free = wanted !== undefined && !place.entries.includes(wanted) && ![...place.carried.values()].includes(wanted);
        const known = place.carried.get(resolved.disk);
        if (wanted !== undefined && !path.isAbsolute(resolved.written) && (known === wanted || (known === undefined && free)))
          if ((await carryIntoPackage(place, resolved, wanted)) === wanted) carried.set(resolved, resolved.site.attribute.value);
        continue;
      }
      const name = await carryIntoPackage(place, resolved);
      if (name !== undefined) carried.set(resolved, posixRelative(entryFolder, name));
    }
  }
  const byPlace = new Map([...carried].map(([resolved, name]) => [resolved.site.attribute.valueStart, name]));
  const rebase = await rebasePaths({
    document,
    baseOf: () => path.dirname(ref.disk),
    outputDirectory,
    kindOf: (diskPath) => nodeFileSystem.kind(diskPath),
    place: (resolved) => byPlace.get(resolved.site.attribute.valueStart),
  });
  const warned = new Set<string>();
  for (const resolved of rebase.resolved) {
    if (byPlace.has(resolved.site.attribute.valueStart) || warned.has(resolved.disk)) continue;
    warned.add(resolved.disk);
    const attribute = resolved.site.attribute;
    place.problems.push({
      source: ref,
      range: document.lines.range(attribute.valueStart, attribute.valueEnd),
      ...reachesOutsidePackageWording({
        kind: resolved.kind,
        disk: resolved.disk,
        rewritten: resolved.rewritten,
        written: attribute.value,
        viaParameter: resolved.viaParameter,
      }),
    });
  }
  if (rebase.edits.length === 0) return bytes;
  return new TextEncoder().encode(declareUtf8(applyEdits(text, rebase.edits)));
}

// A fixed entry time makes two packings of the same files byte-identical.
const ENTRY_DATE = new Date(Date.UTC(2000, 0, 1, 0, 0, 0));

function fileProblem(source: SourceRef, { severity, code, message, hint }: ProblemWording): Problem {
  return { source, range: ZERO_RANGE, severity, code, message, hint };
}

/** The file's text, or undefined with a problem when its encoding cannot be read. */
function decodeOrReport(ref: SourceRef, bytes: Uint8Array, problems: Problem[], base: string | undefined): string | undefined {
  try {
    return decodeScenario(bytes);
  } catch (error) {
    problems.push(fileProblem(ref, ioWording(`${displayRef(ref, base)}: ${(error as Error).message}`)));
    return undefined;
  }
}

function checkXml(ref: SourceRef, bytes: Uint8Array, problems: Problem[], base: string | undefined): void {
  const text = decodeOrReport(ref, bytes, problems, base);
  if (text === undefined) return;
  const document = parseXml(text);
  for (const problem of document.problems) {
    problems.push({
      source: ref,
      range: document.lines.range(problem.start, problem.end),
      ...xmlWording(problem.severity, problem.message),
    });
  }
}

async function generate(zip: JSZip): Promise<Uint8Array> {
  return zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE', compressionOptions: { level: 9 } });
}

/** `-cxm IN... OUT.mosc`: each input at the root of a new package under its base name (SPEC 6). */
export async function packFiles(inputs: string[], limits: Partial<Limits> = {}, options: PackOptions = {}): Promise<PackResult> {
  const problems: Problem[] = [];
  const entries: string[] = [];
  const zip = new JSZip();
  const place: PackPlace = { zip, entries, folder: undefined, carried: new Map(), options, problems };
  const seen = new Map<string, string>();
  for (const input of inputs) {
    const ref = diskRef(input);
    const name = path.basename(input);
    const lower = name.toLowerCase();
    if (!lower.endsWith('.xosc') && !lower.endsWith('.mosc')) {
      problems.push(fileProblem(ref, notPackableWording(name)));
      continue;
    }
    const previous = seen.get(name);
    if (previous) {
      problems.push(fileProblem(ref, duplicateInputWording(name, previous)));
      continue;
    }
    seen.set(name, input);
    const kind = await nodeFileSystem.kind(ref.disk);
    if (kind === 'directory') {
      problems.push(fileProblem(ref, packFolderWording(input)));
      continue;
    }
    let bytes: Uint8Array | undefined;
    try {
      bytes = await nodeFileSystem.readFile(ref.disk, limits.maxEntryBytes ?? DEFAULT_LIMITS.maxEntryBytes);
    } catch (error) {
      problems.push(fileProblem(ref, ioWording((error as Error).message)));
      continue;
    }
    if (!bytes) {
      problems.push(fileProblem(ref, ioWording(`cannot read ${input}: no such file`)));
      continue;
    }
    if (lower.endsWith('.xosc')) {
      checkXml(ref, bytes, problems, options.workingDirectory);
      const text = decodeOrReport(ref, bytes, [], options.workingDirectory);
      const document = text === undefined ? undefined : parseXml(text);
      if (text !== undefined && document && isWellFormed(document))
        bytes = await rebasedForPackage(place, ref, bytes, text, document, name);
    }
    zip.file(name, bytes, { date: ENTRY_DATE, createFolders: false });
    entries.push(name);
  }
  const mains = inputs.filter((input) => path.basename(input) === 'main.xosc');
  if (mains.length !== 1) {
    problems.push(fileProblem(diskRef(inputs[0] ?? '.'), mainCountWording(mains.length)));
  }
  const failed = problems.some((problem) => problem.severity === 'error');
  return { bytes: failed ? undefined : await generate(zip), entries, problems, inputs: inputs.map((input) => diskRef(input)) };
}

/**
 * Packs an unpacked package: `main.xosc` of the folder plus everything it references, found as
 * flattening would find it; referenced folders become nested `.mosc` packages.
 */
export async function packFolder(folder: string, store: ScenarioStore, options: PackFolderOptions = {}): Promise<PackResult> {
  const problems: Problem[] = [];
  const inputs: SourceRef[] = [];
  const result = await packFolderInto(path.resolve(folder), store, options, problems, [], inputs);
  const failed = problems.some((problem) => problem.severity === 'error');
  return { bytes: failed || !result ? undefined : await generate(result.zip), entries: result?.entries ?? [], problems, inputs };
}

async function packFolderInto(
  folder: string,
  store: ScenarioStore,
  options: PackFolderOptions,
  problems: Problem[],
  stack: string[],
  inputs: SourceRef[],
): Promise<{ zip: JSZip; entries: string[] } | undefined> {
  const main = diskRef(path.join(folder, 'main.xosc'));
  if ((await store.kindOf(main.disk)) !== 'file') {
    problems.push(fileProblem(diskRef(folder), notUnpackedPackageWording(store.display(diskRef(folder)))));
    return undefined;
  }
  const zip = new JSZip();
  const entries: string[] = [];
  const place: PackPlace = { zip, entries, folder, carried: new Map(), options, problems };
  const added = new Map<string, string>();
  const add = (name: string, bytes: Uint8Array, origin: string) => {
    const existing = added.get(name);
    if (existing !== undefined) {
      if (existing !== origin) problems.push(fileProblem(main, entryClashWording(name, existing, origin)));
      return;
    }
    added.set(name, origin);
    zip.file(name, bytes, { date: ENTRY_DATE, createFolders: false });
    // A scenario a self-contained package already carries as a file of a catalog folder keeps one entry: its own, rebased.
    if (!entries.includes(name)) entries.push(name);
  };
  const visit = async (ref: SourceRef, entryName: string, chain: string[]) => {
    let bytes: Uint8Array;
    try {
      bytes = await store.readBytes(ref);
    } catch (error) {
      problems.push(fileProblem(ref, ioWording((error as Error).message)));
      return;
    }
    inputs.push(ref);
    const text = decodeOrReport(ref, bytes, problems, store.workingDirectory);
    const document = text === undefined ? undefined : parseXml(text);
    if (text === undefined || !document || !isWellFormed(document)) {
      add(entryName, bytes, refId(ref));
      if (text !== undefined) checkXml(ref, bytes, problems, store.workingDirectory);
      return;
    }
    add(entryName, await rebasedForPackage(place, ref, bytes, text, document, entryName), refId(ref));
    const model = buildModel(document);
    for (const reference of model.references) {
      const range = reference.fileAttribute
        ? document.lines.range(reference.fileAttribute.valueStart, reference.fileAttribute.valueEnd)
        : ZERO_RANGE;
      const report = (code: ProblemCode, message: string, hint?: string, severity: Problem['severity'] = 'error') =>
        problems.push({ source: ref, range, severity, code, message, hint });
      const reportWording = ({ code, message, hint, severity }: ProblemWording) => report(code, message, hint, severity);
      const resolution = await store.resolve(reference.fileName, ref);
      if (resolution.kind === 'scenario') inputs.push(resolution.ref);
      if (resolution.kind === 'package') inputs.push(resolution.packageRef, resolution.main);
      const name = normalizeEntryName(reference.fileName);
      if (resolution.kind === 'missing') {
        reportWording(missingFileWording(reference.fileName, resolution.searched, undefined, resolution.hint));
        continue;
      }
      if (resolution.kind === 'invalid' || resolution.kind === 'unreadable' || name === undefined) {
        reportWording(
          resolution.kind === 'unreadable'
            ? badPackageWording(resolution.message)
            : resolution.kind === 'invalid'
              ? invalidReferenceWording(resolution.message)
              : outsidePackageWording(reference.fileName),
        );
        continue;
      }
      if (resolution.via === 'scenarioPath' && !options.includeScenarioPath) {
        reportWording(leftOutOfPackageWording(reference.fileName));
        continue;
      }
      if (resolution.kind === 'scenario') {
        if (chain.includes(refId(resolution.ref))) continue;
        await visit(resolution.ref, name, [...chain, refId(resolution.ref)]);
        continue;
      }
      const packageName = resolution.fallbackFrom ? fallbackPackageName(name) : name;
      if (resolution.fallbackFrom) reportWording(xoscFallbackWording(resolution.fallbackFrom, packageName, 'stored'));
      if (resolution.folder && resolution.packageRef.entries.length === 0) {
        const nestedFolder = resolution.packageRef.disk;
        if (stack.includes(nestedFolder) || nestedFolder === folder) {
          reportWording(
            packageCycleWording(
              [...stack, folder, nestedFolder].map((entry) =>
                store.workingDirectory === undefined ? entry : path.relative(store.workingDirectory, entry) || '.',
              ),
            ),
          );
          continue;
        }
        const nested = await packFolderInto(nestedFolder, store, options, problems, [...stack, folder], inputs);
        if (nested) add(packageName, await generate(nested.zip), refId(resolution.packageRef));
      } else {
        try {
          add(packageName, await store.readBytes(resolution.packageRef), refId(resolution.packageRef));
        } catch (error) {
          reportWording(ioWording((error as Error).message));
        }
      }
    }
  };
  await visit(main, 'main.xosc', [refId(main)]);
  return { zip, entries };
}
