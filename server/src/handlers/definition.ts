import { definitionPlaces, toLocations } from '../features/definition';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/definition';

/** `textDocument/definition`: where a file, group or key at the cursor is declared, across files and packages. */
export function register(context: ServerContext): void {
  context.connection.onDefinition(
    request(context, METHOD, async (params, token) => {
      const open = await openDocument(context, params.textDocument.uri);
      if (!open) return [];
      const places = await definitionPlaces(context.workspace, open.ref, open.document.offsetAt(params.position));
      checkCancelled(token, METHOD);
      return toLocations(context.workspace, places);
    }),
  );
}
