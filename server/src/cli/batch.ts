import { createHash } from 'node:crypto';
import { setMaxListeners } from 'node:events';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { BatchPlanView, concreteRun, limitWarning, namedPaths, searchPathOf, variedParameters } from '../batch/plan';
import { Progress, Tally } from '../batch/progress';
import { loadQueueModule, QueuePackagesMissingError } from '../batch/queuePackages';
import { CriterionError, parseCriterion } from '../batch/criteria';
import { BatchIdentity, criteriaFailure, ResultsError, ResultsFolder } from '../batch/results';
import { keptBesideRun, NoEsminiError, runConcrete, RunSettings } from '../batch/runConcrete';
import type { PackagedFile } from '../core/flatten/types';
import { CatalogLoader } from '../core/semantics/catalogs';
import { diskRef, displayRef, FileKind, nodeFileSystem, splitScenarioPath } from '../core/sources';
import { loadVariations, rebasedConcreteText, samplingProblem, SamplingError } from '../core/variations';
import { locateEsmini } from '../esmini/locate';
import { controllerFilesFrom } from '../esmini/controllerFiles';
import { foundCatalogFolders, RUN_DEFAULTS, writePackagedFiles } from '../esmini/run';
import {
  CliCommand,
  CliOutput,
  durationOption,
  ExitCode,
  InputError,
  parseCommandLine,
  printed,
  UnavailableError,
  UsageError,
  wholeNumber,
} from './common';
import { concretePackagedFiles, flatteningScenarioLoader, readDistributionFile, scenarioFolderOf, scenarioProblems } from './scenarioText';
import { formatProblem } from '../core/problems';
import { mainOf, storeForInputs } from './inputs';
import { chosenIndices, problemPrinter, samplingOptions } from './vary';

export const BATCH_HELP = `Run every concrete scenario of a distribution in esmini (modular2simple batch FILE --results DIR ...):
  --results DIR             where results.csv and results.json go; run again into the same DIR, only what is
                            missing runs (an interrupted batch loses nothing and repeats nothing)
  --jobs N                  runs at a time (default: the number of cores)
  --sample N --seed S       N concrete scenarios drawn at random (seed S, default 0) instead of all
  --duration S              stop each run at S simulated seconds if its scenario has not ended by then (status
                            limit; a warning before the batch says when the scenario's StopTrigger ends past it);
                            default: each scenario's own end (one not ended after ${RUN_DEFAULTS.runawaySeconds} s, or a second after the
                            time its StopTrigger ends it at when that is later, or that makes no
                            progress for ${RUN_DEFAULTS.stallMs / 1000} s, is stopped: status timeout; one whose StopTrigger has no
                            condition runs ${RUN_DEFAULTS.noEndSeconds} s: status limit); fixed step ${RUN_DEFAULTS.timeStep} s, seed ${RUN_DEFAULTS.seed}
  --max-combinations N      refuse more combinations than N before running anything, unless --sample (default 1000000)
  --keep-runs               keep each run's files in DIR/runs/INDEX/ (scenario.xosc, trajectories.csv, esmini.log),
                            so that the Variations view and results.html can open a run; local runs only
  --fail-if CRITERION       a run fails when CRITERION holds: 'collision', or 'METRIC OP NUMBER' with METRIC one of
                            min_ttc_s, min_distance_m, end_time_s and OP one of < <= > >= == != (such as
                            --fail-if 'min_ttc_s < 1.5'); repeat it for several (a run fails when any holds). A run
                            that did not complete (error, timeout) fails too. Adds the column verdict (pass, fail)
  --junit OUT.xml           write the runs as JUnit XML for CI (a test case per run: failure, error or skipped)
  --queue redis://HOST:PORT put the runs on a BullMQ queue in Redis for 'modular2simple worker' and collect the results
  --esmini PATH, --road-path DIRS, --scenario-path DIRS   as for run
  --force                   run despite the scenario's errors: its ScenarioFile is checked first as run checks
                            it, and one with errors is refused (file, line, what to do) before anything runs
  results.csv (one row per index, in index order once the batch ends): index, status (ok: the scenario ended by itself; limit: stopped at --duration before it ended;
  timeout: it hung or ran away; error: esmini reported an error or did not run it), collision (esmini's collision detection), min_distance_m and min_ttc_s (the ego, or the first entity,
  against every other: bounding-box gap, and gap over closing speed), end_time_s, then one column per varied
  parameter, then reason (why the run is not ok: esmini's own reason for an error, what stopped a timeout or a
  limit; empty when ok). results.json: the same rows with esmini's messages. results.html: the table and a scatter of the
  first two parameters coloured by outcome, self-contained (written at the end, and on every resume).
  Exit codes: 0 every run done (with --fail-if: and passed), 1 the input has errors (nothing run), 2 usage, 3 a run
  failed in esmini (status error: the summary and the column reason say why), no esmini, the queue packages missing
  (bullmq and ioredis, for --queue), Redis unreachable or the results cannot be written, 4 internal error, 5 a run
  failed its --fail-if criteria, 130 interrupted (run it again to finish).`;

