import * as fs from 'node:fs';
import * as path from 'node:path';
import { childRef, diskRef, Limits, ScenarioStore, SourceRef, splitScenarioPath } from '../core/sources';
import { libraryFolders } from '../libraries';
import { cliFileSystem } from './fileSystem';

/** The main file that an input names: a package's main.xosc, a folder's main.xosc, or the file itself. */
export function mainOf(input: string): SourceRef {
  const resolved = path.resolve(input);
  if (fs.existsSync(resolved) && fs.statSync(resolved).isDirectory()) return diskRef(path.join(resolved, 'main.xosc'));
  if (resolved.toLowerCase().endsWith('.mosc')) return childRef(diskRef(resolved), 'main.xosc');
  return diskRef(resolved);
}

/**
 * The store for a command's inputs: the scenario path (options first, then SCENARIO_PATH), and the
 * folder where the search upward from an unpacked folder stops (`root`, else the working directory,
 * or the first input's folder when it lies elsewhere).
 */
export function storeForInputs(
  scenarioPath: string[],
  root: string | undefined,
  inputs: string[],
  limits: Partial<Limits> = {},
  catalogPath: string[] = [],
): ScenarioStore {
  const cwd = process.cwd();
  const firstInput = inputs[0] ? path.resolve(inputs[0]) : cwd;
  const insideCwd = firstInput === cwd || firstInput.startsWith(cwd + path.sep);
  const inputFolder = fs.existsSync(firstInput) && fs.statSync(firstInput).isDirectory() ? firstInput : path.dirname(firstInput);
  return new ScenarioStore({
    scenarioPath: [...scenarioPath, ...splitScenarioPath(process.env.SCENARIO_PATH)],
    catalogPath: catalogPath.map((folder) => path.resolve(folder)),
    root: root ?? (insideCwd ? cwd : inputFolder),
    workingDirectory: cwd,
    limits,
    libraries: libraryFolders([]),
    host: cliFileSystem,
  });
}
