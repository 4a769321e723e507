import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import type { CancellationToken } from 'vscode-languageserver/node';
import { writeFileAtomic } from '../../../common/src/atomic';
import { carlaPython } from '../../../common/src/paths';
import type { CheckInScenarioRunnerParams, CheckInScenarioRunnerResult, ProblemSummary } from '../../../common/src/protocol';
import { HarnessRun, HarnessVerdict, runHarness } from '../carla/harness';
import { CARLA_TOWNS, CarlaExportOptionError, exportForCarla } from '../core/export/carla';
import type { Place } from '../core/export/tree';
import { SourceRef } from '../core/sources';
import { Workspace } from '../workspace';
import { carlaExportOptions, lossSummary } from './carlaExport';
import { invalidParams, refOf } from './commands';

/** Seconds a check may take before it is stopped (ScenarioRunner imports in 2 to 5 s and builds a tree in under 1 s when idle). */
export const DEFAULT_TIME_LIMIT_SECONDS = 120;

const STAGE_WORDS: Record<NonNullable<HarnessVerdict['stage']>, string> = {
  schema: 'validating it against its OpenSCENARIO 1.0 schema',
  version: 'checking its version',
  configuration: 'reading its configuration (parameters, catalogs, road, actors)',
  build: 'building its behaviour tree',
};

function scenarioRunnerFolder(workspace: Workspace, setting: string | undefined): string | undefined {
  if (!setting?.trim()) return undefined;
  return path.resolve(workspace.folders[0] ?? process.cwd(), setting.trim());
}

/** What stands in the folder instead of ScenarioRunner; undefined when it is one. */
function notScenarioRunner(folder: string): string | undefined {
  if (!fs.existsSync(folder)) return `${folder} does not exist`;
  if (!fs.statSync(folder).isDirectory()) return `${folder} is not a folder`;
  if (!fs.existsSync(path.join(folder, 'scenario_runner.py')))
    return `${folder} is not a ScenarioRunner folder: it has no scenario_runner.py`;
  if (!fs.existsSync(path.join(folder, 'srunner', 'scenarioconfigs', 'openscenario_configuration.py')))
    return `${folder} is not a ScenarioRunner folder: it has no srunner/scenarioconfigs/openscenario_configuration.py`;
  return undefined;
}

/**
 * *Check in CARLA ScenarioRunner*: exports the scenario (the editor's text, `modular2simple.carla.release`'s facts)
 * into a private folder, has ScenarioRunner's own loader read it and build its behaviour tree
 * (server/python/scenario_runner_check.py, against a stand-in for the CARLA server), and places what it raised at
 * the source line of the element it failed on. The folder goes afterwards.
 */
export async function checkInScenarioRunner(
  workspace: Workspace,
  params: CheckInScenarioRunnerParams | undefined,
  token?: CancellationToken,
): Promise<CheckInScenarioRunnerResult> {
  const ref = await refOf(workspace, params?.uri);
  const name = path.basename(ref.entries.at(-1) ?? ref.disk);
  const timeLimitSeconds = params?.timeLimitSeconds ?? DEFAULT_TIME_LIMIT_SECONDS;
  if (!(timeLimitSeconds > 0) || !Number.isFinite(timeLimitSeconds))
    throw invalidParams(`the time limit must be a positive number of seconds, not ${String(params?.timeLimitSeconds)}`);
  const folder = scenarioRunnerFolder(workspace, params?.scenarioRunnerPath);
  const python = carlaPython(params?.python, folder ?? '');
  const notRun = (outcome: CheckInScenarioRunnerResult['outcome'], message: string, extra: Partial<CheckInScenarioRunnerResult> = {}) => ({
    outcome,
    message,
    problems: [],
    log: '',
    ...extra,
  });
  if (!folder)
    return notRun(
      'no-scenario-runner',
      'Check in CARLA ScenarioRunner: set modular2simple.carla.scenarioRunnerPath to the folder of CARLA ScenarioRunner (the clone of carla-simulator/scenario_runner that holds scenario_runner.py); nothing was checked.',
    );
  const wrong = notScenarioRunner(folder);
  if (wrong)
    return notRun(
      'no-scenario-runner',
      `Check in CARLA ScenarioRunner: ${wrong}. Set modular2simple.carla.scenarioRunnerPath to the folder that holds scenario_runner.py; nothing was checked.`,
    );

  const runFolder = fs.mkdtempSync(path.join(os.tmpdir(), 'modular2simple-carla-check-'));
  const abort = new AbortController();
  const cancelled = token?.onCancellationRequested(() => abort.abort());
  try {
    const exportFile = path.join(runFolder, name.replace(/\.(xosc|mosc)$/i, '') + '.carla.xosc');
    let exported;
    try {
      exported = await exportForCarla(workspace.store, ref, carlaExportOptions(workspace, ref, exportFile));
    } catch (error) {
      if (error instanceof CarlaExportOptionError) return notRun('not-exported', `Check in CARLA ScenarioRunner: ${error.message}`);
      throw error;
    }
    if (exported.text === undefined)
      return notRun(
        'not-exported',
        `Check in CARLA ScenarioRunner: ${name} was not exported (with the facts of ScenarioRunner ${workspace.settings.carlaRelease}, setting modular2simple.carla.release), so ScenarioRunner did not see it: ${exported.refused ?? 'refused'}`,
        {
          problems: exported.losses.filter((loss) => loss.kind === 'refused').map((loss) => lossSummary(workspace, loss)),
        },
      );
    for (const file of exported.files ?? []) {
      await fs.promises.mkdir(path.dirname(file.path), { recursive: true });
      await writeFileAtomic(file.path, file.bytes);
    }
    await writeFileAtomic(exportFile, exported.text);
    const run = await runHarness({
      python,
      scenarioRunner: folder,
      scenario: exportFile,
      towns: CARLA_TOWNS,
      timeLimitMs: timeLimitSeconds * 1000,
      cancel: abort.signal,
    });
    return reportRun(workspace, ref, run, {
      name,
      folder,
      python,
      timeLimitSeconds,
      placeAt: exported.placeAt ?? (() => undefined),
      losses: exported.losses.length,
    });
  } finally {
    cancelled?.dispose();
    fs.rmSync(runFolder, { recursive: true, force: true });
  }
}