export function jobsOption(text: string | undefined): number {
  const jobs = wholeNumber(text, '--jobs');
  if (jobs === 0n) throw new UsageError('--jobs takes at least 1');
  return jobs === undefined ? Math.max(1, os.availableParallelism?.() ?? os.cpus().length) : Number(jobs);
}

export function queueOption(text: string | undefined): URL | undefined {
  if (text === undefined) return undefined;
  let url: URL;
  try {
    url = new URL(text);
  } catch {
    throw new UsageError(`--queue takes redis://HOST:PORT, not '${text}'`);
  }
  if (url.protocol !== 'redis:' || !url.hostname) throw new UsageError(`--queue takes redis://HOST:PORT, not '${text}'`);
  return url;
}

function sha256(text: string): string {
  return createHash('sha256').update(text).digest('hex');
}

/** `modular2simple batch`: runs the concrete scenarios of a distribution file and writes their results. */
async function batchCommand(argv: string[], io: CliOutput): Promise<number> {
  try {
    return await runBatch(argv, io);
  } catch (error) {
    // The batch runner's own failures (below cli/, which it does not import) are exit 3 as the CLI's.
    if (error instanceof ResultsError || error instanceof NoEsminiError || error instanceof QueuePackagesMissingError)
      throw new UnavailableError(error.message);
    throw error;
  }
}

export const BATCH: CliCommand = { help: BATCH_HELP, run: batchCommand };

