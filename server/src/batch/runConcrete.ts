import * as fs from 'node:fs';
import * as path from 'node:path';
import { EsminiCsvError, parseEsminiCsv } from '../../../common/src/esminiCsv';
import type { ControllerFilesFrom } from '../esmini/controllerFiles';
import { EsminiTextRunResult, limitSentence, removeRunFolder, runScenarioText } from '../esmini/run';
import { esminiMessageSeverity, withoutRunFolder } from '../esmini/messages';
import { csvNamingScenario } from '../esmini/process';
import { trajectoryMetrics } from './metrics';
import { collisionsIn } from '../esmini/log';
import type { BatchRow, RunStatus } from './results';

/** One concrete scenario, as a batch runs it: everything a run needs, on this machine. */
export interface ConcreteRun {
  index: string;
  /** Plain OpenSCENARIO text. */
  text: string;
  /** The varied parameters' values, by name. */
  parameters: Record<string, string>;
  /** Absolute folders for road files and catalogs, in order. */
  searchPath: string[];
  /** Files written beside the scenario in its run folder, at paths relative to it (the package files a kept run names). */
  files?: readonly { path: string; bytes: Uint8Array }[];
  /** The folder the ScenarioFile's relative paths start from: esmini's words naming the run's private folder are said from there. */
  scenarioFolder?: string;
  /** A local run: its controller Files named through a `$parameter` are handed as the files they name from the ScenarioFile's folder, as `run` hands them. */
  controllerFilesFrom?: ControllerFilesFrom;
}

export interface RunSettings {
  /** Simulated seconds at most, as the user set it; undefined: each scenario's own end. */
  duration?: number;
  /** Where the user sets `duration` ('--duration', an editor setting), which a row's reason names (EsminiRunOptions.durationSetBy). */
  durationSetBy?: string;
  /** esmini's seed. */
  seed: number;
  esminiPath?: string;
  runsFolder?: string;
  /**
   * Where each run's folder is kept, as `<index>/` (scenario.xosc, trajectories.csv, esmini.log), instead of
   * removed; on the same file system as `runsFolder`, so that keeping it is a rename.
   */
  keepRunsIn?: string;
}

export class NoEsminiError extends Error {}

/**
 * Runs one concrete scenario in esmini headless, as `run` does (fixed step and seed, bounded by `duration`),
 * with esmini's collision detection on, and makes its result row. Undefined when it was cancelled.
 * Throws NoEsminiError when there is no esmini to run it with.
 */
export async function runConcrete(job: ConcreteRun, settings: RunSettings, cancel?: AbortSignal): Promise<BatchRow | undefined> {
  const result = await runScenarioText(job.text, job.searchPath, {
    esminiPath: settings.esminiPath,
    duration: settings.duration,
    durationSetBy: settings.durationSetBy,
    seed: settings.seed,
    collision: true,
    runsFolder: settings.runsFolder,
    cancel,
    files: job.files,
    controllerFilesFrom: job.controllerFilesFrom,
  });
  const kept =
    settings.keepRunsIn && result.runFolder && result.outcome !== 'cancelled' ? path.join(settings.keepRunsIn, job.index) : undefined;
  const runFolder = result.runFolder;
  // esmini ran the text in a private folder, removed or moved after the run: its words name what that folder stood for.
  const said = (text: string): string =>
    !runFolder || !job.scenarioFolder
      ? text
      : withoutRunFolder(
          text,
          runFolder,
          job.scenarioFolder,
          new Map([[path.join(runFolder, 'scenario.xosc'), kept ? path.join(kept, 'scenario.xosc') : `concrete scenario ${job.index}`]]),
        );
  const words = { ...result, message: said(result.message), messages: result.messages.map((each) => ({ ...each, text: said(each.text) })) };
  try {
    if (result.outcome === 'no-esmini') throw new NoEsminiError(result.message);
    if (result.outcome === 'cancelled') return undefined;
    const status = runStatusOf(result);
    let message = words.message;
    let metrics = {
      ego: undefined as string | undefined,
      minDistance: undefined as number | undefined,
      minTtc: undefined as number | undefined,
    };
    if (result.csvFile) {
      try {
        metrics = trajectoryMetrics(parseEsminiCsv(await fs.promises.readFile(result.csvFile, 'latin1')), result.duration);
      } catch (error) {
        if (!(error instanceof EsminiCsvError)) throw error;
        message += `; its CSV log cannot be read: ${error.message}`;
      }
    }
    const collisions = collisionsIn(result.messages);
    return {
      index: job.index,
      status,
      collision: collisions.length > 0,
      min_distance_m: metrics.minDistance ?? null,
      min_ttc_s: metrics.minTtc ?? null,
      end_time_s: result.simulatedTime ?? null,
      parameters: job.parameters,
      ego: metrics.ego ?? null,
      collisions,
      message,
      reason: reasonOf(status, words, settings.durationSetBy),
      messages: words.messages.map((each) => ({ level: each.level, time: each.time ?? null, text: each.text })),
    };
  } finally {
    if (kept && result.runFolder) keepRunFolder(result.runFolder, result.log, kept);
    else removeRunFolder(result);
  }
}

