import * as vscode from 'vscode';
import type { Middleware } from 'vscode-languageclient';
import { whitespaceEdits } from '../../common/src/whitespaceEdits';

/**
 * A format's reply of one edit split into an edit per changed run of white space: past 1,000 changes the server sends
 * one edit (its JSON a quarter of the edits' for a 15,000-line file), and VS Code applies an edit over 100,000 characters
 * as it is, moving the cursor, folding and markers inside it to its ends. Any other reply is passed on unchanged.
 */
export function separateFormatEdits(
  document: vscode.TextDocument,
  edits: vscode.TextEdit[] | null | undefined,
): vscode.TextEdit[] | null | undefined {
  if (!edits || edits.length !== 1) return edits;
  const [edit] = edits;
  const changes = whitespaceEdits(document.getText(edit.range), edit.newText);
  if (!changes) return edits;
  const base = document.offsetAt(edit.range.start);
  return changes.map(
    (change) =>
      new vscode.TextEdit(
        new vscode.Range(document.positionAt(base + change.start), document.positionAt(base + change.end)),
        change.newText,
      ),
  );
}

/** Format Document and Format Selection with the server's one large edit split again (`separateFormatEdits`). */
export const formattingMiddleware: Middleware = {
  provideDocumentFormattingEdits: async (document, options, token, next) =>
    separateFormatEdits(document, await next(document, options, token)),
  provideDocumentRangeFormattingEdits: async (document, range, options, token, next) =>
    separateFormatEdits(document, await next(document, range, options, token)),
};
