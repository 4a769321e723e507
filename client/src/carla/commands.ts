import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { withNotificationProgress } from '../notificationProgress';
import { PACKAGE_SCHEME, type CheckInScenarioRunnerResult } from '../../../common/src/protocol';
import type { CommandReporter } from '../commands';
import { commandTargets } from '../commands';
import type { ServerCommandClient } from '../languageClient';
import { PlacedDiagnostics } from '../placedDiagnostics';
import { problemLine } from '../placed';
import {
  missingRunSetting,
  reachable,
  runEndMessage,
  scenarioRunnerCommandLine,
  startProblem,
  unreachableMessage,
  type CarlaRunSettings,
} from './run';

export const CHECK_IN_SCENARIO_RUNNER_COMMAND = 'modular2simple.checkInScenarioRunner';
export const RUN_IN_CARLA_COMMAND = 'modular2simple.runInCarla';
const SETTINGS = 'modular2simple.carla';
const REACH_TIMEOUT_MS = 5000;

function carlaSettings(scope: vscode.Uri): CarlaRunSettings & { timeLimit: number } {
  const settings = vscode.workspace.getConfiguration(SETTINGS, scope);
  const folder = vscode.workspace.getWorkspaceFolder(scope) ?? vscode.workspace.workspaceFolders?.[0];
  const configured = settings.get<string>('scenarioRunnerPath')?.trim() ?? '';
  const base = folder?.uri.scheme === 'file' ? folder.uri.fsPath : process.cwd();
  return {
    host: settings.get<string>('host') ?? '',
    port: settings.get<number>('port') ?? 2000,
    scenarioRunner: configured ? path.resolve(base, configured) : '',
    python: settings.get<string>('python')?.trim() || 'python3',
    timeLimit: settings.get<number>('timeLimit') ?? 120,
  };
}

function scenarioTarget(clicked: unknown, selected: unknown, action: string): vscode.Uri | undefined {
  const [target] = commandTargets(clicked, selected);
  if (!target || (target.scheme !== 'file' && target.scheme !== PACKAGE_SCHEME)) {
    void vscode.window.showErrorMessage(`${action}: open or select a .xosc, a main.xosc, a .mosc or an unpacked package folder first.`);
    return undefined;
  }
  return target;
}

function openSettings(setting: string): void {
  void vscode.commands.executeCommand('workbench.action.openSettings', `${SETTINGS}.${setting}`);
}

const SETTING_OF: Partial<Record<CheckInScenarioRunnerResult['outcome'], string>> = {
  'no-scenario-runner': 'scenarioRunnerPath',
  'no-python': 'python',
  requirements: 'python',
  timeout: 'timeLimit',
};

/**
 * *Check in CARLA ScenarioRunner* and *Run in CARLA*: ScenarioRunner's messages land on the source lines (their own
 * diagnostic collection, replaced by the next check), its whole output in an output channel.
 */
export class CarlaCommands implements vscode.Disposable {
  readonly diagnostics = new PlacedDiagnostics('scenario-runner', 'ScenarioRunner');
  readonly output = vscode.window.createOutputChannel('Modular2Simple: ScenarioRunner');
  private readonly disposables: vscode.Disposable[] = [];
  /** The last check's result, for the extension's tests. */
  last: CheckInScenarioRunnerResult | undefined;

  constructor(
    private readonly server: ServerCommandClient,
    private readonly reporter: CommandReporter,
    private readonly exportLosses: PlacedDiagnostics,
    private readonly storage: vscode.Uri,
  ) {
    this.disposables.push(
      this.diagnostics,
      this.output,
      vscode.commands.registerCommand(CHECK_IN_SCENARIO_RUNNER_COMMAND, (clicked: unknown, selected: unknown) =>
        this.check(clicked, selected),
      ),
      vscode.commands.registerCommand(RUN_IN_CARLA_COMMAND, (clicked: unknown, selected: unknown) => this.run(clicked, selected)),
    );
  }

  async check(clicked: unknown, selected?: unknown): Promise<CheckInScenarioRunnerResult | undefined> {
    const action = 'Check in CARLA ScenarioRunner';
    const target = scenarioTarget(clicked, selected, action);
    if (!target) return undefined;
    const settings = carlaSettings(target);
    this.diagnostics.clear();
    let result: CheckInScenarioRunnerResult;
    try {
      const name = path.posix.basename(target.path);
      result = await withNotificationProgress(`Checking ${name} in CARLA ScenarioRunner`, (_progress, token) =>
        this.server.checkInScenarioRunner(
          {
            uri: target.toString(),
            scenarioRunnerPath: settings.scenarioRunner,
            python: settings.python,
            timeLimitSeconds: settings.timeLimit,
          },
          token,
        ),
      );
    } catch (error) {
      this.output.appendLine(`${action} failed: ${(error as Error).stack ?? String(error)}`);
      const choice = await vscode.window.showErrorMessage(`${action} failed: ${(error as Error).message}`, 'Show Log');
      if (choice) this.output.show(true);
      return undefined;
    }
    this.last = result;
    this.diagnostics.replace(result.problems);
    this.output.appendLine(`[${new Date().toISOString()}] ${target.toString(true)}: ${result.outcome}: ${result.message}`);
    for (const problem of result.problems) this.output.appendLine(`  ${problemLine(problem)}`);
    if (result.log) this.output.appendLine(result.log);
    this.tell(result);
    return result;
  }

