import { DidChangeConfigurationNotification, DidChangeWatchedFilesNotification } from 'vscode-languageserver/node';
import { notification, ServerContext } from './context';
import { CONFIGURATION_SECTION, loadSettings } from './didChangeConfiguration';
import * as didChangeWorkspaceFolders from './didChangeWorkspaceFolders';

async function index(context: ServerContext): Promise<void> {
  const progress = await context.connection.window.createWorkDoneProgress();
  progress.begin('Indexing scenarios', 0, 'listing files', false);
  const started = Date.now();
  const count = await context.workspace.indexAll((done, total) =>
    progress.report(Math.round((done / Math.max(1, total)) * 100), `${done}/${total} files`),
  );
  progress.done();
  context.connection.console.info(`indexed ${count} scenario files in ${Date.now() - started} ms`);
}

/** `initialized`: loads the settings, registers for changes, indexes the workspace, then checks the open files. */
export function register(context: ServerContext): void {
  const { connection } = context;
  connection.onInitialized(() => {
    didChangeWorkspaceFolders.listen(context);
    context.indexed = notification(context, 'initialized', async () => {
      await loadSettings(context);
      if (context.client.canConfigure)
        await connection.client.register(DidChangeConfigurationNotification.type, { section: CONFIGURATION_SECTION });
      if (context.client.canWatch) {
        await connection.client.register(DidChangeWatchedFilesNotification.type, {
          // Road files too: the road-file check and the road-network rules read them.
          watchers: [{ globPattern: '**/*.xosc' }, { globPattern: '**/*.mosc' }, { globPattern: '**/*.xodr' }],
        });
        // Files appearing and vanishing are reported from now on: the index keeps its list between walks.
        context.workspace.index.watched = true;
      }
      await index(context);
      context.diagnostics.all();
      context.idle.touch();
    });
  });
}
