import { ErrorCodes, LSPErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { ExtractGroupRequest } from '../../../common/src/protocol';
import { extractGroupEdit, refactoringTarget } from '../features/refactorings';
import { openDocument, request, ServerContext } from './context';

/** `modular2simple/extractGroup`: *Extract to a simple scenario* with the attributes the user chose. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    ExtractGroupRequest,
    request(context, ExtractGroupRequest.method, async (params) => {
      if (typeof params?.uri !== 'string' || typeof params.position?.line !== 'number' || typeof params.position.character !== 'number')
        throw new ResponseError(ErrorCodes.InvalidParams, 'extractGroup needs a uri and a position');
      if (params.attributes !== undefined && !(Array.isArray(params.attributes) && params.attributes.every((id) => typeof id === 'string')))
        throw new ResponseError(ErrorCodes.InvalidParams, 'extractGroup: attributes must be a list of choice ids');
      const open = await openDocument(context, params.uri);
      if (!open) throw new ResponseError(ErrorCodes.InvalidParams, `extractGroup: ${params.uri} is not an open scenario`);
      const offset = open.document.offsetAt(params.position);
      const target = await refactoringTarget(context.workspace, params.uri, open.ref, open.document, offset, offset, context.client.edits);
      if (!target)
        throw new ResponseError(
          LSPErrorCodes.ContentModified,
          'extractGroup: the document is not well-formed XML, or changed while it was read',
        );
      return extractGroupEdit(target, params.attributes);
    }),
  );
}
