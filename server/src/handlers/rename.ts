import { LSPErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { renameAt } from '../features/references';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/rename';

/** `textDocument/rename`: renames a ManeuverGroup with every reference to it, across files. */
export function register(context: ServerContext): void {
  const { workspace } = context;
  context.connection.onRenameRequest(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      const open = await openDocument(context, params.textDocument.uri);
      if (!open) throw new ResponseError(LSPErrorCodes.RequestFailed, 'only ManeuverGroup and parameter names can be renamed');
      return renameAt(workspace, open.ref, open.document.offsetAt(params.position), params.newName, () => checkCancelled(token, METHOD));
    }),
  );
}
