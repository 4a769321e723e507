import { documentLinks } from '../features/documentLinks';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/documentLink`: each resolved scenarioFileName links to its file. */
export function register(context: ServerContext): void {
  context.connection.onDocumentLinks(
    request(context, 'textDocument/documentLink', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      return open ? documentLinks(context.workspace, open.ref) : [];
    }),
  );
}
