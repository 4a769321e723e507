import * as path from 'node:path';
import { decodeScenario } from './core/encoding';
import { childRef, diskRef, refId, SourceRef } from './core/sources';
import { LineIndex, Range } from './core/text';
import { SCENARIO_FILE, walkFiles } from './core/walk';

export interface IndexedGroup {
  name: string;
  range: Range;
  /** The file the group is written in: the indexed file, or an entry of the indexed package. */
  ref: SourceRef;
}

/** The catalog entries one scenario names in `CatalogReference`s: the reverse index from entries to the files naming them. */
export interface IndexedCatalogReferences {
  /** The scenario: the indexed file, or an entry of the indexed package. */
  ref: SourceRef;
  /**
   * Each `entryName` value as written (a `$name` or `${...}` names no entry until the file is analysed);
   * undefined when the scenario was not scanned (too large or not decodable): it may name any.
   */
  entryNames: string[] | undefined;
}

/** What the index knows of one scenario file on disk without keeping its parse tree. */
export interface IndexedFile {
  path: string;
  kind: 'xosc' | 'mosc';
  groups: IndexedGroup[];
  /** Whether the file holds ScenarioReferences (and so can refer to other files). */
  modular: boolean;
  /** Its scenarios (the file, or each of a package) that name catalog entries, or were not scanned. */
  catalogReferences: IndexedCatalogReferences[];
  /**
   * Each `scenarioFileName` value as written in the file (in a package: in any of its scenarios), the
   * reverse index from files to the main files that may reach them; undefined when a package holds
   * what the scan does not read (a nested package, a scenario too large or not decodable): it may reach any.
   */
  scenarioNames: string[] | undefined;
  /** For a ParameterValueDistribution file: its ScenarioFile's `filepath` as written (the scenario whose root parameters it varies). */
  distributionOf?: string;
}

/** A file's text for the index; a file in an encoding that cannot be read is indexed without groups (its analysis reports why). */
export function decodeOrUndefined(bytes: Uint8Array): string | undefined {
  try {
    return decodeScenario(bytes);
  } catch {
    return undefined;
  }
}

/**
 * A name read from a file's text, copied out of it: V8 keeps a slice of 13 characters or more as a view of
 * the whole text, so a kept scenarioFileName held every indexed file's text in memory.
 */
function detached(name: string): string {
  return (' ' + name).slice(1);
}

const ENTRY_NAME = /\sentryName\s*=\s*(?:"([^"]*)"|'([^']*)')/;
const SCENARIO_FILE_NAME = /\sscenarioFileName\s*=\s*(?:"([^"]*)"|'([^']*)')/;
const DISTRIBUTION_SCENARIO_FILE = /<ScenarioFile\b[^>]*?\sfilepath\s*=\s*(?:"([^"]*)"|'([^']*)')/;

/**
 * Group names (with ranges), whether references occur and the catalog references, by a scan of the
 * text: the index of a large workspace is built without keeping or even building parse trees.
 * Comments are skipped.
 */
