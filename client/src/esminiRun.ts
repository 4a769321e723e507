import * as vscode from 'vscode';
import { RunEsminiRequest, type RunEsminiResult } from '../../common/src/protocol';
import { runAnywayQuestion, runBlockingErrors, runLensTitles } from './anyway';
import { commandTargets } from './commands';
import type { ServerCommandClient } from './languageClient';
import { withNotificationProgress } from './notificationProgress';

export const RUN_ESMINI_COMMAND = 'modular2simple.runEsmini';
/** *Run Anyway*: the run that `run --force` makes, for a scenario with errors. */
export const RUN_ESMINI_ANYWAY_COMMAND = 'modular2simple.runEsminiAnyway';
const SETTINGS = 'modular2simple.esmini';

/** A finished run, for views that show its trajectories (the CSV path is in `result.csvFile`). */
export interface EsminiRunEvent {
  source: vscode.Uri;
  result: RunEsminiResult;
}

function toRange(range: RunEsminiResult['problems'][number]['range']): vscode.Range {
  return new vscode.Range(range.start.line, range.start.character, range.end.line, range.end.character);
}

/** The file's own errors as the language server reports them that a run in esmini is refused for (runBlockingErrors). */
function scenarioErrors(uri: vscode.Uri): number {
  return runBlockingErrors(
    vscode.languages.getDiagnostics(uri).map((diagnostic) => ({
      isError: diagnostic.severity === vscode.DiagnosticSeverity.Error,
      source: diagnostic.source,
      code: diagnostic.code,
    })),
  );
}

/**
 * "▶ Run in esmini" above the root element of every scenario (a main file runs flattened, a plain one as
 * it is), and "▶ Run Anyway" beside it while the file has errors.
 */
class RunLensProvider implements vscode.CodeLensProvider, vscode.Disposable {
  private readonly changes = new vscode.EventEmitter<void>();
  readonly onDidChangeCodeLenses = this.changes.event;
  private readonly subscription = vscode.languages.onDidChangeDiagnostics((event) => {
    if (event.uris.some((uri) => /\.xosc$/i.test(uri.path))) this.changes.fire();
  });

  provideCodeLenses(document: vscode.TextDocument): vscode.CodeLens[] {
    const text = document.getText();
    const root = text.search(/<OpenSCENARIO[\s>]/);
    if (root < 0) return [];
    const position = document.positionAt(root);
    const range = new vscode.Range(position, position);
    return runLensTitles(scenarioErrors(document.uri)).map(
      ({ title, force }) =>
        new vscode.CodeLens(range, { title, command: force ? RUN_ESMINI_ANYWAY_COMMAND : RUN_ESMINI_COMMAND, arguments: [document.uri] }),
    );
  }

  dispose(): void {
    this.subscription.dispose();
    this.changes.dispose();
  }
}

/**
 * The Run in esmini command: the server flattens the editor's text and runs esmini; its messages go
 * to their own diagnostic collection (replaced by the next run), its whole log to an output channel.
 */
export class EsminiRunner implements vscode.Disposable {
  readonly diagnostics = vscode.languages.createDiagnosticCollection('esmini');
  readonly output = vscode.window.createOutputChannel('Modular2Simple: esmini');
  private readonly emitter = new vscode.EventEmitter<EsminiRunEvent>();
  /** Fires after every run that produced a result. */
  readonly onDidRun = this.emitter.event;
  private readonly disposables: vscode.Disposable[] = [];
  last: EsminiRunEvent | undefined;

  constructor(private readonly server: ServerCommandClient) {
    const lenses = new RunLensProvider();
    this.disposables.push(
      this.diagnostics,
      this.output,
      this.emitter,
      lenses,
      vscode.commands.registerCommand(RUN_ESMINI_COMMAND, (clicked: unknown) => this.run(clicked)),
      vscode.commands.registerCommand(RUN_ESMINI_ANYWAY_COMMAND, (clicked: unknown) => this.run(clicked, true)),
      vscode.languages.registerCodeLensProvider(
        [
          { language: 'xosc', scheme: 'file' },
          { language: 'xosc', scheme: 'mosc' },
          { language: 'xosc', scheme: 'untitled' },
        ],
        lenses,
      ),
    );
  }

  /** Runs the scenario; `force` (*Run Anyway*) runs whatever can be flattened despite its errors. */
  async run(clicked: unknown, force = false): Promise<RunEsminiResult | undefined> {
    const [source] = commandTargets(clicked, undefined);
    if (!source) {
      void vscode.window.showErrorMessage('Run in esmini: open a scenario (.xosc or .mosc) first.');
      return undefined;
    }
    const settings = vscode.workspace.getConfiguration(SETTINGS, source);
    const params = {
      uri: source.toString(),
      esminiPath: settings.get<string>('path') || undefined,
      roadPath: settings.get<string[]>('roadPath') ?? [],
      duration: settings.get<number>('duration'),
      ...(force ? { force: true } : {}),
    };
    try {
      const client = await this.server.running();
      const name = source.path.split('/').pop();
      const result = await withNotificationProgress(`Running ${name} in esmini`, (_progress, token) =>
        client.sendRequest(RunEsminiRequest, params, token),
      );
      this.show(source, result);
      const question = runAnywayQuestion(result);
      // Not awaited: the command answers with this run's result, and the answer to the question starts another.
      if (question) void this.offerRunAnyway(source, question, result);
      return result;
    } catch (error) {
      this.output.appendLine(`Run in esmini failed: ${(error as Error).stack ?? String(error)}`);
      const choice = await vscode.window.showErrorMessage(`Run in esmini failed: ${(error as Error).message}`, 'Show Log');
      if (choice) this.output.show(true);
      return undefined;
    }
  }

