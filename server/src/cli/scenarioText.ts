import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener, parameterPackagedFiles } from '../core/flatten';
import type { PackagedFile } from '../core/flatten/types';
import { formatProblem, Problem } from '../core/problems';
import { diskRef, ScenarioStore, SourceRef } from '../core/sources';
import { CatalogLoader } from '../core/semantics/catalogs';
import { loadVariations, ScenarioTextLoader } from '../core/variations';
import type { SearchPathCatalogFolders } from '../core/variations/concrete';
import { readScenarioParameters } from '../core/variations/concrete';
import { distributionProblems, isDistributionText } from '../core/variations/problems';
import { readUtf8Exactly } from './fileSystem';

export { readUtf8Exactly };
import { mainOf, storeForInputs } from './inputs';

/** The distribution file named on the command line, or what is wrong with it in a few words (`vary` and `batch` report it alike). */
export async function readDistributionFile(given: string): Promise<{ path: string; text: string } | { problem: string }> {
  const file = path.resolve(given);
  try {
    return { path: file, text: await readUtf8Exactly(file) };
  } catch (error) {
    const reason = (error as NodeJS.ErrnoException).code === 'ENOENT' ? 'no such file' : (error as Error).message;
    return { problem: `${given}: ${reason}` };
  }
}

// A main file is a scenario with a ScenarioReference in some ManeuverGroup; a plain one has none at all.
const REFERENCE = /<ScenarioReference\b/;

/**
 * The hook of the variations engine for modular scenarios: a ParameterValueDistribution's ScenarioFile as
 * plain OpenSCENARIO. A plain `.xosc` is read as it is (byte for byte, as esmini reads it); a modular main,
 * an unpacked folder or a `.mosc` is flattened once, as `modular2simple flatten` does, and its values are
 * then spliced into the flattened text. A scenario that cannot be flattened is refused with its problems.
 * `packagedFiles` receives the files of a self-contained package the text names beside its folder (`flattened.files/`).
 */
export function flatteningScenarioLoader(
  scenarioPath: string[] = [],
  packagedFiles?: PackagedFile[],
  catalogPath: string[] = [],
  /** Flatten a modular ScenarioFile despite its errors (`batch --force`), as `run --force` does. */
  force = false,
): ScenarioTextLoader {
  return async (file: string): Promise<string> => {
    const isFolder = fs.existsSync(file) && fs.statSync(file).isDirectory();
    if (!isFolder && !file.toLowerCase().endsWith('.mosc')) {
      const text = await readUtf8Exactly(file);
      if (!REFERENCE.test(text)) return text;
    } else if (!fs.existsSync(file)) {
      throw Object.assign(new Error('no such file'), { code: 'ENOENT' });
    }
    const flattener = new Flattener(storeForInputs(scenarioPath, undefined, [file], {}, catalogPath));
    const result = await flattener.flatten(mainOf(file), { force });
    if (result.text !== undefined) {
      packagedFiles?.push(...result.files);
      return result.text;
    }
    const errors = result.problems.filter((problem) => problem.severity === 'error');
    const shown = errors.slice(0, 10).map((problem) => '\n  ' + formatProblem(problem, process.cwd()).replace(/\n/g, '\n  '));
    const more = errors.length > shown.length ? `\n  (${errors.length - shown.length} more)` : '';
    throw new Error(`cannot be flattened (${errors.length} error${errors.length === 1 ? '' : 's'}):${shown.join('')}${more}`);
  };
}

/**
 * For a ScenarioFile inside a package: the package files a concrete scenario's text names through a `$parameter` (a varied
 * road), placed from the ScenarioFile's folder as the flattening places the files it carries; none for a file on disk.
 */
export function concretePackagedFiles(
  file: string,
  scenarioPath: string[],
  catalogPath: string[] = [],
): (text: string) => Promise<PackagedFile[]> {
  const main = mainOf(file);
  if (main.entries.length === 0) return () => Promise.resolve([]);
  const store = storeForInputs(scenarioPath, undefined, [file], {}, catalogPath);
  return (text) => parameterPackagedFiles(text, main, scenarioFolderOf(file), store);
}

/**
 * The check `run` makes before it runs a scenario: its problems as flattening it finds them, with the same scenario
 * path and catalog folders. `batch` makes it on its ScenarioFile, plain or modular, before any run.
 */
export async function scenarioProblems(file: string, scenarioPath: string[], catalogPath: string[]): Promise<Problem[]> {
  const flattener = new Flattener(storeForInputs(scenarioPath, undefined, [file], {}, catalogPath));
  return (await flattener.flatten(mainOf(file))).problems;
}

/**
 * The folders holding catalog files that a `Directory path` written in `from` reaches only through the store's scenario path
 * (not from its own folder): an output keeps such a path as written (SPEC 11.6), and esmini then needs them on `--path`.
 */
export function catalogFoldersThroughSearchPath(store: ScenarioStore, from: SourceRef): SearchPathCatalogFolders {
  const catalogs = new CatalogLoader(store);
  const holdsCatalogFiles = async (folder: string): Promise<boolean> =>
    (await fs.promises.readdir(folder).catch(() => [] as string[])).some((name) => name.toLowerCase().endsWith('.xosc'));
  return async (written) => {
    const found = (await catalogs.directories(from, written)).filter(
      (directory) => directory.via === 'scenarioPath' && !directory.packageRef,
    );
    const folders: string[] = [];
    for (const directory of found) if (await holdsCatalogFiles(directory.directory)) folders.push(directory.directory);
    return folders;
  };
}

/** The folder the ScenarioFile's relative paths (roads, catalogs) start from: its own folder, a package's, or the unpacked folder itself. */
export function scenarioFolderOf(file: string): string {
  return fs.existsSync(file) && fs.statSync(file).isDirectory() ? file : path.dirname(file);
}

/**
 * A distribution file's problems as `vary` finds them (its ScenarioFile read by the same loader: a parameterName the
 * scenario does not declare, a ScenarioFile that does not resolve, values that do not fit), located in the file as
 * the editor shows them; none for a file that is no distribution.
 */
export async function distributionFileProblems(file: string, scenarioPath: string[]): Promise<Problem[]> {
  const absolute = path.resolve(file);
  let text: string;
  try {
    text = await readUtf8Exactly(absolute);
  } catch {
    return []; // The flattener reports a file it cannot read.
  }
  if (!isDistributionText(text)) return [];
  const load = flatteningScenarioLoader(scenarioPath);
  let scenarioText: string | undefined;
  let scenarioFile = '';
  const loaded = await loadVariations(text, absolute, async (scenario) => {
    scenarioFile = scenario;
    scenarioText = await load(scenario);
    return scenarioText;
  });
  const parameters = scenarioText === undefined ? [] : (readScenarioParameters(scenarioText, scenarioFile).scenario?.declarations ?? []);
  return distributionProblems({ ref: diskRef(absolute), file: absolute, text, loaded, parameters });
}
