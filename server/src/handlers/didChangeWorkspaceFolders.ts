import { filePathOf } from '../uris';
import { notification, ServerContext } from './context';
import { loadSettings } from './didChangeConfiguration';

/**
 * `workspace/didChangeWorkspaceFolders`: new search roots and folder settings, a new index, every
 * open file checked again. Called by `initialized`: the connection offers the event only after
 * `initialize` was answered, and only to a client that sends it.
 */
export function listen(context: ServerContext): void {
  const { connection, workspace } = context;
  if (!context.client.foldersChange) return;
  connection.workspace.onDidChangeWorkspaceFolders((event) => {
    void notification(context, 'workspace/didChangeWorkspaceFolders', async () => {
      const paths = (folders: { uri: string }[]) =>
        folders.map((folder) => filePathOf(folder.uri)).filter((folder): folder is string => folder !== undefined);
      const removed = new Set(paths(event.removed));
      const folders = [...workspace.folders.filter((folder) => !removed.has(folder)), ...paths(event.added)];
      workspace.configure(folders, workspace.settings);
      workspace.index.clear();
      await loadSettings(context);
      await context.indexed;
      await workspace.indexAll();
      context.diagnostics.all();
    });
  });
}
