import { packCommand } from '../features/pack';
import { PackRequest } from '../../../common/src/protocol';
import { request, ServerContext } from './context';

/** `modular2simple/pack`: writes a .mosc of a folder (or main.xosc) with what it references, or of chosen files. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    PackRequest,
    request(
      context,
      PackRequest.method,
      (params) => packCommand(context.workspace, params?.inputs, params?.outputPath, params?.selfContained),
      { writes: true },
    ),
  );
}
