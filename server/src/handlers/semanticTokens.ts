import { semanticTokens } from '../features/semanticTokens';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/semanticTokens/full` and `/range`: `$name` and `${...}` told apart from literal values. */
export function register(context: ServerContext): void {
  const tokensOf = async (
    uri: string,
    range?: { start: { line: number; character: number }; end: { line: number; character: number } },
  ) => {
    const open = await openDocument(context, uri);
    const semantics = open ? (await context.workspace.source(open.ref)).semantics : undefined;
    if (!open || !semantics) return { data: [] };
    return range
      ? semanticTokens(semantics, open.document.offsetAt(range.start), open.document.offsetAt(range.end))
      : semanticTokens(semantics);
  };
  context.connection.languages.semanticTokens.on(
    request(context, 'textDocument/semanticTokens/full', (params) => tokensOf(params.textDocument.uri)),
  );
  context.connection.languages.semanticTokens.onRange(
    request(context, 'textDocument/semanticTokens/range', (params) => tokensOf(params.textDocument.uri, params.range)),
  );
}