async function runBatch(argv: string[], io: CliOutput): Promise<number> {
  const { values, positionals } = parseCommandLine(argv, {
    results: { type: 'string' },
    jobs: { type: 'string' },
    sample: { type: 'string' },
    seed: { type: 'string' },
    duration: { type: 'string' },
    'max-combinations': { type: 'string' },
    queue: { type: 'string' },
    'keep-runs': { type: 'boolean', default: false },
    force: { type: 'boolean', default: false },
    esmini: { type: 'string' },
    'road-path': { type: 'string', multiple: true },
    'scenario-path': { type: 'string', multiple: true },
    quiet: { type: 'boolean', short: 'q', default: false },
    'fail-if': { type: 'string', multiple: true },
    junit: { type: 'string' },
  });
  if (positionals.length !== 1) throw new UsageError('batch takes one distribution file');
  const criteria = (values['fail-if'] ?? []).map((text) => {
    try {
      return parseCriterion(text);
    } catch (error) {
      if (error instanceof CriterionError) throw new UsageError(error.message);
      throw error;
    }
  });
  const junitFile = values.junit === undefined ? undefined : path.resolve(values.junit);
  if (values.results === undefined) throw new UsageError('batch needs --results DIR');
  const sampling = samplingOptions(values);
  const { sample, seed } = sampling;
  const jobs = jobsOption(values.jobs);
  const duration = durationOption(values.duration);
  const queue = queueOption(values.queue);
  if (queue && values['keep-runs']) throw new UsageError('--keep-runs keeps the runs of this machine: it does not go with --queue');

  const distribution = await readDistributionFile(positionals[0]);
  if ('problem' in distribution) throw new InputError(distribution.problem);
  const { path: distributionPath, text: distributionText } = distribution;
  const base = process.cwd();
  const packagedFiles: PackagedFile[] = [];
  const scenarioPath = (values['scenario-path'] ?? []).flatMap(splitScenarioPath);
  const roadPath = (values['road-path'] ?? []).flatMap(splitScenarioPath);
  const loaded = await loadVariations(
    distributionText,
    distributionPath,
    flatteningScenarioLoader(scenarioPath, packagedFiles, roadPath, values.force),
  );
  const printProblems = problemPrinter(loaded, values.quiet, io, base);
  printProblems();
  const variations = loaded.variations;
  if (!variations) return ExitCode.problems;
  // The check run makes, on the ScenarioFile as it is: what esmini would refuse in every run is said once, on its line.
  const problems = await scenarioProblems(variations.scenarioPath, scenarioPath, roadPath);
  for (const problem of problems) if (printed(problem, values.quiet)) io.err(formatProblem(problem, base));
  const errors = problems.filter((problem) => problem.severity === 'error').length;
  const counted = `the scenario has ${errors} error${errors === 1 ? '' : 's'}`;
  const shown = displayRef(diskRef(variations.scenarioPath), base);
  if (errors > 0 && !values.force) {
    io.err(`${shown}: ${counted}; nothing was run (--force runs it anyway)`);
    return ExitCode.problems;
  }
  if (errors > 0) io.err(`${shown}: ${counted}; running anyway (--force)`);
  const chosen = chosenIndices(variations, sampling, positionals[0], 'nothing was run');
  if (chosen instanceof SamplingError) {
    printProblems([samplingProblem(chosen, distributionPath)]);
    return ExitCode.problems;
  }
  const settings: RunSettings = {
    duration,
    // Run Variations runs this command with its setting as --duration, and says so here, for the rows' reasons.
    durationSetBy: process.env.MODULAR2SIMPLE_DURATION_SET_BY || '--duration',
    seed: RUN_DEFAULTS.seed,
    esminiPath: values.esmini,
  };
  if (!queue) {
    const location = locateEsmini(values.esmini);
    if (!location.found) throw new NoEsminiError(location.message);
  }
  const identity: BatchIdentity = {
    distribution: distributionPath,
    distributionSha256: sha256(distributionText),
    scenarioSha256: sha256(variations.scenario.text),
    sample: sample === undefined ? null : sample.toString(),
    seed,
    duration: duration ?? null,
    esminiSeed: settings.seed,
    ...(criteria.length > 0 ? { criteria: criteria.map((each) => each.text).join('; ') } : {}),
  };
  const parameterNames = variedParameters(variations);
  const scenarioFolder = scenarioFolderOf(variations.scenarioPath);
  // esmini gets the catalog directories the flattening found through the scenario path, as run does.
  const catalogStore = storeForInputs(scenarioPath, undefined, [variations.scenarioPath], {}, roadPath);
  const found = await foundCatalogFolders(catalogStore, scenarioFolder, namedPaths(variations.scenario.text).catalogFolders);
  const searchPath = searchPathOf(variations.scenario.text, scenarioFolder, [...found, ...roadPath]);
  const packagedOf = concretePackagedFiles(variations.scenarioPath, scenarioPath, roadPath);
  const catalogs = new CatalogLoader(catalogStore);
  const controllerFilesOf = (text: string) => controllerFilesFrom(text, scenarioFolder, catalogs);
  const plan: BatchPlanView = {
    variations,
    chosen,
    parameterNames,
    searchPath,
    scenarioFolder,
    packagedFiles,
    packagedOf,
    controllerFilesOf,
  };
  const warning = limitWarning(plan, duration);
  if (warning) io.err(`${positionals[0]}: warning: ${warning}`);

  if (queue) {
    const { queueBatch, RedisUnreachableError } = await loadQueueModule(() => import('../batch/queue'));
    try {
      const queued = await queueBatch(queue, plan, identity, values.results, { quiet: values.quiet, io, settings, criteria, junitFile });
      if (queued.ended === 'interrupted') return ExitCode.interrupted;
      if (queued.ended === 'workers-failed') return ExitCode.io;
      return endOfBatch(queued.results, queued.summary, io, values.quiet);
    } catch (error) {
      if (error instanceof RedisUnreachableError)
        throw new ResultsError(error.lostAfterStart ? error.message : `${error.message}; nothing was written`);
      throw error;
    }
  }
  const results = await ResultsFolder.open(path.resolve(values.results), parameterNames, identity, criteria, junitFile);
  if (values['keep-runs']) {
    settings.keepRunsIn = path.join(results.folder, 'runs');
    // Runs are made beside where they are kept: keeping one is then a rename, never a copy across file systems.
    settings.runsFolder = path.join(settings.keepRunsIn, '.running');
  }
  // The roads and catalogs a self-contained package ScenarioFile holds, laid out as its flattened text names them from its folder.
  const packagedFolder =
    packagedFiles.length > 0 || mainOf(variations.scenarioPath).entries.length > 0
      ? await fs.promises.mkdtemp(path.join(os.tmpdir(), 'modular2simple-batch-'))
      : undefined;
  try {
    if (packagedFolder)
      writePackagedFiles(
        packagedFiles.map((file) => ({ path: path.relative(scenarioFolder, file.path), bytes: file.bytes })),
        packagedFolder,
      );
    return await runLocally({ ...plan, packagedFolder }, results, settings, jobs, io, values.quiet);
  } finally {
    if (packagedFolder) await fs.promises.rm(packagedFolder, { recursive: true, force: true });
    // Left only when empty: a run cut short by a kill leaves its folder there, to be looked at.
    if (settings.runsFolder) await fs.promises.rmdir(settings.runsFolder).catch(() => undefined);
  }
}

