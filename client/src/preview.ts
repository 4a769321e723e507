import * as vscode from 'vscode';
import { previewLineOf } from '../../common/src/lineSegments';
import type { PreviewResult, ProblemSummary } from '../../common/src/protocol';
import { LANGUAGE_ID } from './languageClient';
import { flattenedName } from './naming';

export const PREVIEW_SCHEME = 'modular2simple-preview';

/** The preview of `source`: a read-only virtual document named as Flatten names its output, in the `xosc` language. */
export function previewUri(source: vscode.Uri): vscode.Uri {
  const folder = vscode.Uri.joinPath(source, '..');
  return vscode.Uri.from({
    scheme: PREVIEW_SCHEME,
    path: vscode.Uri.joinPath(folder, flattenedName(source)).path,
    query: source.toString(),
  });
}

export function previewSource(preview: vscode.Uri): vscode.Uri {
  return vscode.Uri.parse(preview.query);
}

function describeProblems(problems: ProblemSummary[]): string {
  return problems
    .map(
      (problem) =>
        `  ${problem.severity}: ${problem.uri}:${problem.line + 1}:${problem.character + 1}: ${problem.message}${problem.hint ? ` (${problem.hint})` : ''}`,
    )
    .join('\n');
}

/** What the preview shows when flattening fails: why, as an XML comment, so the document stays valid XML. */
export function failureText(source: vscode.Uri, problems: ProblemSummary[]): string {
  const body = problems.length > 0 ? describeProblems(problems) : '  the language server gave no result';
  return `<!-- ${source.toString()} cannot be flattened yet:\n${body.replace(/--/g, '- -')}\n-->\n`;
}

/** True when the preview shows why flattening failed (failureText) instead of a flattened scenario. */
function showsFailure(result: PreviewResult | undefined): boolean {
  return result !== undefined && result.text === null;
}

/** Where a preview was asked to open: a line of its source (the CodeLens's reference, or the cursor's line). */
export interface PreviewPlace {
  line: number;
}

export function isPreviewPlace(value: unknown): value is PreviewPlace {
  return typeof value === 'object' && value !== null && typeof (value as { line?: unknown }).line === 'number';
}

/** One preview's latest result, and whether a request for it is running or wanted again. */
interface PreviewState {
  result: PreviewResult | undefined;
  running: Promise<PreviewResult> | undefined;
  again: boolean;
}

/**
 * Live flattened previews, refreshed as soon as the language server has an edit of any scenario
 * (a change to a simple scenario changes every main file that imports it), as the Markdown
 * preview is. The text and the map from source lines to preview lines come from the server's
 * flattener; one request per preview runs at a time, and edits made meanwhile ask for one more.
 */
export class FlattenedPreview implements vscode.TextDocumentContentProvider, vscode.Disposable {
  private readonly changes = new vscode.EventEmitter<vscode.Uri>();
  readonly onDidChange = this.changes.event;
  private readonly subscriptions: vscode.Disposable[] = [];
  private readonly states = new Map<string, PreviewState>();

  constructor(
    private readonly request: (source: vscode.Uri) => Promise<PreviewResult>,
    private readonly log: (message: string) => void,
  ) {
    this.subscriptions.push(
      vscode.workspace.onDidSaveTextDocument(() => this.refreshAll()),
      vscode.workspace.onDidCloseTextDocument((document) => {
        if (document.uri.scheme === PREVIEW_SCHEME) this.states.delete(document.uri.toString());
      }),
      vscode.window.onDidChangeTextEditorSelection((event) => this.follow(event.textEditor)),
      vscode.workspace.onDidChangeTextDocument((event) => {
        if (event.document.uri.scheme === PREVIEW_SCHEME) this.showFailureFromTop(event.document.uri);
      }),
      // A preview shown again (say, a closed tab reopened) asks for the current text.
      vscode.window.tabGroups.onDidChangeTabs((event) => {
        for (const tab of event.opened) {
          if (
            tab.input instanceof vscode.TabInputText &&
            tab.input.uri.scheme === PREVIEW_SCHEME &&
            !this.states.has(tab.input.uri.toString())
          )
            void this.refresh(tab.input.uri);
        }
      }),
    );
  }

  /**
   * Called once the language server has been sent an edit (or a file event), so the request sees
   * it. Previews in no tab (closed, though VS Code keeps their documents a while) are not
   * flattened on every keystroke: they forget their text and ask again when shown.
   */
  refreshAll(): void {
    const inTabs = new Set(
      vscode.window.tabGroups.all.flatMap((group) =>
        group.tabs.map((tab) => (tab.input instanceof vscode.TabInputText ? tab.input.uri.toString() : undefined)),
      ),
    );
    for (const document of vscode.workspace.textDocuments) {
      if (document.uri.scheme !== PREVIEW_SCHEME || document.isClosed) continue;
      if (inTabs.has(document.uri.toString())) void this.refresh(document.uri);
      else this.states.delete(document.uri.toString());
    }
  }

