import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from './flatten';
import { Limits, ScenarioStore, diskRef, refId } from './sources';
import { countEditorLines } from './text';

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
  rows: StatsRow[];
  /** Simple scenarios outside the scenario folders that the mains use, counted once each. */
  shared: { file: string; lines: number }[];
  totals: { modularLines: number; flattenedLines: number; reduction: number };
  problems: string[];
}

function reduction(modular: number, flattened: number): number {
  return flattened === 0 ? 0 : Math.round((1 - modular / flattened) * 1000) / 10;
}

/** The paper's Table 1 for a library of modular scenarios (SPEC 9); messages show paths relative to `workingDirectory`. */
export async function libraryStats(library: string, limits: Partial<Limits> = {}, workingDirectory?: string): Promise<LibraryStats> {
  const root = path.resolve(library);
  const folders = fs
    .readdirSync(root, { withFileTypes: true })
    .filter((entry) => entry.isDirectory() && fs.existsSync(path.join(root, entry.name, 'main.xosc')))
    .map((entry) => entry.name)
    .sort();
  const store = new ScenarioStore({ root, scenarioPath: [root], limits, workingDirectory });
  const flattener = new Flattener(store);
  const rows: StatsRow[] = [];
  const shared = new Map<string, number>();
  const problems: string[] = [];
  // Read through the store, which refuses folders, FIFOs, devices and files over the size bound.
  const readLines = async (filePath: string): Promise<number | undefined> => {
    try {
      return countEditorLines(await store.readText(diskRef(filePath)));
    } catch (error) {
      problems.push((error as Error).message);
      return undefined;
    }
  };
  for (const folder of folders) {
    const mainPath = path.join(root, folder, 'main.xosc');
    const resultPath = path.join(root, folder, 'result.xosc');
    const modularLines = await readLines(mainPath);
    if (modularLines === undefined) continue;
    const flattened = await flattener.flatten(diskRef(mainPath));
    for (const dependency of flattened.source.dependencies) {
      const id = refId(dependency);
      if (dependency.entries.length === 0 && !id.startsWith(path.join(root, folder) + path.sep) && id !== mainPath) {
        const lines = await readLines(id);
        if (lines !== undefined) shared.set(id, lines);
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
      problems.push(
        `${folder}: cannot be flattened (${flattened.problems.filter((p) => p.severity === 'error').length} errors; run 'modular2simple check')`,
      );
      continue;
    }
    rows.push({ scenario: folder, modularLines, flattenedLines, reduction: reduction(modularLines, flattenedLines), flattenedFrom });
  }
  const sharedList = [...shared.entries()].sort(([a], [b]) => a.localeCompare(b)).map(([file, lines]) => ({ file, lines }));
  const modularLines = rows.reduce((sum, row) => sum + row.modularLines, 0) + sharedList.reduce((sum, item) => sum + item.lines, 0);
  const flattenedLines = rows.reduce((sum, row) => sum + row.flattenedLines, 0);
  return {
    rows,
    shared: sharedList,
    totals: { modularLines, flattenedLines, reduction: reduction(modularLines, flattenedLines) },
    problems,
  };
}
