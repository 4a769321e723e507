import { TextDocument } from 'vscode-languageserver-textdocument';
import { refId } from '../core/sources';
import { notification, ServerContext } from './context';

/** `textDocument/didChange`: applies the edits to the registry's text, then re-checks what depends on the file. */
export function register(context: ServerContext): void {
  const { connection, workspace, diagnostics } = context;
  connection.onDidChangeTextDocument(({ textDocument, contentChanges }) => {
    context.idle.touch();
    const current = workspace.documents.text(textDocument.uri);
    if (!current) {
      connection.console.warn(`textDocument/didChange for ${textDocument.uri}, which is not open`);
      return;
    }
    workspace.documents.setText(textDocument.uri, TextDocument.update(current, contentChanges, textDocument.version));
    void notification(context, 'textDocument/didChange', async () => {
      const open = await workspace.documents.atUri(textDocument.uri);
      if (!open) return;
      workspace.update(open.ref);
      diagnostics.changed([refId(open.ref)]);
    });
  });
}
