import { hover } from '../features/hover';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/hover`: what a reference, group or key at the cursor resolves to. */
export function register(context: ServerContext): void {
  context.connection.onHover(
    request(context, 'textDocument/hover', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      return open ? hover(context.workspace, open.ref, open.document.offsetAt(params.position)) : null;
    }),
  );
}
