import { documentSymbols } from '../features/symbols';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/documentSymbol`: the outline of one file. */
export function register(context: ServerContext): void {
  context.connection.onDocumentSymbol(
    request(context, 'textDocument/documentSymbol', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      const source = open ? await context.workspace.source(open.ref) : undefined;
      return source?.original ? documentSymbols(source.original.document) : [];
    }),
  );
}
