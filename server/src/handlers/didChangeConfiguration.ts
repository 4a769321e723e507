import { readSettings } from '../workspace';
import { notification, ServerContext } from './context';

export const CONFIGURATION_SECTION = 'modular2simple';

/** Asks the client for the settings (when it can answer) and applies them. */
export async function loadSettings(context: ServerContext): Promise<void> {
  if (!context.client.canConfigure) return;
  const value: unknown = await context.connection.workspace.getConfiguration(CONFIGURATION_SECTION);
  context.workspace.configure(context.workspace.folders, readSettings(value));
}

/** `workspace/didChangeConfiguration`: new settings can change how any name resolves, so every open file is checked again. */
export function register(context: ServerContext): void {
  const { connection, workspace } = context;
  connection.onDidChangeConfiguration((change) => {
    void notification(context, 'workspace/didChangeConfiguration', async () => {
      if (context.client.canConfigure) await loadSettings(context);
      else workspace.configure(workspace.folders, readSettings((change.settings as Record<string, unknown> | undefined)?.[CONFIGURATION_SECTION]));
      context.diagnostics.all();
    });
  });
}
