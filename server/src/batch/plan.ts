import * as fs from 'node:fs';
import * as path from 'node:path';
import type { PackagedFile } from '../core/flatten/types';
import type { Variations } from '../core/variations';
import { valuesAfter } from '../core/variations/concrete';
import { Evaluator, semanticModelOf } from '../core/semantics';
import { attribute, descendants, parseXml, XmlElement } from '../core/xml';
import { scenarioEnd } from '../esmini/timeLimit';
import type { ControllerFilesFrom } from '../esmini/controllerFiles';
import type { ConcreteRun } from './runConcrete';
import type { BatchRow } from './results';

/** What a batch runs: the chosen indices of a distribution, with where their runs look for files. */
export interface BatchPlanView {
  variations: Variations;
  chosen: bigint[];
  parameterNames: string[];
  searchPath: string[];
  scenarioFolder: string;
  /** Files of a self-contained package ScenarioFile that its flattened text names (`flattened.files/`), relative to `scenarioFolder`. */
  packagedFiles: PackagedFile[];
  /** Where a local batch wrote `packagedFiles`, in the same layout, and those `packagedOf` names. */
  packagedFolder?: string;
  /** The package files a concrete scenario's text names through a `$parameter` (a varied road), placed as `packagedFiles` are. */
  packagedOf?: (text: string) => Promise<PackagedFile[]>;
  /** Where a concrete scenario's controller Files named through a `$parameter` are looked up from, as `run` looks them up (esmini/controllerFiles.ts). */
  controllerFilesOf?: (text: string) => Promise<ControllerFilesFrom>;
}

/** The varied parameters, in the order the distribution names them first: the columns after the fixed ones. */
export function variedParameters(variations: Variations): string[] {
  const names: string[] = [];
  const add = (name: string) => {
    if (!names.includes(name)) names.push(name);
  };
  for (const distribution of variations.distribution.deterministic ?? []) {
    if (distribution.kind === 'multi') distribution.sets.flat().forEach((value) => add(value.parameter));
    else add(distribution.parameter);
  }
  for (const distribution of variations.distribution.stochastic?.distributions ?? []) add(distribution.parameter);
  return names;
}

/** The paths a scenario names outside itself, `$name` and `${...}` evaluated as esmini reads them: its LogicFile and its catalog directories. */
export interface NamedPaths {
  roads: string[];
  catalogFolders: string[];
}

export function namedPaths(text: string): NamedPaths {
  const document = parseXml(text);
  const roads: string[] = [];
  const catalogFolders: string[] = [];
  let evaluator: Evaluator | undefined;
  // A concrete scenario of a distribution often names its road through a varied parameter (ALKS: filepath="$Road").
  const valueOf = (element: XmlElement, name: string): string | undefined => {
    const found = attribute(element, name);
    if (!found?.value) return undefined;
    if (!found.value.includes('$')) return found.value;
    evaluator ??= new Evaluator(semanticModelOf(document), undefined, 'esmini');
    const result = evaluator.attributeValue(element, found);
    return result.ok && typeof result.value === 'string' && result.value ? result.value : undefined;
  };
  for (const child of document.root?.children ?? []) {
    if (child.name === 'RoadNetwork') {
      const logicFile = child.children.find((each) => each.name === 'LogicFile');
      const logic = logicFile ? valueOf(logicFile, 'filepath') : undefined;
      if (logic) roads.push(logic);
    }
    if (child.name === 'CatalogLocations') {
      for (const directory of descendants(child)) {
        const value = directory.name === 'Directory' ? valueOf(directory, 'path') : undefined;
        if (value) catalogFolders.push(value);
      }
    }
  }
  return { roads, catalogFolders };
}

/** Where a run of the scenario looks for roads and catalogs: its own folder, its catalog folders, then the road path. */
export function searchPathOf(text: string, scenarioFolder: string, roadPath: string[]): string[] {
  const folders = [
    scenarioFolder,
    ...namedPaths(text).catalogFolders.map((folder) => path.resolve(scenarioFolder, folder)),
    ...roadPath.map((folder) => path.resolve(folder)),
  ];
  return [...new Set(folders)];
}