/** Runs what results.csv lacks on this machine, `jobs` at a time; SIGINT or SIGTERM stop it cleanly. */
async function runLocally(
  plan: BatchPlanView,
  results: ResultsFolder,
  settings: RunSettings,
  jobs: number,
  io: CliOutput,
  quiet: boolean,
): Promise<number> {
  const already = plan.chosen.filter((index) => results.done.has(index.toString())).length;
  const todo = plan.chosen.filter((index) => !results.done.has(index.toString()));
  const stop = new AbortController();
  // Each run in flight listens for the stop: past node's default of 10 (--jobs 11, or a machine with more cores) it warned of a leak.
  setMaxListeners(jobs + 1, stop.signal);
  // A second signal does not wait for the runs in flight to be stopped.
  const onSignal = () => (stop.signal.aborted ? process.exit(ExitCode.interrupted) : stop.abort());
  process.on('SIGINT', onSignal);
  process.on('SIGTERM', onSignal);
  const progress = new Progress(
    todo.length,
    quiet ? undefined : process.stderr.isTTY ? process.stderr : undefined,
    quiet ? () => undefined : io.err,
  );
  const tally = new Tally();
  let failure: unknown;
  let next = 0;
  // A run's scenario is written to a private folder: its paths name the ScenarioFile's roads and catalogs absolutely (SPEC 11.6).
  const kinds = new Map<string, Promise<FileKind>>();
  const kindOf = (diskPath: string): Promise<FileKind> => {
    let known = kinds.get(diskPath);
    if (!known) kinds.set(diskPath, (known = nodeFileSystem.kind(diskPath)));
    return known;
  };
  // Each package file a concrete scenario names through a `$parameter` is written once, before the first run that needs it.
  const namedWritten = new Map<string, Promise<void>>(
    plan.packagedFiles.map((file) => [path.relative(plan.scenarioFolder, file.path), Promise.resolve()]),
  );
  const writeNamedPackaged = async (files: PackagedFile[]): Promise<void> => {
    for (const file of files) {
      const relative = path.relative(plan.scenarioFolder, file.path);
      if (!namedWritten.has(relative))
        namedWritten.set(
          relative,
          Promise.resolve().then(() => writePackagedFiles([{ path: relative, bytes: file.bytes }], plan.packagedFolder as string)),
        );
      await namedWritten.get(relative);
    }
  };
  const unkept = new Set<string>();
  const keptWarned = new Set<string>();
  /** The package files run `index` names, laid out beside its scenario; undefined (told once per file) when one cannot lie there. */
  const keptPackagedFiles = (
    view: BatchPlanView,
    named: PackagedFile[],
    index: string,
  ): { path: string; bytes: Uint8Array }[] | undefined => {
    // The flattening's copies named through a `$parameter` are those of its default value; `named` holds this run's.
    const needed = [...view.packagedFiles.filter((file) => file.namedBy === undefined), ...named].map((file) => ({
      path: path.relative(view.scenarioFolder, file.path),
      bytes: file.bytes,
    }));
    const { files, left } = keptBesideRun(needed);
    for (const file of left.filter((each) => !unkept.has(each))) {
      unkept.add(file);
      io.err(
        `modular2simple: warning: the package file ${file} cannot be kept beside a run's scenario.xosc (it would replace the run's own file or lie outside its folder); run ${index} and those naming it are kept naming the batch's temporary copy, so they do not rerun by themselves`,
      );
    }
    return left.length === 0 ? files : undefined;
  };
  const work = async (): Promise<void> => {
    while (!stop.signal.aborted && next < todo.length) {
      const index = todo[next++];
      const run = concreteRun(plan.variations, index, plan.parameterNames, plan.searchPath);
      if ('discarded' in run) {
        await results.append(run.discarded);
        tally.add(run.discarded);
        progress.tick(run.discarded);
        continue;
      }
      const named = plan.packagedFolder && plan.packagedOf ? await plan.packagedOf(run.text) : [];
      await writeNamedPackaged(named);
      let text = (await rebasedConcreteText(run.text, plan.scenarioFolder, undefined, kindOf)).text;
      // A kept run names a `$parameter` path as written (SPEC 11.6): one relative to the ScenarioFile's folder is said, once.
      if (settings.keepRunsIn && !plan.packagedFolder) {
        for (const warning of (await rebasedConcreteText(run.text, plan.scenarioFolder, settings.keepRunsIn, kindOf)).warnings) {
          if (keptWarned.has(warning)) continue;
          keptWarned.add(warning);
          if (!quiet)
            io.err(
              `modular2simple: warning: kept runs: ${warning}; the runs here found it through esmini's --path, so rerun a kept run with --path ${plan.scenarioFolder}`,
            );
        }
      }
      // A kept run holds the package files it names beside its scenario, which names them there as from the ScenarioFile's folder, so that it reruns by itself.
      const kept = plan.packagedFolder && settings.keepRunsIn ? keptPackagedFiles(plan, named, run.index) : undefined;
      if (plan.packagedFolder && !kept) text = (await rebasedConcreteText(text, plan.packagedFolder, undefined, kindOf)).text;
      // A `$parameter` LogicFile naming a packaged road stays as written (SPEC 11.6): esmini finds the copy by its name there, first.
      const searchPath = plan.packagedFolder ? [plan.packagedFolder, ...run.searchPath] : run.searchPath;
      // Its controller Files named through a `$parameter`, looked up as `run` looks them up (from the ScenarioFile's folder).
      const controllerFilesFrom = await plan.controllerFilesOf?.(run.text);
      const job = { ...run, text, searchPath, files: kept, scenarioFolder: plan.scenarioFolder, controllerFilesFrom };
      const row = await runConcrete(job, settings, stop.signal);
      // Ctrl-C on a terminal reaches esmini too, which then ends early as if by itself: such a run is not a result.
      if (!row || stop.signal.aborted) continue;
      await results.append(row);
      tally.add(row);
      progress.tick(row);
    }
  };
  try {
    await Promise.all(
      Array.from({ length: Math.min(jobs, Math.max(todo.length, 1)) }, () =>
        work().catch((error: unknown) => {
          failure ??= error;
          stop.abort();
        }),
      ),
    );
  } finally {
    process.off('SIGINT', onSignal);
    process.off('SIGTERM', onSignal);
    progress.end();
    await results.finish();
  }
  if (failure) throw failure;
  const summary = tally.summary(already, results.csvFile);
  if (stop.signal.aborted) {
    io.err(`interrupted after ${summary}; ${results.done.size} rows are in ${results.csvFile}: run the same command again to run the rest`);
    return ExitCode.interrupted;
  }
  return endOfBatch(results, summary, io, quiet);
}

/**
 * What a batch whose rows are all written says, local or queued alike, and its exit code: runs that failed in esmini
 * (status error, each with its reason) are exit 3 as esmini failing is for `run`, before runs failing the criteria (5).
 */
function endOfBatch(results: ResultsFolder, summary: string, io: CliOutput, quiet: boolean): number {
  if (!quiet) io.err(`${summary}; results in ${results.csvFile}, ${results.jsonFile} and ${results.htmlFile}`);
  if (results.notDone) io.err(`modular2simple: error: ${results.notDone}`);
  const failed = criteriaFailure(results);
  if (failed) io.err(`modular2simple: ${failed}`);
  if (results.notDone) return ExitCode.io;
  return failed ? ExitCode.criteria : ExitCode.ok;
}
