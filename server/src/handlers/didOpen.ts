import { TextDocument } from 'vscode-languageserver-textdocument';
import { refId, SourceRef } from '../core/sources';
import { notification, ServerContext } from './context';

/** `textDocument/didOpen`: the text is registered at once; once its file is known, it overrides the disk and is checked. */
export function register(context: ServerContext): void {
  const { connection, workspace, diagnostics } = context;
  connection.onDidOpenTextDocument(({ textDocument }) => {
    const { uri } = textDocument;
    const ref: Promise<SourceRef | undefined> = workspace.uris.toRef(uri).then(
      (resolved) => {
        if (!resolved) connection.console.warn(`cannot read ${uri} as a scenario file`);
        return resolved;
      },
      (error: unknown) => {
        connection.console.warn(`cannot read ${uri} as a scenario file: ${error instanceof Error ? error.message : String(error)}`);
        return undefined;
      },
    );
    workspace.documents.add(uri, TextDocument.create(uri, textDocument.languageId, textDocument.version, textDocument.text), ref);
    void notification(context, 'textDocument/didOpen', async () => {
      const resolved = await ref;
      if (!resolved) return;
      // Undefined when the document was closed before its file was known.
      if (workspace.open(uri, resolved)) diagnostics.changed([refId(resolved)]);
    });
  });
}
