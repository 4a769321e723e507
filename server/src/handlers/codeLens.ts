import { codeLenses } from '../features/symbols';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/codeLens`: the override counts above each ScenarioReference, opening the preview. */
export function register(context: ServerContext): void {
  context.connection.onCodeLens(
    request(context, 'textDocument/codeLens', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      return open ? codeLenses(context.workspace, params.textDocument.uri, open.ref) : [];
    }),
  );
}
