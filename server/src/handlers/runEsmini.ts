import { RunEsminiRequest } from '../../../common/src/protocol';
import { request, ServerContext } from './context';

/** `modular2simple/runEsmini`: runs the editor's text of a scenario in esmini. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    RunEsminiRequest,
    request(context, RunEsminiRequest.method, (params, token) => context.esminiRuns.run(params, token)),
  );
}
