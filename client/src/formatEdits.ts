import * as vscode from 'vscode';
import type { Middleware } from 'vscode-languageclient';
import { splitFormatReply } from '../../common/src/whitespaceEdits';

/**
 * Format Document and Format Selection with a reply of one edit split into an edit per changed run of white space:
 * past 1,000 changes the server sends one edit (its JSON a third of the edits' for a 15,000-line file), which VS Code
 * would apply as it is past 100,000 characters (markers inside it moved to its ends); split, it gets the edits it got before.
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