  private state(uri: vscode.Uri): PreviewState {
    let state = this.states.get(uri.toString());
    if (!state) {
      state = { result: undefined, running: undefined, again: false };
      this.states.set(uri.toString(), state);
    }
    return state;
  }

  /** Asks the server again; while a request runs, one more is made after it, with the latest text. */
  private refresh(uri: vscode.Uri): Promise<PreviewResult> {
    const state = this.state(uri);
    if (state.running) {
      state.again = true;
      return state.running;
    }
    const run = async (): Promise<PreviewResult> => {
      let result: PreviewResult;
      do {
        state.again = false;
        result = await this.fetch(uri);
        state.result = result;
        this.changes.fire(uri);
      } while (state.again);
      state.running = undefined;
      return result;
    };
    state.running = run();
    return state.running;
  }

  private async fetch(uri: vscode.Uri): Promise<PreviewResult> {
    const source = previewSource(uri);
    try {
      const result = await this.request(source);
      if (result.text === null) this.log(`preview of ${source.toString()}: cannot flatten\n${describeProblems(result.problems)}`);
      return result;
    } catch (error) {
      this.log(`preview of ${source.toString()}: ${(error as Error).stack ?? String(error)}`);
      return {
        text: null,
        problems: [{ uri: source.toString(), line: 0, character: 0, severity: 'error', message: (error as Error).message }],
        lines: [],
      };
    }
  }

  async provideTextDocumentContent(uri: vscode.Uri): Promise<string> {
    const state = this.state(uri);
    const result = state.result ?? (await this.refresh(uri));
    return result.text ?? failureText(previewSource(uri), result.problems);
  }

  /** The preview line that shows `line` of the source, by the server's map. */
  previewLine(preview: vscode.Uri, line: number): number | undefined {
    const lines = this.states.get(preview.toString())?.result?.lines;
    return lines ? previewLineOf(lines, line) : undefined;
  }

  private reveal(previewEditor: vscode.TextEditor, sourceLine: number, how: vscode.TextEditorRevealType): boolean {
    const line = this.previewLine(previewEditor.document.uri, sourceLine);
    if (line === undefined) return false;
    const position = new vscode.Position(line, 0);
    previewEditor.revealRange(new vscode.Range(position, position), how);
    return true;
  }

  /**
   * A preview that turned into the few lines saying why it cannot be flattened would keep its scroll
   * position below them and look blank: its editors go to the first line.
   */
  private showFailureFromTop(preview: vscode.Uri): void {
    if (!showsFailure(this.states.get(preview.toString())?.result)) return;
    for (const editor of vscode.window.visibleTextEditors) {
      if (editor.document.uri.toString() !== preview.toString()) continue;
      editor.selection = new vscode.Selection(0, 0, 0, 0);
      editor.revealRange(new vscode.Range(0, 0, 0, 0), vscode.TextEditorRevealType.AtTop);
    }
  }

  /** Scrolls the visible preview of this editor's document to the place that shows the cursor's line. */
  private follow(editor: vscode.TextEditor): void {
    if (editor.document.uri.scheme === PREVIEW_SCHEME) return;
    const wanted = previewUri(editor.document.uri).toString();
    const previewEditor = vscode.window.visibleTextEditors.find((visible) => visible.document.uri.toString() === wanted);
    if (previewEditor) this.reveal(previewEditor, editor.selection.active.line, vscode.TextEditorRevealType.InCenterIfOutsideViewport);
  }

  /** Opens the preview beside the source, at the group of `place` (or of the source editor's cursor). */
  async open(source: vscode.Uri, place?: PreviewPlace): Promise<vscode.TextEditor> {
    const uri = previewUri(source);
    await this.refresh(uri);
    const document = await vscode.workspace.openTextDocument(uri);
    await vscode.languages.setTextDocumentLanguage(document, LANGUAGE_ID);
    const editor = await vscode.window.showTextDocument(document, {
      viewColumn: vscode.ViewColumn.Beside,
      preserveFocus: true,
      preview: true,
    });
    const sourceEditor = vscode.window.visibleTextEditors.find((visible) => visible.document.uri.toString() === source.toString());
    const line = place?.line ?? sourceEditor?.selection.active.line;
    if (showsFailure(this.states.get(uri.toString())?.result)) this.showFailureFromTop(uri);
    else if (line !== undefined) this.reveal(editor, line, vscode.TextEditorRevealType.AtTop);
    return editor;
  }

  dispose(): void {
    for (const subscription of this.subscriptions) subscription.dispose();
    this.changes.dispose();
  }
}