export function scanScenario(
  text: string,
  ref: SourceRef,
): Pick<IndexedFile, 'groups' | 'modular' | 'catalogReferences' | 'scenarioNames' | 'distributionOf'> {
  const lines = new LineIndex(text);
  const groups: IndexedGroup[] = [];
  const entryNames: string[] = [];
  let scenarioNames: string[] | undefined = [];
  // A reference's tag is read quote-aware: a `>` inside another attribute's value must not hide the name read.
  const pattern =
    /<!--[\s\S]*?(?:-->|$)|<ManeuverGroup\b[^>]*>|<(CatalogReference|ScenarioReference)\b(?:[^>"']|"[^"]*"|'[^']*')*>|(<ScenarioReference\b)/g;
  for (let match = pattern.exec(text); match; match = pattern.exec(text)) {
    if (match[0].startsWith('<!--')) continue;
    if (match[1] === 'CatalogReference') {
      const entryName = ENTRY_NAME.exec(match[0]);
      entryNames.push(entryName ? detached(entryName[1] ?? entryName[2]) : '');
      continue;
    }
    if (match[1] === 'ScenarioReference' || match[2]) {
      // A tag the scan cannot read whole (a quote left open) may still name a file for the parser: it may reach any.
      const fileName = match[2] ? null : SCENARIO_FILE_NAME.exec(match[0]);
      if (fileName) scenarioNames?.push(detached(fileName[1] ?? fileName[2]));
      else if (match[2]) scenarioNames = undefined;
      continue;
    }
    const name = /\sname\s*=\s*(?:"([^"]*)"|'([^']*)')/.exec(match[0]);
    groups.push({ name: name ? (name[1] ?? name[2]) : '', range: lines.range(match.index, match.index + match[0].length), ref });
  }
  const scenarioFile = text.includes('<ParameterValueDistribution') ? DISTRIBUTION_SCENARIO_FILE.exec(text) : null;
  return {
    ...(scenarioFile ? { distributionOf: scenarioFile[1] ?? scenarioFile[2] } : {}),
    groups,
    modular: /<ScenarioReference\b/.test(text),
    catalogReferences: entryNames.length > 0 ? [{ ref, entryNames }] : [],
    scenarioNames,
  };
}

/** Build output and test runner caches of an editor workspace are not scenarios of its own. */
const INDEX_SKIPPED_FOLDERS = new Set(['node_modules', '.git', 'dist', 'out', '.vscode-test']);

/** Every `.xosc` and `.mosc` below the folders, skipping build and dependency folders; never throws. */
export function listScenarioFiles(folders: string[], limit = 100_000): Promise<string[]> {
  return walkFiles(folders, {
    files: SCENARIO_FILE,
    skipFolders: INDEX_SKIPPED_FOLDERS,
    skipDotFiles: false,
    regularFilesOnly: true,
    unreadable: 'skip',
    sorted: true,
    limit,
  });
}

/** Whether a folder's scenario files are in the index: below a workspace folder, through no folder the walk skips. */
export function isIndexedFolder(folder: string, folders: string[]): boolean {
  return folders.some((root) => {
    const relative = path.relative(root, folder);
    if (relative === '') return true;
    if (path.isAbsolute(relative)) return false;
    return relative.split(path.sep).every((part) => part !== '..' && !part.startsWith('.') && !INDEX_SKIPPED_FOLDERS.has(part));
  });
}

/** The main file `check` analyses for an indexed file: the file itself, or a package's main.xosc. */
export function mainOf(filePath: string, kind: IndexedFile['kind']): SourceRef {
  return kind === 'mosc' ? childRef(diskRef(filePath), 'main.xosc') : diskRef(filePath);
}

/** A file name as a `scenarioFileName` may end in it: lowercased, without `.xosc` or `.mosc` (`NAME.xosc` may read `NAME.mosc`). */
function stemOf(fileName: string): string {
  const lower = fileName.toLowerCase();
  return lower.endsWith('.xosc') || lower.endsWith('.mosc') ? lower.slice(0, -'.xosc'.length) : lower;
}

/**
 * The stems under which a `scenarioFileName` may reach a file: its own name's, and for a `main.xosc` its
 * folder's or package's (a folder package `P.mosc`, or `P.xosc` read as that package).
 */
function stemsReaching(ref: SourceRef): string[] {
  const parts = [path.basename(ref.disk), ...ref.entries.flatMap((entry) => entry.split('/'))];
  const stems = [stemOf(parts[parts.length - 1])];
  if (parts.length === 1 && stems[0] === 'main') stems.push(stemOf(path.basename(path.dirname(ref.disk))));
  else if (stems[0] === 'main') stems.push(stemOf(parts[parts.length - 2]));
  return stems;
}

/**
 * The stem a written `scenarioFileName` names, or undefined when it may reach a file under another name
 * or outside the index: a parameter or entity reference, white space the parser normalizes, an absolute
 * path, a path through `..` or through a folder the index skips.
 */
function writtenStem(name: string): string | undefined {
  const trimmed = name.trim();
  if (mayReadOtherwise(trimmed) || path.isAbsolute(trimmed) || /^[a-zA-Z]:/.test(trimmed)) return undefined;
  const parts = trimmed.split(/[/\\]/);
  const folders = parts.slice(0, -1).filter((part) => part !== '.' && part !== '');
  if (folders.some((part) => part.startsWith('.') || INDEX_SKIPPED_FOLDERS.has(part))) return undefined;
  return stemOf(parts[parts.length - 1]);
}

/** An entry name as written that may read as another name: a parameter, an entity reference, white space the parser normalizes. */
function mayReadOtherwise(entryName: string): boolean {
  return /[$&\t\n\r]/.test(entryName);
}

/**
 * The index of the workspace's scenario files: an entry per file (read again after the file changes)
 * and the list of the files. The list comes from one walk of the folders; while the client reports
 * files appearing and vanishing (`watched`), it stays true until such an event, so the passes that ask
 * the index (a diagnostic pass above all) walk no folder.
 */
export class WorkspaceIndex {
  private readonly entries = new Map<string, IndexedFile>();
  /** The scenario files as the last walk found them, sorted; undefined until a walk or after a file appeared or vanished. */
  private listed: string[] | undefined;
  /** Whether the client reports files appearing and vanishing (watched-file events), so the list stays true between walks. */
  watched = false;

  get(filePath: string): IndexedFile | undefined {
    return this.entries.get(filePath);
  }

  set(filePath: string, entry: IndexedFile): void {
    this.entries.set(filePath, entry);
  }

  /** The file's entry is stale (read again on next use); the file stays in the list. */
  delete(filePath: string): void {
    this.entries.delete(filePath);
  }

  /** A file appeared or vanished: the list is walked again on next use. */
  forgetListing(): void {
    this.listed = undefined;
  }

  /** Everything: the folders changed. */
  clear(): void {
    this.entries.clear();
    this.listed = undefined;
  }

  /** The scenario files of the folders, by a walk, which the list then keeps. */
  async walk(folders: string[]): Promise<string[]> {
    const walked = await listScenarioFiles(folders);
    this.listed = walked;
    return walked;
  }

  /** The scenario files of the folders: the list kept while watched, else a walk. */
  async paths(folders: string[]): Promise<string[]> {
    return this.watched && this.listed ? this.listed : this.walk(folders);
  }

  /**
   * The scenarios that may name catalog entry `entryName` (`undefined`: any entry) in a CatalogReference,
   * from the entries' scans: those writing it, or a `$name` in its place, and those not scanned.
   */
  static catalogReferrers(entries: IndexedFile[], entryName: string | undefined): SourceRef[] {
    const refs = new Map<string, SourceRef>();
    for (const entry of entries)
      for (const { ref, entryNames } of entry.catalogReferences)
        if (!entryNames || entryName === undefined || entryNames.some((name) => name === entryName || mayReadOtherwise(name)))
          refs.set(refId(ref), ref);
    return [...refs.values()];
  }

  /**
   * The main files (as `mainOf` gives them, in the entries' order) whose references may reach `target`,
   * directly or through other files, from the entries' scans: a main naming a file under one of the
   * names reaching the target, or under one reaching such a main, or under any name when its scan
   * cannot tell (`scenarioNames` undefined, a name `writtenStem` cannot read). A file too large to scan
   * is no main (as for `check`'s pull) but may stand between a main and the target.
   */
  static referrersOf(entries: IndexedFile[], target: SourceRef): SourceRef[] {
    const reached = new Set(stemsReaching(target));
    for (const entry of entries)
      if (!entry.scenarioNames) for (const stem of stemsReaching(mainOf(entry.path, entry.kind))) reached.add(stem);
    const candidates = entries.filter((entry) => entry.kind === 'mosc' || entry.modular);
    const selected = new Set<IndexedFile>();
    for (let grew = true; grew;) {
      grew = false;
      for (const entry of candidates) {
        if (selected.has(entry)) continue;
        const reaches =
          !entry.scenarioNames ||
          entry.scenarioNames.some((name) => {
            const stem = writtenStem(name);
            return stem === undefined || reached.has(stem);
          });
        if (!reaches) continue;
        selected.add(entry);
        for (const stem of stemsReaching(mainOf(entry.path, entry.kind))) reached.add(stem);
        grew = true;
      }
    }
    return candidates.filter((entry) => selected.has(entry)).map((entry) => mainOf(entry.path, entry.kind));
  }
}
