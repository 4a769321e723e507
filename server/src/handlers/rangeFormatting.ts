import { request, ServerContext } from './context';
import { formatDocument } from './formatting';

/** `textDocument/rangeFormatting`: Format Selection, only the white space of the selected lines. */
export function register(context: ServerContext): void {
  context.connection.onDocumentRangeFormatting(
    request(context, 'textDocument/rangeFormatting', async (params) => {
      const document = context.workspace.documents.text(params.textDocument.uri);
      if (!document) return [];
      const range = { start: document.offsetAt(params.range.start), end: document.offsetAt(params.range.end) };
      return formatDocument(context, params.textDocument.uri, params.options, range);
    }),
  );
}
