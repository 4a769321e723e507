import { distributionLenses } from '../features/distributions';
import { codeLenses } from '../features/symbols';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/codeLens`: the override counts above each ScenarioReference, opening the preview; a distribution's count and Run Variations. */
export function register(context: ServerContext): void {
  context.connection.onCodeLens(
    request(context, 'textDocument/codeLens', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      if (!open) return [];
      return [
        ...(await distributionLenses(context.workspace, params.textDocument.uri, open.ref)),
        ...(await codeLenses(context.workspace, params.textDocument.uri, open.ref)),
      ];
    }),
  );
}
