import { prepareRenameAt } from '../features/references';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/prepareRename`: ManeuverGroup names (declarations or references) and parameters can be renamed. */
export function register(context: ServerContext): void {
  const { workspace } = context;
  context.connection.onPrepareRename(
    request(context, 'textDocument/prepareRename', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      return open ? prepareRenameAt(workspace, open.ref, open.document.offsetAt(params.position)) : null;
    }),
  );
}
