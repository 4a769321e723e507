import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { Flattener, FlatSource } from '../core/flatten';
import { Problem } from '../core/problems';
import { SourceRef } from '../core/sources';
import { attribute, descendants } from '../core/xml';
import { locateEsmini } from './locate';
import { EsminiLogMessage, parseEsminiLog } from './log';
import { EsminiProblem, mapEsminiMessages } from './messages';
import { EsminiEnd, EsminiProcessResult, lastCsvTime, makeRunFolder, runEsminiProcess } from './process';
import { withTimeLimit } from './timeLimit';

export const RUN_DEFAULTS = {
  /** Simulated seconds. */
  duration: 30,
  /** Seconds per step, decoupled from the clock. */
  timeStep: 0.05,
  seed: 1,
  wallTimeoutMs: 60_000,
  maxCsvBytes: 200 * 1024 * 1024,
  maxOutputChars: 8 * 1024 * 1024,
} as const;

export interface EsminiRunOptions {
  /** The configured esmini (setting or --esmini); PATH when empty. */
  esminiPath?: string;
  /** Base of a relative esminiPath (the workspace folder, or the working directory). */
  base?: string;
  /** Extra folders for road files (and catalogs), after the scenario's own folders. */
  roadPath?: string[];
  duration?: number;
  timeStep?: number;
  seed?: number;
  wallTimeoutMs?: number;
  /** esmini's global collision detection (`--collision`): each collision is logged as a warning. */
  collision?: boolean;
  /** Parent of the private run folder; the system's temporary folder by default. */
  runsFolder?: string;
  onOutput?: (text: string) => void;
  cancel?: AbortSignal;
}

/**
 * What a run produced. `csvFile` is esmini's own CSV (`--csv_logger`): 6 header lines, a column
 * line, then one row per step; rows with TimeStamp above `duration` may follow when the run was
 * interrupted, and are to be dropped. The files live in `runFolder` until the caller removes it.
 */
export interface EsminiRunResult {
  outcome:
    /** esmini ran and reported no error (warnings may be in `problems`). */
    | 'ok'
    /** esmini ran, or failed to load the scenario, and reported at least one error. */
    | 'errors'
    /** The scenario could not be flattened: nothing was run; see `flattenProblems`. */
    | 'not-flattened'
    /** No esmini: `message` says how to get it. */
    | 'no-esmini'
    /** esmini could not be started, or was killed. */
    | 'failed'
    | 'cancelled';
  message: string;
  esmini?: string;
  args?: string[];
  runFolder?: string;
  /** The flattened scenario as handed to esmini (with the added time limit). */
  scenarioFile?: string;
  csvFile?: string;
  /** esmini's stdout and stderr. */
  log: string;
  end?: EsminiEnd;
  exitCode?: number | null;
  /** Simulated seconds covered by the CSV (its last TimeStamp, at most `duration`). */
  simulatedTime?: number;
  duration: number;
  timeStep: number;
  seed: number;
  wallMs: number;
  problems: EsminiProblem[];
  flattenProblems: Problem[];
}

/** The folder a scenario's relative file names start from: the main file's folder, or the package's. */
export function sourceFolderOf(ref: SourceRef): string {
  return path.dirname(ref.disk);
}

/** Catalog folders that the scenario names, resolved against its source folder (esmini would use the temporary file's). */
export function catalogFolders(source: FlatSource, sourceFolder: string): string[] {
  const root = (source.model ?? source.original)?.document.root;
  const locations = root?.children.find((child) => child.name === 'CatalogLocations');
  if (!locations) return [];
  const folders: string[] = [];
  for (const element of descendants(locations)) {
    if (element.name !== 'Directory') continue;
    const value = attribute(element, 'path')?.value;
    if (value && !value.includes('$')) folders.push(path.resolve(sourceFolder, value));
  }
  return folders;
}

function unique(items: string[]): string[] {
  return [...new Set(items)];
}