  private tell(result: CheckInScenarioRunnerResult): void {
    const setting = SETTING_OF[result.outcome];
    if (result.outcome === 'built') {
      void vscode.window.showInformationMessage(result.message);
    } else if (setting) {
      void vscode.window.showWarningMessage(result.message, 'Open Settings', 'Show Log').then((choice) => {
        if (choice === 'Open Settings') openSettings(setting);
        if (choice === 'Show Log') this.output.show(true);
      });
    } else {
      const first = result.problems[0];
      void vscode.window.showErrorMessage(result.message, ...(first ? ['Go to Problem'] : []), 'Show Log').then(async (choice) => {
        if (choice === 'Show Log') this.output.show(true);
        if (choice === 'Go to Problem' && first)
          await vscode.window.showTextDocument(vscode.Uri.parse(first.uri), {
            selection: new vscode.Range(first.line, first.character, first.line, first.character),
          });
      });
    }
  }

  /** Exports into the extension's storage and starts ScenarioRunner on it in a task whose end says whether it ran. */
  async run(clicked: unknown, selected?: unknown): Promise<{ ran: boolean; message: string } | undefined> {
    const action = 'Run in CARLA';
    const target = scenarioTarget(clicked, selected, action);
    if (!target) return undefined;
    const settings = carlaSettings(target);
    const missing = missingRunSetting(settings);
    if (missing) {
      const setting = !settings.host.trim() ? 'host' : missing.includes('.port') ? 'port' : 'scenarioRunnerPath';
      void vscode.window.showWarningMessage(missing, 'Open Settings').then((choice) => {
        if (choice) openSettings(setting);
      });
      return { ran: false, message: missing };
    }
    const cannotStart = startProblem(settings);
    if (cannotStart) {
      const setting = cannotStart.includes('scenario_runner.py') ? 'scenarioRunnerPath' : 'python';
      void vscode.window.showErrorMessage(cannotStart, 'Open Settings').then((choice) => {
        if (choice) openSettings(setting);
      });
      return { ran: false, message: cannotStart };
    }
    const name = path.posix.basename(target.path).replace(/\.(xosc|mosc)$/i, '');
    const folder = path.join(this.storage.fsPath, 'carla-runs');
    fs.mkdirSync(folder, { recursive: true });
    const exportFile = path.join(folder, `${name}.carla.xosc`);
    const exported = await this.server.exportForCarla(target, exportFile, undefined, true);
    this.exportLosses.replace(exported.problems);
    if (exported.written === null) {
      // The command answers that nothing ran while the message waits for the user.
      this.reporter.problemsWithoutWaiting(action, exported.problems);
      return { ran: false, message: `${action}: the export was refused; nothing was run.` };
    }
    const reach = await reachable(settings.host.trim(), settings.port, REACH_TIMEOUT_MS);
    if (!reach.ok) {
      const message = unreachableMessage(settings, reach.reason);
      void vscode.window.showErrorMessage(message, 'Open Settings').then((choice) => {
        if (choice) openSettings('host');
      });
      return { ran: false, message };
    }
    const line = scenarioRunnerCommandLine(settings, exportFile);
    this.output.appendLine(`[${new Date().toISOString()}] ${action}: ${line.program} ${line.args.join(' ')} (in ${line.cwd})`);
    const task = new vscode.Task(
      { type: 'modular2simple.carla', scenario: target.toString() },
      vscode.TaskScope.Workspace,
      `ScenarioRunner: ${name}`,
      'Modular2Simple',
      new vscode.ProcessExecution(line.program, line.args, { cwd: line.cwd }),
    );
    const execution = await vscode.tasks.executeTask(task);
    // The process's end carries its exit code; the task's end alone (a process that never started) means no code.
    const end = await new Promise<number | undefined>((resolve) => {
      const listeners = [
        vscode.tasks.onDidEndTaskProcess((event) => {
          if (event.execution === execution) finish(event.exitCode);
        }),
        vscode.tasks.onDidEndTask((event) => {
          if (event.execution === execution) finish(undefined);
        }),
      ];
      const finish = (code: number | undefined): void => {
        for (const listener of listeners) listener.dispose();
        resolve(code);
      };
    });
    const outcome = runEndMessage(name, end);
    this.output.appendLine(outcome.message);
    if (outcome.ran) void vscode.window.showInformationMessage(outcome.message);
    else void vscode.window.showErrorMessage(outcome.message);
    return outcome;
  }

  dispose(): void {
    for (const disposable of this.disposables) disposable.dispose();
  }
}
