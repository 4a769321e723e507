import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from './flatten';
import { Problem } from './problems';
import { buildModel } from './model';
import { notAPlainScenario } from './modularize';
import { LibraryFolder, Limits, ScenarioStore, diskRef, refId } from './sources';
import { countEditorLines } from './text';
import { parseXml } from './xml';

/** Why a scenario has no row: its errors counted, and the check that lists them (with the options stats was given). */
function cannotBeFlattened(name: string, file: string, problems: readonly Problem[]): string {
  const errors = problems.filter((problem) => problem.severity === 'error').length;
  return `${name}: cannot be flattened (${errors} error${errors === 1 ? '' : 's'}; 'modular2simple check ${file}', with the options given here, lists ${errors === 1 ? 'it' : 'them'})`;
}

export interface StatsRow {
  scenario: string;
  modularLines: number;
  flattenedLines: number;
  /** 1 - modular / flattened, as a percentage with one decimal. */
  reduction: number;
  /** Where the flattened figure comes from: the library's own result.xosc, or our flattening. */
  flattenedFrom: 'result.xosc' | 'flattened';
}

export interface LibraryStats {
  /** How the library is laid out: the paper's folders NAME/main.xosc, or scenario files side by side as modularize writes them. */
  layout: 'folders' | 'files';
  rows: StatsRow[];
  /** Simple scenarios outside the scenario folders that the mains use, counted once each. */
  shared: { file: string; lines: number }[];
  totals: { modularLines: number; flattenedLines: number; reduction: number };
  problems: string[];
}

function reduction(modular: number, flattened: number): number {
  return flattened === 0 ? 0 : Math.round((1 - modular / flattened) * 1000) / 10;
}

/** The .xosc files below `root`, hidden folders left out, sorted by path. */
function scenarioFilesBelow(root: string): string[] {
  const files: string[] = [];
  const walk = (folder: string) => {
    for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
      if (entry.name.startsWith('.')) continue;
      const full = path.join(folder, entry.name);
      if (entry.isDirectory()) walk(full);
      else if (entry.isFile() && entry.name.toLowerCase().endsWith('.xosc')) files.push(full);
    }
  };
  walk(root);
  return files.sort();
}

/**
 * Table 1 for scenario files side by side, as modularize writes them (DIR/rel.xosc beside DIR/simple/):
 * each scenario is a row (a main: its lines against its flattening; a plain one: its lines, both
 * sides), and each file a main imports is counted once among the shared simple scenarios. Catalogs and
 * parameter distributions are neither.
 */
function isWithin(folder: string, file: string): boolean {
  return file.startsWith(folder + path.sep);
}

/** A file a main depends on that is no simple scenario: a catalog its references read, or a parameter distribution. */
function isCatalogOrDistribution(text: string): boolean {
  const kinds = parseXml(text).root?.children.map((child) => child.name) ?? [];
  return kinds.includes('Catalog') || kinds.includes('ParameterValueDistribution');
}

async function filesLayout(
  root: string,
  flattener: Flattener,
  readText: (filePath: string) => Promise<string | undefined>,
  problems: string[],
): Promise<{ rows: StatsRow[]; shared: Map<string, number> }> {
  const scenarios: { file: string; lines: number; main: boolean }[] = [];
  for (const file of scenarioFilesBelow(root)) {
    const text = await readText(file);
    if (text === undefined) continue;
    const document = parseXml(text);
    const main = buildModel(document).references.length > 0;
    if (main || notAPlainScenario(document) === undefined) scenarios.push({ file, lines: countEditorLines(text), main });
  }
  const counted = new Set(scenarios.map((scenario) => scenario.file));
  const imported = new Set<string>();
  // Simple scenarios outside the folder (a library's modules, a scenario path's files): written once, counted once.
  const outside = new Map<string, number>();
  const flattenedLines = new Map<string, number>();
  for (const scenario of scenarios.filter((candidate) => candidate.main)) {
    const flattened = await flattener.flatten(diskRef(scenario.file));
    for (const dependency of flattened.source.dependencies) {
      const id = refId(dependency);
      if (dependency.entries.length > 0 || id === scenario.file) continue;
      if (counted.has(id)) imported.add(id);
      else if (!isWithin(root, id) && !outside.has(id)) {
        const text = await readText(id);
        if (text !== undefined && !isCatalogOrDistribution(text)) outside.set(id, countEditorLines(text));
      }
    }
    if (flattened.text !== undefined) flattenedLines.set(scenario.file, countEditorLines(flattened.text));
    else problems.push(cannotBeFlattened(path.relative(root, scenario.file), scenario.file, flattened.problems));
  }
  if (!scenarios.some((scenario) => scenario.main))
    problems.push(
      scenarios.length === 0
        ? `${root} holds no scenario: neither folders NAME/ with a main.xosc (the paper's layout) nor .xosc scenario files (as modularize writes them)`
        : `no scenario of ${root} imports groups (no ScenarioReference): there is nothing modular to count`,
    );
  const rows: StatsRow[] = [];
  const shared = new Map<string, number>(outside);
  for (const scenario of scenarios) {
    if (imported.has(scenario.file)) {
      shared.set(scenario.file, scenario.lines);
      continue;
    }
    const flattened = scenario.main ? flattenedLines.get(scenario.file) : scenario.lines;
    if (flattened === undefined) continue;
    rows.push({
      scenario: path.relative(root, scenario.file),
      modularLines: scenario.lines,
      flattenedLines: flattened,
      reduction: reduction(scenario.lines, flattened),
      flattenedFrom: 'flattened',
    });
  }
  return { rows, shared };
}

