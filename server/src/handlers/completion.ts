import { complete } from '../features/completion';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/completion`: file names, group names, override keys and ScenarioReference snippets. */
export function register(context: ServerContext): void {
  context.connection.onCompletion(
    request(context, 'textDocument/completion', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      return open ? complete(context.workspace, open.ref, open.document, open.document.offsetAt(params.position)) : [];
    }),
  );
}
