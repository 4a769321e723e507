import * as vscode from 'vscode';
import { LANGUAGE_ID } from './languageClient';
import { closingTagFor } from './tagClosing';

/** Inserts `</Name>` after the cursor when the user types the `>` of `<Name ...>` (setting modular2simple.autoCloseTags). */
export function registerTagClosing(): vscode.Disposable {
  return vscode.workspace.onDidChangeTextDocument((event) => {
    const editor = vscode.window.activeTextEditor;
    if (!editor || editor.document !== event.document || event.document.languageId !== LANGUAGE_ID) return;
    if (event.reason !== undefined || event.contentChanges.length !== 1) return;
    const [change] = event.contentChanges;
    if (change.text !== '>' || change.rangeLength !== 0) return;
    if (!vscode.workspace.getConfiguration('modular2simple', event.document).get<boolean>('autoCloseTags', true)) return;
    const line = event.document.lineAt(change.range.start.line).text;
    const cursor = change.range.start.character + 1;
    const closing = closingTagFor(line.slice(0, cursor), line.slice(cursor));
    if (!closing) return;
    const position = change.range.start.translate(0, 1);
    void editor.insertSnippet(new vscode.SnippetString(`$0${closing}`), position, { undoStopBefore: false, undoStopAfter: false });
  });
}
