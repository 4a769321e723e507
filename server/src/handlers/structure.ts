import { structure } from '../features/commands';
import { StructureRequest } from '../../../common/src/protocol';
import { request, ServerContext } from './context';

/** `modular2simple/structure`: the reference graph for the Show Structure view. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    StructureRequest,
    request(context, StructureRequest.method, (params) => structure(context.workspace, params?.uri)),
  );
}