interface RunContext {
  name: string;
  folder: string;
  python: string;
  timeLimitSeconds: number;
  placeAt: (index: number) => Place | undefined;
  losses: number;
}

function reportRun(workspace: Workspace, ref: SourceRef, run: HarnessRun, context: RunContext): CheckInScenarioRunnerResult {
  const { name, folder, python } = context;
  if (run.kind === 'cancelled')
    return {
      outcome: 'failed',
      message: 'Check in CARLA ScenarioRunner: cancelled; nothing was checked.',
      problems: [],
      log: '',
      command: run.command,
    };
  if (run.kind === 'no-python')
    return {
      outcome: 'no-python',
      message: `Check in CARLA ScenarioRunner: ${run.message}. Set modular2simple.carla.python to a Python 3 that has ScenarioRunner's requirements (pip install -r ${path.join(folder, 'requirements.txt')}); nothing was checked.`,
      problems: [],
      log: run.message,
      command: run.command,
    };
  if (run.kind === 'timeout')
    return {
      outcome: 'timeout',
      message: `Check in CARLA ScenarioRunner: no answer within ${context.timeLimitSeconds} s (modular2simple.carla.timeLimit); the check was stopped and its processes killed, nothing was checked.`,
      problems: [],
      log: run.output,
      command: run.command,
    };
  if (run.kind === 'no-verdict')
    return {
      outcome: 'failed',
      message: `Check in CARLA ScenarioRunner: ${python} ended (${run.signal ?? `exit code ${String(run.code)}`}) without a verdict: ${lastLine(run.output) || 'it printed nothing'}. Is it a Python 3? Nothing was checked.`,
      problems: [],
      log: run.output,
      command: run.command,
    };
  const verdict = run.verdict;
  const log = [`${run.command.join(' ')}`, ...(verdict.warnings ?? []).map((line) => `ScenarioRunner: ${line}`), run.output]
    .filter(Boolean)
    .join('\n');
  const base = { log, command: run.command, problems: [] as ProblemSummary[] };
  switch (verdict.status) {
    case 'not-scenario-runner':
      return {
        ...base,
        outcome: 'no-scenario-runner',
        message: `Check in CARLA ScenarioRunner: ${verdict.reason ?? folder}. Set modular2simple.carla.scenarioRunnerPath to a ScenarioRunner folder; nothing was checked.`,
      };
    case 'requirements':
      return {
        ...base,
        outcome: 'requirements',
        message: `Check in CARLA ScenarioRunner: the Python ${python} lacks ScenarioRunner's requirements (${verdict.reason ?? 'an import failed'}). Install them (${python} -m pip install -r ${path.join(folder, 'requirements.txt')}) or set modular2simple.carla.python to a Python that has them; nothing was checked.`,
      };
    case 'error':
      return {
        ...base,
        outcome: 'failed',
        message: `Check in CARLA ScenarioRunner: the harness failed (${verdict.reason ?? 'no reason'}); nothing was checked. See the output for its stack.`,
        log: `${log}\n${verdict.traceback ?? ''}`,
      };
    case 'built': {
      const losses =
        context.losses > 0
          ? ` (the export names ${context.losses} loss${context.losses === 1 ? '' : 'es'}: Export for CARLA… shows them)`
          : '';
      return {
        ...base,
        outcome: 'built',
        message: `ScenarioRunner (${folder}) loaded the export of ${name} and built its behaviour tree (${verdict.tree_nodes ?? '?'} nodes${verdict.town ? `, on ${verdict.town}` : ''})${losses}.`,
      };
    }
    case 'refused': {
      const stage = verdict.stage ? STAGE_WORDS[verdict.stage] : 'loading it';
      const at = verdict.where ? ` (at ${verdict.where})` : '';
      const place = placeOf(context.placeAt, verdict.element?.index);
      const element = verdict.element ? `<${verdict.element.tag}${verdict.element.name ? ` name="${verdict.element.name}"` : ''}>: ` : '';
      const problem: ProblemSummary = {
        uri: workspace.uriOf(place?.source ?? ref),
        line: place?.range.start.line ?? 0,
        character: place?.range.start.character ?? 0,
        ...(place ? { end: { line: place.range.end.line, character: place.range.end.character } } : {}),
        severity: 'error',
        message: `ScenarioRunner refused it while ${stage}: ${element}${verdict.reason ?? 'no reason given'}${at}`,
        code: 'scenario-runner',
      };
      return {
        ...base,
        outcome: 'refused',
        problems: [problem],
        message: `ScenarioRunner refused the export of ${name} while ${stage}: ${verdict.reason ?? 'no reason given'}${at}.`,
      };
    }
  }
}

/** Where the export's element N came from; the root's place when ScenarioRunner named no element. */
function placeOf(placeAt: (index: number) => Place | undefined, index: number | null | undefined): Place | undefined {
  return (index !== null && index !== undefined ? placeAt(index) : undefined) ?? placeAt(0);
}

function lastLine(text: string): string {
  return text.trim().split('\n').at(-1)?.trim() ?? '';
}
