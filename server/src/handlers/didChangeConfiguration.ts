import { fileUri } from '../uris';
import { readSettings } from '../settings';
import { notification, ServerContext } from './context';

export const CONFIGURATION_SECTION = 'modular2simple';

/** Asks the client for the settings of the window and of each folder (when it can answer) and applies them. */
export async function loadSettings(context: ServerContext): Promise<void> {
  if (!context.client.canConfigure) return;
  const folders = context.workspace.folders;
  const items = [
    { section: CONFIGURATION_SECTION },
    ...folders.map((folder) => ({ section: CONFIGURATION_SECTION, scopeUri: fileUri(folder).toString() })),
  ];
  const values = (await context.connection.workspace.getConfiguration(items)) as unknown[];
  const perFolder = new Map(folders.map((folder, index) => [folder, readSettings(values[index + 1]).scenarioPath]));
  context.workspace.configure(folders, readSettings(values[0]), perFolder);
}

/** `workspace/didChangeConfiguration`: new settings can change how any name resolves, so every open file is checked again. */
export function register(context: ServerContext): void {
  const { connection, workspace } = context;
  connection.onDidChangeConfiguration((change) => {
    void notification(context, 'workspace/didChangeConfiguration', async () => {
      if (context.client.canConfigure) await loadSettings(context);
      else
        workspace.configure(
          workspace.folders,
          readSettings((change.settings as Record<string, unknown> | undefined)?.[CONFIGURATION_SECTION]),
        );
      context.diagnostics.all();
    });
  });
}
