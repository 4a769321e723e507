import * as vscode from 'vscode';
import type { Middleware } from 'vscode-languageclient';
import { splitFormatReply } from '../../common/src/whitespaceEdits';

/**
 * Format Document and Format Selection with a reply of one edit split into an edit per changed run of white space:
 * past 1,000 changes the server sends one edit (its JSON a third of the edits' for a 15,000-line file), and VS Code
 * applies an edit over 100,000 characters as it is, moving the cursor, folding and markers inside it to its ends.
 */
export const formattingMiddleware: Middleware = {
  provideDocumentFormattingEdits: async (document, options, token, next) =>
    splitFormatReply<vscode.Position, vscode.Range, vscode.TextEdit>(document, await next(document, options, token), textEdit),
  provideDocumentRangeFormattingEdits: async (document, range, options, token, next) =>
    splitFormatReply<vscode.Position, vscode.Range, vscode.TextEdit>(document, await next(document, range, options, token), textEdit),
};

function textEdit(start: vscode.Position, end: vscode.Position, newText: string): vscode.TextEdit {
  return new vscode.TextEdit(new vscode.Range(start, end), newText);
}
