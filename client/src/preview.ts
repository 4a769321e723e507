import * as vscode from 'vscode';
import type { FlattenTextResult, ProblemSummary } from '../../server/src/protocol';
import { LANGUAGE_ID } from './languageClient';
import { previewLineFor } from './previewSync';

export const PREVIEW_SCHEME = 'modular2simple-preview';
const REFRESH_DELAY_MS = 250;

/** The preview of `source`: a read-only virtual document named after it, in the `xosc` language. */
export function previewUri(source: vscode.Uri): vscode.Uri {
  const name = source.path.replace(/\.(xosc|mosc)$/i, '') + '.flattened.xosc';
  return vscode.Uri.from({ scheme: PREVIEW_SCHEME, path: name, query: source.toString() });
}

export function previewSource(preview: vscode.Uri): vscode.Uri {
  return vscode.Uri.parse(preview.query);
}

function describeProblems(problems: ProblemSummary[]): string {
  return problems.map((problem) => `  ${problem.severity}: ${problem.uri}:${problem.line + 1}:${problem.character + 1}: ${problem.message}${problem.hint ? ` (${problem.hint})` : ''}`).join('\n');
}

/** What the preview shows when flattening fails: why, as an XML comment, so the document stays valid XML. */
export function failureText(source: vscode.Uri, problems: ProblemSummary[]): string {
  const body = problems.length > 0 ? describeProblems(problems) : '  the language server gave no result';
  return `<!-- ${source.toString()} cannot be flattened yet:\n${body.replace(/--/g, '- -')}\n-->\n`;
}

/**
 * Live flattened previews, refreshed as the user types in any scenario (a change to a simple
 * scenario changes every main file that imports it), as the Markdown preview is.
 */
export class FlattenedPreview implements vscode.TextDocumentContentProvider, vscode.Disposable {
  private readonly changes = new vscode.EventEmitter<vscode.Uri>();
  readonly onDidChange = this.changes.event;
  private readonly subscriptions: vscode.Disposable[] = [];
  private refreshTimer: NodeJS.Timeout | undefined;

  constructor(
    private readonly flatten: (source: vscode.Uri) => Promise<FlattenTextResult>,
    private readonly log: (message: string) => void,
  ) {
    this.subscriptions.push(
      vscode.workspace.onDidChangeTextDocument((event) => {
        if (event.document.languageId === LANGUAGE_ID && event.document.uri.scheme !== PREVIEW_SCHEME) this.scheduleRefresh();
      }),
      vscode.workspace.onDidSaveTextDocument(() => this.scheduleRefresh()),
      vscode.window.onDidChangeTextEditorSelection((event) => this.follow(event.textEditor)),
    );
  }

  /** Scrolls the visible preview of this editor's document to the place that shows the cursor's line. */
  private follow(editor: vscode.TextEditor): void {
    if (editor.document.uri.scheme === PREVIEW_SCHEME) return;
    const wanted = previewUri(editor.document.uri).toString();
    const previewEditor = vscode.window.visibleTextEditors.find((visible) => visible.document.uri.toString() === wanted);
    if (!previewEditor) return;
    const line = previewLineFor(editor.document.getText(), previewEditor.document.getText(), editor.selection.active.line);
    if (line === undefined) return;
    const position = new vscode.Position(line, 0);
    previewEditor.revealRange(new vscode.Range(position, position), vscode.TextEditorRevealType.InCenterIfOutsideViewport);
  }

  private openPreviews(): vscode.Uri[] {
    return vscode.workspace.textDocuments.filter((document) => document.uri.scheme === PREVIEW_SCHEME && !document.isClosed).map((document) => document.uri);
  }

  scheduleRefresh(): void {
    if (this.refreshTimer) clearTimeout(this.refreshTimer);
    this.refreshTimer = setTimeout(() => {
      this.refreshTimer = undefined;
      for (const uri of this.openPreviews()) this.changes.fire(uri);
    }, REFRESH_DELAY_MS);
  }

  async provideTextDocumentContent(uri: vscode.Uri): Promise<string> {
    const source = previewSource(uri);
    try {
      const result = await this.flatten(source);
      if (result.text !== null) return result.text;
      this.log(`preview of ${source.toString()}: cannot flatten\n${describeProblems(result.problems)}`);
      return failureText(source, result.problems);
    } catch (error) {
      this.log(`preview of ${source.toString()}: ${(error as Error).stack ?? String(error)}`);
      return failureText(source, [{ uri: source.toString(), line: 0, character: 0, severity: 'error', message: (error as Error).message }]);
    }
  }

  async open(source: vscode.Uri): Promise<vscode.TextEditor> {
    const document = await vscode.workspace.openTextDocument(previewUri(source));
    await vscode.languages.setTextDocumentLanguage(document, LANGUAGE_ID);
    return vscode.window.showTextDocument(document, { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true, preview: true });
  }

  dispose(): void {
    if (this.refreshTimer) clearTimeout(this.refreshTimer);
    for (const subscription of this.subscriptions) subscription.dispose();
    this.changes.dispose();
  }
}
