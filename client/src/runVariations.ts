import { ChildProcess, fork } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { commandTargets } from './commands';
import { withNotificationProgress } from './notificationProgress';
import { batchFailure, limitedRuns, otherBatchInResults } from './variations/batchFailure';

export const RUN_VARIATIONS_COMMAND = 'modular2simple.runVariations';
/** The Variations view's command (another part of the extension); results.csv opens instead when it is not there. */
export const SHOW_VARIATIONS_COMMAND = 'modular2simple.showVariations';
const SETTINGS = 'modular2simple.esmini';

/** Where a distribution's batch writes: `<name>.results/` beside it. */
export function resultsFolderOf(distribution: string): string {
  return path.join(path.dirname(distribution), `${path.basename(distribution).replace(/\.[^.]*$/, '')}.results`);
}

/** How a batch ended, for a caller (a test) that runs the command. */
export interface VariationsRun {
  exitCode: number | null;
  resultsFolder: string;
  cancelled: boolean;
  /** Why it did not end well, as the CLI said it (runs esmini refused, with esmini's reason); shown in the notification. */
  failure?: string;
  /** How the batch whose results were in the folder differs from this one, when the CLI refused to mix them. */
  otherBatch?: string;
  /** How many runs the time limit stopped before their scenario ended (status limit), as the CLI's summary counts them. */
  limited?: number;
}

/** The setting that gives a run its time limit, named where a limit stopped runs. */
const DURATION_SETTING = 'modular2simple.esmini.duration';

// The CLI prints one line per finished run when its standard error is not a terminal: "[3/12] 2: ok".
const PROGRESS_LINE = /^\[(\d+)\/(\d+)\]/;

/**
 * *Run Variations*: runs `modular2simple batch FILE --results <name>.results` (the bundled CLI) with a
 * cancellable progress notification, then opens the results: the Variations view when there is one,
 * else results.csv. Running it again completes an interrupted batch (the CLI resumes); when the folder holds the
 * results of a batch that differs (another duration, an edited scenario), it asks before replacing them.
 */
export class VariationsRunner implements vscode.Disposable {
  private readonly output = vscode.window.createOutputChannel('Modular2Simple Variations');
  private readonly running = new Set<ChildProcess>();

  constructor(private readonly cliPath: string) {}

  dispose(): void {
    for (const child of this.running) child.kill('SIGTERM');
    this.output.dispose();
  }

