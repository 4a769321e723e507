import { refId } from '../core/sources';
import { ServerContext } from './context';

/** `textDocument/didClose`: the disk text counts again; the file's own diagnostics are cleared. */
export function register(context: ServerContext): void {
  const { connection, workspace, diagnostics } = context;
  connection.onDidCloseTextDocument(({ textDocument }) => {
    context.idle.touch();
    const closed = workspace.close(textDocument.uri);
    if (!closed) return;
    diagnostics.closed(closed.ref, textDocument.uri);
    diagnostics.changed([refId(closed.ref)]);
    context.outsideWatchers.schedule();
  });
}
