import type { CancellationToken } from 'vscode-languageserver/node';
import * as path from 'node:path';
import { Flattener } from '../core/flatten';
import { Problem } from '../core/problems';
import { diskRef, refId } from '../core/sources';
import { SamplingError } from '../core/variations';
import { EsminiRunOptions, EsminiRunResult, removeRunFolder, runScenario, runScenarioText } from '../esmini/run';
import { searchPathOf } from '../batch/plan';
import { CatalogLoader } from '../core/semantics/catalogs';
import { controllerFilesFrom } from '../esmini/controllerFiles';
import { DistributionAnalysis, distributionAnalysis, distributionProblems } from './distributions';
import { RunEsminiParams, RunEsminiResult } from '../../../common/src/protocol';
import { Workspace } from '../workspace';
import { refOf, summarize } from './commands';

/** The strings of a list a client sent (blank ones and others left out). */
export function stringList(value: unknown): string[] {
  return Array.isArray(value) ? value.filter((item): item is string => typeof item === 'string' && item.trim().length > 0) : [];
}

/** The latest run folders of every server of this process, removed when it exits: one exit listener for all (tests start many servers in one process). */
const runsUntilExit = new Set<EsminiRunResult>();
let exitListener = false;

function keepUntilExit(run: EsminiRunResult): void {
  runsUntilExit.add(run);
  if (exitListener) return;
  exitListener = true;
  process.on('exit', () => runsUntilExit.forEach((kept) => removeRunFolder(kept)));
}

function removeNow(run: EsminiRunResult): void {
  removeRunFolder(run);
  runsUntilExit.delete(run);
}

/**
 * Run in esmini for one server: flattens the file as the editor has it and runs it. The files of a
 * file's previous run are removed when it runs again, and all of this server's when the process exits.
 */
export class EsminiRuns {
  /** The run folders still on disk, the latest run of each file. */
  private readonly previous = new Map<string, EsminiRunResult>();

  constructor(private readonly workspace: Workspace) {}

  async run(params: RunEsminiParams, token?: CancellationToken): Promise<RunEsminiResult> {
    const workspace = this.workspace;
    const ref = await refOf(workspace, params?.uri);
    const duration =
      typeof params.duration === 'number' && params.duration > 0 && Number.isFinite(params.duration) ? params.duration : undefined;
    const cancel = new AbortController();
    token?.onCancellationRequested(() => cancel.abort());
    const options: EsminiRunOptions = {
      esminiPath: typeof params.esminiPath === 'string' ? params.esminiPath : undefined,
      roadPath: stringList(params.roadPath),
      base: workspace.folders[0],
      duration,
      durationSetBy: 'the modular2simple.esmini.duration setting',
      cancel: cancel.signal,
      force: params.force === true,
    };
    const distribution = await distributionAnalysis(workspace, ref);
    const result = distribution
      ? await runFirstConcrete(distribution, options, new CatalogLoader(workspace.store))
      : await runScenario(new Flattener(workspace.store), ref, options);
    const id = refId(ref);
    const earlier = this.previous.get(id);
    if (earlier) removeNow(earlier);
    this.previous.set(id, result);
    // Added with the first run, so that a process whose servers never run esmini adds no exit listener.
    keepUntilExit(result);
    return {
      outcome: result.outcome,
      message: result.message,
      uri: workspace.uriOf(ref),
      problems: result.problems.map((problem) => ({
        uri: workspace.uriOf(problem.source),
        range: problem.range,
        severity: problem.severity,
        message: problem.message,
        count: problem.count,
        ...(problem.time !== undefined ? { time: problem.time } : {}),
        located: problem.located,
        ...(problem.note ? { note: problem.note } : {}),
      })),
      flattenProblems: result.flattenProblems.map((problem) => summarize(workspace, problem)),
      esminiFindings: result.esminiFindings.map((problem) => summarize(workspace, problem)),
      ...(result.forcible ? { forcible: true } : {}),
      log: result.log,
      ...(result.trace ? { trace: result.trace } : {}),
      csvFile: result.csvFile,
      ...(result.collisions?.length ? { collisions: result.collisions.map(({ entities, time }) => ({ entities, time: time ?? 0 })) } : {}),
      scenarioFile: result.scenarioFile,
      // A distribution file has no roads or entities of its own: the view draws its concrete scenario's on its ScenarioFile.
      ...(distribution?.loaded.variations && /\.xosc$/i.test(distribution.loaded.variations.scenarioPath)
        ? { scenarioOf: workspace.uriOf(diskRef(distribution.loaded.variations.scenarioPath)) }
        : {}),
      duration: result.duration,
      timeStep: result.timeStep,
      seed: result.seed,
      simulatedTime: result.simulatedTime,
      wallMs: result.wallMs,
      esmini: result.esmini,
      args: result.args,
      remarks: result.remarks.map((remark) => ({ message: remark.text, count: remark.count, origin: remark.origin, why: remark.why })),
      ...(result.roadFile
        ? {
            roadFile: {
              filepath: result.roadFile.filepath,
              resolved: result.roadFile.resolved,
              ...(result.roadFile.packaged ? { packaged: result.roadFile.packaged } : {}),
              loaded: result.roadFile.loaded,
            },
          }
        : {}),
    };
  }
}