/**
 * Flattens `main` as the flattener's store sees it (unsaved text included when the store has
 * overlays), writes it to a private folder and runs esmini headless on it with a fixed step and seed
 * for a bounded simulated time. Never throws for a bad scenario or a missing esmini.
 */
export async function runScenario(flattener: Flattener, main: SourceRef, options: EsminiRunOptions = {}): Promise<EsminiRunResult> {
  const started = Date.now();
  const duration = options.duration ?? RUN_DEFAULTS.duration;
  const timeStep = options.timeStep ?? RUN_DEFAULTS.timeStep;
  const seed = options.seed ?? RUN_DEFAULTS.seed;
  const base = { log: '', duration, timeStep, seed, problems: [] as EsminiProblem[], flattenProblems: [] as Problem[] };
  const elapsed = () => Date.now() - started;
  if (!(duration > 0) || !Number.isFinite(duration)) throw new Error(`the duration must be a positive number of seconds, not ${duration}`);

  const location = locateEsmini(options.esminiPath, options.base);
  if (!location.found) return { ...base, outcome: 'no-esmini', message: location.message, wallMs: elapsed() };

  const flat = await flattener.flatten(main);
  const flattenProblems = flat.problems;
  if (flat.text === undefined) {
    const errors = flattenProblems.filter((problem) => problem.severity === 'error').length;
    return { ...base, flattenProblems, outcome: 'not-flattened', esmini: location.program, message: `the scenario has ${errors} error${errors === 1 ? '' : 's'} and cannot be flattened; nothing was run`, wallMs: elapsed() };
  }
  const limited = withTimeLimit(flat.text, duration);
  if (limited === undefined) {
    return { ...base, flattenProblems, outcome: 'not-flattened', esmini: location.program, message: 'the scenario has no <Storyboard>, so esmini has nothing to run', wallMs: elapsed() };
  }

  const sourceFolder = sourceFolderOf(main);
  const searchPath = unique([sourceFolder, ...catalogFolders(flat.source, sourceFolder), ...(options.roadPath ?? []).map((folder) => path.resolve(options.base ?? process.cwd(), folder))]);
  const ran = await runLimitedText(location.program, limited, searchPath, options, timeStep, seed, duration);
  const problems = mapEsminiMessages(parseEsminiLog(ran.run.output), flat.source, main);
  const errors = problems.filter((problem) => problem.severity === 'error').length;
  return { ...base, flattenProblems, problems, ...ran.common, esmini: location.program, wallMs: elapsed(), ...outcomeOf(ran, errors, problems.length - errors) };
}

/** A plain scenario's run (`runScenarioText`): esmini's messages as it printed them, placed on no source line. */
export type EsminiTextRunResult = Omit<EsminiRunResult, 'problems' | 'flattenProblems'> & { messages: EsminiLogMessage[] };

/**
 * Runs plain OpenSCENARIO text (already flat, such as a concrete scenario of a distribution) as `runScenario`
 * runs a flattened file: the same time limit, step, seed and bounds. `searchPath`: absolute folders for roads
 * and catalogs, in order. Never throws for a bad scenario or a missing esmini.
 */
export async function runScenarioText(text: string, searchPath: string[], options: EsminiRunOptions = {}): Promise<EsminiTextRunResult> {
  const started = Date.now();
  const duration = options.duration ?? RUN_DEFAULTS.duration;
  const timeStep = options.timeStep ?? RUN_DEFAULTS.timeStep;
  const seed = options.seed ?? RUN_DEFAULTS.seed;
  const base = { log: '', duration, timeStep, seed, messages: [] as EsminiLogMessage[] };
  const elapsed = () => Date.now() - started;
  if (!(duration > 0) || !Number.isFinite(duration)) throw new Error(`the duration must be a positive number of seconds, not ${duration}`);
  const location = locateEsmini(options.esminiPath, options.base);
  if (!location.found) return { ...base, outcome: 'no-esmini', message: location.message, wallMs: elapsed() };
  const limited = withTimeLimit(text, duration);
  if (limited === undefined) return { ...base, outcome: 'not-flattened', esmini: location.program, message: 'the scenario has no <Storyboard>, so esmini has nothing to run', wallMs: elapsed() };
  const roadPath = (options.roadPath ?? []).map((folder) => path.resolve(options.base ?? process.cwd(), folder));
  const ran = await runLimitedText(location.program, limited, unique([...searchPath, ...roadPath]), options, timeStep, seed, duration);
  const messages = parseEsminiLog(ran.run.output);
  const errors = messages.filter((message) => message.level === 'error').length;
  return { ...base, messages, ...ran.common, esmini: location.program, wallMs: elapsed(), ...outcomeOf(ran, errors, messages.length - errors) };
}