/**
 * A run's status: `ok` when the scenario ended by itself; `limit` when the limit the user set stopped it first, or
 * the default length of a scenario whose StopTrigger has no condition; `timeout` when it hung (no progress) or ran
 * away (its CSV past the size bound, or an hour simulated with no limit set and its StopTrigger not fired); `error` when esmini reported an error or did not run it.
 */
export function runStatusOf(result: EsminiTextRunResult): RunStatus {
  if (result.outcome === 'failed' && result.end === 'killed') return 'timeout';
  if (result.outcome !== 'ok') return 'error';
  if (result.end === 'interrupted' && !result.reachedLimit) return 'timeout';
  if (result.reachedLimit) return result.limitKind === 'runaway' ? 'timeout' : 'limit';
  return 'ok';
}

/**
 * Why a run of `status` is not `ok` (BatchRow.reason): esmini's first error when it reported some (a run it refused
 * says so, with esmini's message), what stopped a run cut short, the limit that ended it; empty when ok.
 */
export function reasonOf(status: RunStatus, result: EsminiTextRunResult, durationSetBy?: string): string {
  if (status === 'ok' || status === 'discarded') return '';
  if (status === 'error' && result.outcome === 'errors') {
    const errors = result.messages.filter((message) => esminiMessageSeverity(message) === 'error');
    const first = errors[0];
    const when = first?.time === undefined ? '' : ` at ${first.time} s`;
    const count = errors.length === 1 ? 'an error' : `${errors.length} errors, the first`;
    return `esmini reported ${count}${when}: ${first?.text ?? 'see its log'}`;
  }
  // esmini did not run it, could not be started, hung, or ended without saying why: the run's message says which.
  if (result.outcome !== 'ok' && result.outcome !== 'errors') return result.message;
  if (result.reachedLimit) return limitSentence({ seconds: result.duration, kind: result.limitKind, setBy: durationSetBy });
  return result.stopReason ? `esmini was stopped: ${result.stopReason}` : result.message;
}

/** The files of a kept run's folder (keepRunFolder) that no package file may replace. */
const KEPT_RUN_OWN_FILES = new Set(['scenario.xosc', 'trajectories.csv', 'esmini.log']);

/**
 * Of package files at paths relative to the scenario's folder, those a kept run's folder can hold beside its scenario, so that
 * the kept run names them there and reruns by itself; `left`: those that would replace one of the run's own files or lie
 * outside its folder.
 */
export function keptBesideRun(files: readonly { path: string; bytes: Uint8Array }[]): {
  files: { path: string; bytes: Uint8Array }[];
  left: string[];
} {
  const beside: { path: string; bytes: Uint8Array }[] = [];
  const left: string[] = [];
  for (const file of files) {
    const relative = path.normalize(file.path);
    const outside = path.isAbsolute(relative) || relative === '..' || relative.startsWith(`..${path.sep}`);
    if (outside || KEPT_RUN_OWN_FILES.has(relative)) left.push(file.path);
    else if (!beside.some((known) => known.path === relative)) beside.push({ path: relative, bytes: file.bytes });
  }
  return { files: beside, left };
}

/** Moves a run's folder to `target` (replacing a run kept there before), with esmini's log beside its CSV. */
function keepRunFolder(runFolder: string, log: string, target: string): void {
  fs.writeFileSync(path.join(runFolder, 'esmini.log'), log);
  // The CSV's header named the run's private folder, which the rename removes: it names the kept scenario.
  const csv = path.join(runFolder, 'trajectories.csv');
  if (fs.existsSync(csv)) fs.writeFileSync(csv, csvNamingScenario(fs.readFileSync(csv, 'utf8'), path.join(target, 'scenario.xosc')));
  fs.rmSync(target, { recursive: true, force: true });
  fs.renameSync(runFolder, target);
}
