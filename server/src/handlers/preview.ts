import { preview } from '../features/preview';
import { PreviewRequest } from '../../../common/src/protocol';
import { request, ServerContext } from './context';

/** `modular2simple/preview`: the live preview's flattened text and the map from source lines to its lines. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    PreviewRequest,
    request(context, PreviewRequest.method, (params) => preview(context.workspace, params)),
  );
}