interface LimitedRun {
  run: EsminiProcessResult;
  common: Pick<EsminiRunResult, 'args' | 'runFolder' | 'scenarioFile' | 'csvFile' | 'log' | 'end' | 'exitCode' | 'simulatedTime'>;
}

/** Writes the time-limited text to a private folder and runs esmini on it. */
async function runLimitedText(program: string, limited: string, searchPath: string[], options: EsminiRunOptions, timeStep: number, seed: number, duration: number): Promise<LimitedRun> {
  const runFolder = makeRunFolder(options.runsFolder ?? path.join(os.tmpdir(), 'modular2simple-esmini'));
  const scenarioFile = path.join(runFolder, 'scenario.xosc');
  const csvFile = path.join(runFolder, 'trajectories.csv');
  fs.writeFileSync(scenarioFile, limited);
  const run = await runEsminiProcess({
    program,
    scenarioFile,
    workDir: runFolder,
    csvFile,
    searchPath,
    timeStep,
    seed,
    duration,
    collision: options.collision,
    wallTimeoutMs: options.wallTimeoutMs ?? RUN_DEFAULTS.wallTimeoutMs,
    maxCsvBytes: RUN_DEFAULTS.maxCsvBytes,
    maxOutputChars: RUN_DEFAULTS.maxOutputChars,
    onOutput: options.onOutput,
    cancel: options.cancel,
  });
  const hasCsv = fs.existsSync(csvFile);
  const lastTime = hasCsv ? lastCsvTime(csvFile) : undefined;
  return {
    run,
    common: {
      args: run.args,
      runFolder,
      scenarioFile,
      csvFile: hasCsv ? csvFile : undefined,
      log: run.output,
      end: run.end,
      exitCode: run.exitCode,
      simulatedTime: lastTime === undefined ? undefined : Math.min(lastTime, duration),
    },
  };
}

/** How a run ended, in a word and a sentence, from how the process ended and how many errors esmini reported. */
function outcomeOf(ran: LimitedRun, errors: number, warnings: number): Pick<EsminiRunResult, 'outcome' | 'message'> {
  const { run, common } = ran;
  const counts = `${errors} error${errors === 1 ? '' : 's'}, ${warnings} warning${warnings === 1 ? '' : 's'}`;
  if (run.end === 'cancelled') return { outcome: 'cancelled', message: 'the run was cancelled' };
  if (run.end === 'not-started' || run.end === 'killed') return { outcome: 'failed', message: `esmini ${run.reason ?? 'failed'}` };
  if (run.exitCode !== 0 && run.end === 'exited' && errors === 0) {
    return { outcome: 'failed', message: `esmini ended with exit code ${run.exitCode} without an error message; see its log` };
  }
  const covered =
    common.simulatedTime === undefined ? 'no trajectory: esmini placed no entity (each needs a position in Init, such as a TeleportAction)' : `${common.simulatedTime.toFixed(2)} s simulated`;
  return { outcome: errors > 0 ? 'errors' : 'ok', message: `esmini: ${counts}; ${covered} (${(run.wallMs / 1000).toFixed(2)} s)` };
}

/** Removes a run's private folder (its CSV and scenario copy). */
export function removeRunFolder(result: Pick<EsminiRunResult, 'runFolder'>): void {
  if (result.runFolder) fs.rmSync(result.runFolder, { recursive: true, force: true });
}