/**
 * The files a run needs besides the scenario, found as esmini finds them (the path as written from the scenario's
 * folder, then each search folder with the path and with its file name): the road file and every catalog file.
 */
export function filesNeeded(text: string, scenarioFolder: string, searchPath: string[]): string[] {
  return filesNamed(namedPaths(text), scenarioFolder, searchPath);
}

/** `filesNeeded` of the paths a scenario names. */
export function filesNamed({ roads, catalogFolders }: NamedPaths, scenarioFolder: string, searchPath: string[]): string[] {
  const files = new Set<string>();
  for (const road of roads) {
    const candidates = [
      path.resolve(scenarioFolder, road),
      ...searchPath.flatMap((folder) => [path.resolve(folder, road), path.join(folder, path.basename(road))]),
    ];
    const found = candidates.find((candidate) => fs.existsSync(candidate) && fs.statSync(candidate).isFile());
    if (found) files.add(found);
  }
  for (const folder of catalogFolders) {
    const resolved = path.resolve(scenarioFolder, folder);
    let names: string[] = [];
    try {
      names = fs.readdirSync(resolved);
    } catch {
      continue;
    }
    for (const name of names)
      if (name.toLowerCase().endsWith('.xosc') && fs.statSync(path.join(resolved, name)).isFile()) files.add(path.join(resolved, name));
  }
  return [...files];
}

/** Concrete scenario `index` as a run, or its row when the scenario's ValueConstraintGroups discard it. */
export function concreteRun(
  variations: Variations,
  index: bigint,
  parameterNames: string[],
  searchPath: string[],
): ConcreteRun | { discarded: BatchRow } {
  const concrete = variations.concreteAt(index);
  const values = valuesAfter(variations.scenario, concrete.assignments);
  const parameters: Record<string, string> = {};
  for (const name of parameterNames) parameters[name] = values.get(name) ?? '';
  if ('broken' in concrete) return { discarded: discardedRow(index.toString(), parameters, concrete.broken) };
  return { index: index.toString(), text: concrete.text, parameters, searchPath };
}

/** The row of a combination that breaks the scenario's ValueConstraintGroups: it keeps its index and values, and does not run. */
function discardedRow(index: string, parameters: Record<string, string>, broken: { parameter: string; value: string }): BatchRow {
  return {
    index,
    status: 'discarded',
    collision: false,
    min_distance_m: null,
    min_ttc_s: null,
    end_time_s: null,
    parameters,
    ego: null,
    collisions: [],
    message: `discarded: parameter '${broken.parameter}' = '${broken.value}' breaks its ValueConstraintGroups`,
    reason: `parameter '${broken.parameter}' = '${broken.value}' breaks its ValueConstraintGroups`,
    messages: [],
  };
}

/** Runs whose end `limitWarning` reads before a batch starts: enough to speak for a batch, bounded for a huge one. */
const ENDS_READ = 1000;

/**
 * What to say before a batch whose limit (`--duration`) comes before the scenario's own end in some runs: they will
 * stop at the limit with status `limit`. Undefined when no run read ends past it (or no limit is set).
 */
export function limitWarning(plan: Pick<BatchPlanView, 'variations' | 'chosen'>, duration: number | undefined): string | undefined {
  if (duration === undefined) return undefined;
  let read = 0;
  let past = 0;
  let latest = 0;
  let only = true;
  for (const index of plan.chosen.slice(0, ENDS_READ)) {
    const concrete = plan.variations.concreteAt(index);
    if ('broken' in concrete) continue;
    read++;
    const end = scenarioEnd(concrete.text);
    if (!end || end.seconds <= duration) continue;
    past++;
    latest = Math.max(latest, end.seconds);
    only &&= end.only;
  }
  if (past === 0) return undefined;
  const which =
    past === read
      ? read === 1
        ? 'the run'
        : `all ${read} runs`
      : `${past} of ${read === plan.chosen.length ? 'the' : 'the first'} ${read} runs`;
  return (
    `the scenario's StopTrigger ends ${which} after the --duration limit of ${duration} s (at up to ${Number(latest.toFixed(3))} s)` +
    `${only ? '' : ', unless its other stop conditions end them first'}: they will stop at ${duration} s with status limit; ` +
    `leave --duration out to run each to its own end`
  );
}