/** The paper's Table 1 for a library of modular scenarios (SPEC 9); messages show paths relative to `workingDirectory`. */
export async function libraryStats(
  library: string,
  limits: Partial<Limits> = {},
  workingDirectory?: string,
  /** Folders searched after the library's own (the CLI's --scenario-path, then SCENARIO_PATH), as `check` searches them. */
  scenarioPath: readonly string[] = [],
  /** The scenario libraries `library:NAME` resolves in, as `check` has them; their modules a main uses count as shared. */
  libraries: LibraryFolder[] = [],
  /** Where the mains' search upward stops (the CLI's --root); the library folder by default. */
  searchRoot?: string,
): Promise<LibraryStats> {
  const root = path.resolve(library);
  const folders = fs
    .readdirSync(root, { withFileTypes: true })
    .filter((entry) => entry.isDirectory() && fs.existsSync(path.join(root, entry.name, 'main.xosc')))
    .map((entry) => entry.name)
    .sort();
  // The paper's mains name the shared simple scenarios beside their folders; modularize's name them by relative path (simple/NAME.xosc).
  const store = new ScenarioStore({
    root: searchRoot === undefined ? root : path.resolve(searchRoot),
    scenarioPath: [...(folders.length > 0 ? [root] : []), ...scenarioPath],
    limits,
    workingDirectory,
    libraries,
  });
  const flattener = new Flattener(store);
  const problems: string[] = [];
  // Read through the store, which refuses folders, FIFOs, devices and files over the size bound.
  const readText = async (filePath: string): Promise<string | undefined> => {
    try {
      return await store.readText(diskRef(filePath));
    } catch (error) {
      problems.push((error as Error).message);
      return undefined;
    }
  };
  const readLines = async (filePath: string): Promise<number | undefined> => {
    const text = await readText(filePath);
    return text === undefined ? undefined : countEditorLines(text);
  };
  if (folders.length === 0) {
    const { rows, shared } = await filesLayout(root, flattener, readText, problems);
    return summary('files', rows, shared, problems);
  }
  const rows: StatsRow[] = [];
  const shared = new Map<string, number>();
  for (const folder of folders) {
    const mainPath = path.join(root, folder, 'main.xosc');
    const resultPath = path.join(root, folder, 'result.xosc');
    const modularLines = await readLines(mainPath);
    if (modularLines === undefined) continue;
    const flattened = await flattener.flatten(diskRef(mainPath));
    for (const dependency of flattened.source.dependencies) {
      const id = refId(dependency);
      if (dependency.entries.length === 0 && !id.startsWith(path.join(root, folder) + path.sep) && id !== mainPath) {
        const text = await readText(id);
        if (text !== undefined && !isCatalogOrDistribution(text)) shared.set(id, countEditorLines(text));
      }
    }
    let flattenedLines: number;
    let flattenedFrom: StatsRow['flattenedFrom'];
    const resultLines = fs.existsSync(resultPath) ? await readLines(resultPath) : undefined;
    if (resultLines !== undefined) {
      flattenedLines = resultLines;
      flattenedFrom = 'result.xosc';
    } else if (flattened.text !== undefined) {
      flattenedLines = countEditorLines(flattened.text);
      flattenedFrom = 'flattened';
    } else {
      problems.push(cannotBeFlattened(folder, mainPath, flattened.problems));
      continue;
    }
    rows.push({ scenario: folder, modularLines, flattenedLines, reduction: reduction(modularLines, flattenedLines), flattenedFrom });
  }
  return summary('folders', rows, shared, problems);
}

/** The table with its shared simple scenarios (counted once, on the modular side) and its totals. */
function summary(layout: LibraryStats['layout'], rows: StatsRow[], shared: Map<string, number>, problems: string[]): LibraryStats {
  const sharedList = [...shared.entries()].sort(([a], [b]) => a.localeCompare(b)).map(([file, lines]) => ({ file, lines }));
  const modularLines = rows.reduce((sum, row) => sum + row.modularLines, 0) + sharedList.reduce((sum, item) => sum + item.lines, 0);
  const flattenedLines = rows.reduce((sum, row) => sum + row.flattenedLines, 0);
  return {
    layout,
    rows,
    shared: sharedList,
    totals: { modularLines, flattenedLines, reduction: reduction(modularLines, flattenedLines) },
    problems,
  };
}