  /** Asks whether to run a refused scenario anyway, naming its errors. */
  private async offerRunAnyway(source: vscode.Uri, question: string, result: RunEsminiResult): Promise<void> {
    const runAnyway = 'Run Anyway';
    const choice = await vscode.window.showWarningMessage(question, runAnyway, 'Go to Problem');
    if (choice === runAnyway) {
      await this.run(source, true);
      return;
    }
    const first = result.flattenProblems.find((problem) => problem.severity === 'error');
    if (choice === 'Go to Problem' && first) {
      await vscode.window.showTextDocument(vscode.Uri.parse(first.uri), {
        selection: new vscode.Range(first.line, first.character, first.line, first.character),
      });
    }
  }

  private show(source: vscode.Uri, result: RunEsminiResult): void {
    this.diagnostics.clear();
    const byUri = new Map<string, vscode.Diagnostic[]>();
    for (const problem of result.problems) {
      const diagnostic = new vscode.Diagnostic(
        toRange(problem.range),
        problem.message + (problem.count > 1 ? ` (${problem.count} times)` : '') + (problem.note ? ` (${problem.note})` : ''),
        problem.severity === 'error' ? vscode.DiagnosticSeverity.Error : vscode.DiagnosticSeverity.Warning,
      );
      diagnostic.source = 'esmini';
      const list = byUri.get(problem.uri) ?? [];
      list.push(diagnostic);
      byUri.set(problem.uri, list);
    }
    // What esmini runs otherwise than written, in the Problems view beside esmini's messages (with the simulator setting esmini, the check shows them, with their fixes).
    const checkedForEsmini = vscode.workspace.getConfiguration('modular2simple', source).get<string>('simulator') === 'esmini';
    for (const finding of checkedForEsmini ? [] : result.esminiFindings) {
      const end = finding.end ?? { line: finding.line, character: Number.MAX_SAFE_INTEGER };
      const diagnostic = new vscode.Diagnostic(
        new vscode.Range(finding.line, finding.character, end.line, end.character),
        finding.message + (finding.hint ? ` (${finding.hint})` : ''),
        finding.severity === 'error' ? vscode.DiagnosticSeverity.Error : vscode.DiagnosticSeverity.Warning,
      );
      diagnostic.source = 'esmini';
      const list = byUri.get(finding.uri) ?? [];
      list.push(diagnostic);
      byUri.set(finding.uri, list);
    }
    for (const [uri, list] of byUri) this.diagnostics.set(vscode.Uri.parse(uri), list);

    this.output.clear();
    this.output.appendLine(`[${new Date().toISOString()}] ${source.toString(true)}: ${result.message}`);
    if (result.esmini) this.output.appendLine(`${result.esmini} ${(result.args ?? []).join(' ')}`);
    if (result.csvFile) this.output.appendLine(`CSV: ${result.csvFile}`);
    if (result.roadFile)
      this.output.appendLine(
        `Road: ${result.roadFile.filepath} -> ${result.roadFile.loaded ?? result.roadFile.resolved ?? 'not found'}${result.roadFile.packaged ? ` (a copy of ${result.roadFile.packaged})` : ''}`,
      );
    for (const remark of result.remarks ?? [])
      this.output.appendLine(
        `info: ${remark.message}${remark.count > 1 ? ` (${remark.count} times)` : ''}: esmini's remark about its own files, not the scenario (${remark.why}; ${remark.origin})`,
      );
    for (const problem of [...result.flattenProblems, ...result.esminiFindings])
      this.output.appendLine(`${problem.uri}:${problem.line + 1}:${problem.character + 1}: ${problem.severity}: ${problem.message}`);
    this.output.append(result.log);
    this.last = { source, result };
    this.emitter.fire(this.last);

    const errors = result.problems.filter((problem) => problem.severity === 'error').length;
    if (result.outcome === 'ok') {
      void vscode.window.showInformationMessage(result.message);
    } else if (result.outcome === 'no-esmini') {
      void vscode.window.showWarningMessage(result.message, 'Open Settings').then((choice) => {
        if (choice) void vscode.commands.executeCommand('workbench.action.openSettings', `${SETTINGS}.path`);
      });
    } else if (!runAnywayQuestion(result)) {
      // A refusal that Run Anyway would start is asked about by run(), not reported here as well.
      const detail = result.outcome === 'errors' ? `${errors} error${errors === 1 ? '' : 's'} in the Problems view` : result.message;
      void vscode.window.showErrorMessage(`Run in esmini: ${detail}`, 'Show Log').then((choice) => {
        if (choice) this.output.show(true);
      });
    }
  }

  dispose(): void {
    for (const disposable of this.disposables) disposable.dispose();
  }
}
