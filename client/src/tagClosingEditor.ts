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
    const position = change.range.start.translate(0, 1);
    const line = event.document.lineAt(position.line).text;
    // The whole text before the cursor: a tag's attributes and a comment may span lines.
    const before = event.document.getText(new vscode.Range(new vscode.Position(0, 0), position));
    const closing = closingTagFor(before, line.slice(position.character));
    if (!closing) return;
    void editor.insertSnippet(new vscode.SnippetString(`$0${closing}`), position, { undoStopBefore: false, undoStopAfter: false });
  });
}
