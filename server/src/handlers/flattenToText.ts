import { flattenToText } from '../features/commands';
import { FlattenToTextRequest } from '../../../common/src/protocol';
import { request, ServerContext } from './context';

/** `modular2simple/flattenToText`: the flattened scenario from the editor's text, for the live preview. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    FlattenToTextRequest,
    request(context, FlattenToTextRequest.method, (params) => flattenToText(context.workspace, params?.uri, params?.options)),
  );
}
