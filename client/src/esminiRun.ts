import * as vscode from 'vscode';
import type { LanguageClient } from 'vscode-languageclient/node';
import { RunEsminiRequest, type RunEsminiResult } from '../../common/src/protocol';
import { commandTargets } from './commands';

export const RUN_ESMINI_COMMAND = 'modular2simple.runEsmini';
const SETTINGS = 'modular2simple.esmini';

/** A finished run, for views that show its trajectories (the CSV path is in `result.csvFile`). */
export interface EsminiRunEvent {
  source: vscode.Uri;
  result: RunEsminiResult;
}

function toRange(range: RunEsminiResult['problems'][number]['range']): vscode.Range {
  return new vscode.Range(range.start.line, range.start.character, range.end.line, range.end.character);
}

/** "▶ Run in esmini" above the root element of every scenario (a main file runs flattened, a plain one as it is). */
class RunLensProvider implements vscode.CodeLensProvider {
  provideCodeLenses(document: vscode.TextDocument): vscode.CodeLens[] {
    const text = document.getText();
    const root = text.search(/<OpenSCENARIO[\s>]/);
    if (root < 0) return [];
    const position = document.positionAt(root);
    return [new vscode.CodeLens(new vscode.Range(position, position), { title: '▶ Run in esmini', command: RUN_ESMINI_COMMAND, arguments: [document.uri] })];
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

  constructor(private readonly client: LanguageClient) {
    this.disposables.push(
      this.diagnostics,
      this.output,
      this.emitter,
      vscode.commands.registerCommand(RUN_ESMINI_COMMAND, (clicked: unknown) => this.run(clicked)),
      vscode.languages.registerCodeLensProvider([{ language: 'xosc', scheme: 'file' }, { language: 'xosc', scheme: 'mosc' }, { language: 'xosc', scheme: 'untitled' }], new RunLensProvider()),
    );
  }

  async run(clicked: unknown): Promise<RunEsminiResult | undefined> {
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
    };
    try {
      if (!this.client.isRunning()) await this.client.start();
      const name = source.path.split('/').pop();
      const result = await vscode.window.withProgress(
        { location: vscode.ProgressLocation.Notification, title: `Running ${name} in esmini`, cancellable: true },
        (_progress, token) => this.client.sendRequest(RunEsminiRequest, params, token),
      );
      this.show(source, result);
      return result;
    } catch (error) {
      this.output.appendLine(`Run in esmini failed: ${(error as Error).stack ?? String(error)}`);
      const choice = await vscode.window.showErrorMessage(`Run in esmini failed: ${(error as Error).message}`, 'Show Log');
      if (choice) this.output.show(true);
      return undefined;
    }
  }

  private show(source: vscode.Uri, result: RunEsminiResult): void {
    this.diagnostics.clear();
    const byUri = new Map<string, vscode.Diagnostic[]>();
    for (const problem of result.problems) {
      const diagnostic = new vscode.Diagnostic(toRange(problem.range), problem.message + (problem.count > 1 ? ` (${problem.count} times)` : '') + (problem.note ? ` (${problem.note})` : ''), problem.severity === 'error' ? vscode.DiagnosticSeverity.Error : vscode.DiagnosticSeverity.Warning);
      diagnostic.source = 'esmini';
      const list = byUri.get(problem.uri) ?? [];
      list.push(diagnostic);
      byUri.set(problem.uri, list);
    }
    for (const [uri, list] of byUri) this.diagnostics.set(vscode.Uri.parse(uri), list);

    this.output.clear();
    this.output.appendLine(`[${new Date().toISOString()}] ${source.toString(true)}: ${result.message}`);
    if (result.esmini) this.output.appendLine(`${result.esmini} ${(result.args ?? []).join(' ')}`);
    if (result.csvFile) this.output.appendLine(`CSV: ${result.csvFile}`);
    if (result.roadFile) this.output.appendLine(`Road: ${result.roadFile.filepath} -> ${result.roadFile.loaded ?? result.roadFile.resolved ?? 'not found'}`);
    for (const remark of result.remarks ?? []) this.output.appendLine(`info: ${remark.message}${remark.count > 1 ? ` (${remark.count} times)` : ''}: esmini's remark about its own files, not the scenario (${remark.why}; ${remark.origin})`);
    for (const problem of result.flattenProblems) this.output.appendLine(`${problem.uri}:${problem.line + 1}:${problem.character + 1}: ${problem.severity}: ${problem.message}`);
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
    } else {
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
