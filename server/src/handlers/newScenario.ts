import { NewScenarioRequest } from '../../../common/src/protocol';
import { newScenario } from '../features/newScenario';
import { request, ServerContext } from './context';

/** `modular2simple/newScenario`: the text of a new main scenario with an ego on a chosen road network. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    NewScenarioRequest,
    request(context, NewScenarioRequest.method, (params) => newScenario(context.workspace, params)),
  );
}