/**
 * Run in esmini on a distribution file: its first concrete scenario that the ValueConstraintGroups keep,
 * run as `batch` runs it (from the ScenarioFile's folder), the message saying which index it was.
 */
async function runFirstConcrete(
  analysis: DistributionAnalysis,
  options: EsminiRunOptions,
  catalogs: CatalogLoader,
): Promise<EsminiRunResult> {
  const variations = analysis.loaded.variations;
  const notRun = (message: string, flattenProblems: Problem[] = []): EsminiRunResult => ({
    outcome: 'not-flattened',
    message,
    log: '',
    duration: options.duration ?? 0,
    limitKind: options.duration === undefined ? 'runaway' : 'user',
    timeStep: 0,
    seed: 0,
    wallMs: 0,
    problems: [],
    remarks: [],
    flattenProblems,
    esminiFindings: [],
  });
  if (!variations) {
    const problems = distributionProblems(analysis).filter((problem) => problem.severity === 'error');
    return notRun(
      `the distribution has ${problems.length} error${problems.length === 1 ? '' : 's'}, so it has no concrete scenario to run`,
      problems,
    );
  }
  let chosen: { index: bigint; text: string; values: string } | undefined;
  try {
    for (let index = 0n; index < variations.count && !chosen; index++) {
      const concrete = variations.concreteAt(index);
      if ('text' in concrete)
        chosen = {
          index,
          text: concrete.text,
          values: concrete.assignments.map((assignment) => `${assignment.parameter} = ${assignment.value}`).join(', '),
        };
    }
  } catch (error) {
    if (!(error instanceof SamplingError)) throw error;
    return notRun(`the distribution cannot be drawn from: ${error.message}`);
  }
  if (!chosen)
    return notRun(
      `every one of the distribution's ${variations.count} combinations breaks the scenario's ValueConstraintGroups: nothing to run`,
    );
  const scenarioFolder = path.dirname(variations.scenarioPath);
  // Its controller Files named through a `$parameter` are looked up as `run` looks them up, from the ScenarioFile's folder.
  const controllerFiles = await controllerFilesFrom(chosen.text, scenarioFolder, catalogs);
  const ran = await runScenarioText(chosen.text, searchPathOf(chosen.text, scenarioFolder, []), {
    ...options,
    controllerFilesFrom: controllerFiles,
  });
  const which = `concrete scenario ${chosen.index} of ${variations.count} (${chosen.values})`;
  return { ...ran, message: `ran ${which}: ${ran.message}`, problems: [], flattenProblems: [], esminiFindings: [] };
}
