import { placesToLocations, referencesAt } from '../features/references';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/references';

/** `textDocument/references`: every use of a group or file across the indexed workspace. */
export function register(context: ServerContext): void {
  context.connection.onReferences(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      const open = await openDocument(context, params.textDocument.uri);
      if (!open) return [];
      const places = await referencesAt(
        context.workspace,
        open.ref,
        open.document.offsetAt(params.position),
        params.context.includeDeclaration,
        () => checkCancelled(token, METHOD),
      );
      return placesToLocations(context.workspace, places);
    }),
  );
}