  async run(clicked: unknown): Promise<VariationsRun | undefined> {
    const [source] = commandTargets(clicked, undefined);
    if (!source || source.scheme !== 'file') {
      void vscode.window.showErrorMessage(
        'Run Variations: open a distribution file (a .xosc with a ParameterValueDistribution) on disk first.',
      );
      return undefined;
    }
    const document = vscode.workspace.textDocuments.find((candidate) => candidate.uri.toString() === source.toString());
    // The CLI reads the disk: unsaved edits would not be what runs.
    if (document?.isDirty) await document.save();
    const file = source.fsPath;
    const resultsFolder = resultsFolderOf(file);
    const settings = vscode.workspace.getConfiguration(SETTINGS, source);
    const args = ['batch', file, '--results', resultsFolder];
    const esminiPath = settings.get<string>('path');
    if (esminiPath)
      args.push('--esmini', path.resolve(vscode.workspace.getWorkspaceFolder(source)?.uri.fsPath ?? path.dirname(file), esminiPath));
    const roadPath = settings.get<string[]>('roadPath') ?? [];
    if (roadPath.length > 0) args.push('--road-path', roadPath.join(path.delimiter));
    // No duration set: each run goes to its scenario's own end (the CLI's default), not to an arbitrary limit.
    const duration = settings.get<number | null>('duration');
    if (typeof duration === 'number' && duration > 0) args.push('--duration', String(duration));
    // Kept by default, so that a row of the Variations view opens its run.
    if (vscode.workspace.getConfiguration('modular2simple.variations', source).get<boolean>('keepRuns') !== false) args.push('--keep-runs');

    this.output.appendLine(`modular2simple ${args.join(' ')}`);
    const name = path.basename(file);
    const csv = path.join(resultsFolder, 'results.csv');
    const outcome = await withNotificationProgress(
      `Running the variations of ${name}`,
      (progress, token) =>
        new Promise<VariationsRun>((resolve) => {
          // In VS Code's desktop extension host, process.execPath is Electron: it runs the CLI as Node only when told to.
          const child = fork(this.cliPath, args, {
            cwd: path.dirname(file),
            stdio: ['ignore', 'pipe', 'pipe', 'ipc'],
            // The rows' reasons then name the setting that set the time limit, not the --duration it is passed as.
            env: { ...process.env, ELECTRON_RUN_AS_NODE: '1', MODULAR2SIMPLE_DURATION_SET_BY: `the ${DURATION_SETTING} setting` },
          });
          this.running.add(child);
          let cancelled = false;
          let reported = 0;
          let pending = '';
          const printed: string[] = [];
          const subscription = token.onCancellationRequested(() => {
            cancelled = true;
            // SIGTERM stops the batch cleanly: the rows written so far stay, a later run does the rest.
            child.kill('SIGTERM');
          });
          const onText = (chunk: Buffer): void => {
            const text = pending + chunk.toString();
            const lines = text.split('\n');
            pending = lines.pop() ?? '';
            for (const line of lines) {
              this.output.appendLine(line);
              printed.push(line);
              const counted = PROGRESS_LINE.exec(line);
              if (!counted) continue;
              const done = Number(counted[1]);
              const total = Number(counted[2]);
              const percent = (100 * done) / Math.max(total, 1);
              progress.report({ message: `${done} of ${total}`, increment: percent - reported });
              reported = percent;
            }
          };
          child.stdout?.on('data', onText);
          child.stderr?.on('data', onText);
          let finished = false;
          const finish = (exitCode: number | null): void => {
            if (finished) return;
            finished = true;
            subscription.dispose();
            this.running.delete(child);
            if (pending) {
              this.output.appendLine(pending);
              printed.push(pending);
            }
            resolve({
              exitCode,
              resultsFolder,
              cancelled,
              failure: exitCode === 0 ? undefined : batchFailure(printed, { path: csv, name: vscode.workspace.asRelativePath(csv) }),
              otherBatch: exitCode === 0 ? undefined : otherBatchInResults(printed),
              limited: limitedRuns(printed),
            });
          };
          child.on('error', (error) => {
            this.output.appendLine(`cannot start the CLI: ${error.stack ?? error.message}`);
            finish(null);
          });
          // 'close', not 'exit': the CLI's last lines (why it ended) may still be in its pipes when it exits.
          child.on('close', (code) => finish(code));
        }),
    );
    if (outcome.otherBatch !== undefined) {
      // The CLI's way out (another --results folder) is not the editor's: it asks, and never shows the old results as this batch's.
      const replace = 'Replace';
      const choice = await vscode.window.showWarningMessage(
        `Run Variations of ${name}: ${path.basename(resultsFolder)} holds the results of an earlier batch, and ${outcome.otherBatch}. Replace them (rows, reports and kept runs) with a new batch?`,
        replace,
      );
      if (choice !== replace) return outcome;
      this.output.appendLine(`removing ${resultsFolder}: it held another batch's results (${outcome.otherBatch})`);
      await fs.promises.rm(resultsFolder, { recursive: true, force: true });
      return this.run(source);
    }
    if (outcome.cancelled) {
      void vscode.window.showInformationMessage(
        `Run Variations stopped: the rows so far are in ${path.basename(resultsFolder)}/results.csv; run it again to run the rest.`,
      );
    } else if (outcome.exitCode !== 0) {
      // Not awaited: an error notification stays until dismissed, and the results (each run's reason) open meanwhile.
      void vscode.window
        .showErrorMessage(
          outcome.failure
            ? `Run Variations of ${name}: ${outcome.failure}`
            : `Run Variations of ${name} failed (exit code ${outcome.exitCode}): see the output for why.`,
          'Show Output',
        )
        .then((choice) => {
          if (choice === 'Show Output') this.output.show();
        });
    }
    if (outcome.limited && typeof duration === 'number' && duration > 0) {
      // The rows name the setting too; this tells it without opening the view, and opens the setting.
      const open = 'Open Setting';
      void vscode.window
        .showInformationMessage(
          `Run Variations of ${name}: ${outcome.limited} run${outcome.limited === 1 ? '' : 's'} stopped at the ${duration} s limit of the ${DURATION_SETTING} setting, before the scenario ended by itself.`,
          open,
        )
        .then((choice) => {
          if (choice === open) void vscode.commands.executeCommand('workbench.action.openSettings', DURATION_SETTING);
        });
    }
    if (!fs.existsSync(csv)) return outcome;
    const commands = await vscode.commands.getCommands(true);
    if (commands.includes(SHOW_VARIATIONS_COMMAND))
      await vscode.commands.executeCommand(SHOW_VARIATIONS_COMMAND, vscode.Uri.file(resultsFolder));
    else await vscode.window.showTextDocument(vscode.Uri.file(csv));
    return outcome;
  }
}
