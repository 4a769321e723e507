import { expressionHints } from '../features/inlayHints';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/inlayHint`: the evaluated value of every `${...}` in the visible range. */
export function register(context: ServerContext): void {
  context.connection.languages.inlayHint.on(
    request(context, 'textDocument/inlayHint', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      const semantics = open ? (await context.workspace.source(open.ref)).semantics : undefined;
      if (!open || !semantics) return [];
      return expressionHints(semantics, open.document.offsetAt(params.range.start), open.document.offsetAt(params.range.end));
    }),
  );
}
