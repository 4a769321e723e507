import { notification, ServerContext } from './context';

/** `textDocument/didSave`: the file on disk changed, so what was cached of its bytes goes (Pack reads the disk right after saving). */
export function register(context: ServerContext): void {
  const { connection, workspace } = context;
  connection.onDidSaveTextDocument(({ textDocument }) => {
    void notification(context, 'textDocument/didSave', async () => {
      const open = await workspace.documents.atUri(textDocument.uri);
      if (open) workspace.fileChanged(open.ref.disk, false);
    });
  });
}
