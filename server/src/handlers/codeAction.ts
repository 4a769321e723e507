import { codeActions } from '../features/codeActions';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/codeAction`: quick fixes for the server's own diagnostics, adding a group's missing keys, and the refactorings. */
export function register(context: ServerContext): void {
  context.connection.onCodeAction(
    request(context, 'textDocument/codeAction', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      return open
        ? codeActions(
            context.workspace,
            params.textDocument.uri,
            open.ref,
            open.document,
            params.range,
            params.context.diagnostics,
            params.context.only,
            context.client.edits,
          )
        : [];
    }),
  );
}
