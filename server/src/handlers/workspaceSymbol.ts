import { workspaceSymbols } from '../features/symbols';
import { checkCancelled, request, ServerContext } from './context';

const METHOD = 'workspace/symbol';

/** `workspace/symbol`: ManeuverGroups of the whole indexed workspace by name. */
export function register(context: ServerContext): void {
  context.connection.onWorkspaceSymbol(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      return workspaceSymbols(context.workspace, params.query);
    }),
  );
}
