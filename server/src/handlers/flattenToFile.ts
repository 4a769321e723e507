import { flattenToFile } from '../features/commands';
import { FlattenToFileRequest } from '../../../common/src/protocol';
import { request, ServerContext } from './context';

/** `modular2simple/flattenToFile`: writes the flattened scenario atomically, never over one of its inputs. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    FlattenToFileRequest,
    request(
      context,
      FlattenToFileRequest.method,
      (params) =>
        flattenToFile(context.workspace, params?.uri, params?.outputPath, {
          ...params?.options,
          outsideWorkspace: params?.outsideWorkspace,
        }),
      { writes: true },
    ),
  );
}
