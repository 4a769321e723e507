import { fileRenameEdits } from '../features/references';
import { checkCancelled, request, ServerContext } from './context';

const METHOD = 'workspace/willRenameFiles';

/** `workspace/willRenameFiles`: updates the scenarioFileName values that name a renamed file or folder. */
export function register(context: ServerContext): void {
  context.connection.workspace.onWillRenameFiles(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      return fileRenameEdits(context.workspace, params.files);
    }),
  );
}
