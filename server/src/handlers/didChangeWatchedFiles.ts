import { FileChangeType } from 'vscode-languageserver/node';
import { filePathOf } from '../uris';
import { notification, ServerContext } from './context';

/** `workspace/didChangeWatchedFiles`: forgets what was read of the files and checks the open files that depend on them. */
export function register(context: ServerContext): void {
  const { connection, workspace, diagnostics } = context;
  connection.onDidChangeWatchedFiles((params) => {
    void notification(context, 'workspace/didChangeWatchedFiles', async () => {
      const changed: string[] = [];
      for (const change of params.changes) {
        const filePath = filePathOf(change.uri);
        if (!filePath) continue;
        workspace.fileChanged(filePath, change.type !== FileChangeType.Changed);
        changed.push(filePath);
        if (change.type !== FileChangeType.Deleted && /\.(xosc|mosc)$/i.test(filePath)) await workspace.indexFile(filePath);
      }
      // A file appearing can change how a name resolves anywhere, so every open file is checked again.
      if (params.changes.some((change) => change.type !== FileChangeType.Changed)) diagnostics.all();
      else diagnostics.changed(changed);
    });
  });
}
