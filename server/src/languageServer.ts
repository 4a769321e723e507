import { Connection } from 'vscode-languageserver/node';
import { DiagnosticsScheduler } from './features/diagnostics';
import { EsminiRuns } from './features/esminiRun';
import { OutsideFolderWatchers } from './features/outsideFolderWatchers';
import { RoadNetworkCache } from './features/scene';
import { NO_CLIENT_EDITS } from './features/refactorings';
import { ServerContext } from './handlers/context';
import { registerHandlers } from './handlers';
import { IdleCollector } from './idleCollector';
import { Workspace } from './workspace';

export { CONFIGURATION_SECTION } from './handlers/didChangeConfiguration';

/** Wires every handler (server/src/handlers/) to a connection; the caller calls `connection.listen()`. */
export function startServer(connection: Connection): Workspace {
  const workspace = new Workspace();
  const diagnostics = new DiagnosticsScheduler(connection, workspace);
  const outsideWatchers = new OutsideFolderWatchers(connection, workspace);
  diagnostics.onPassDone = () => outsideWatchers.schedule();
  connection.onShutdown(() => outsideWatchers.dispose());
  const context: ServerContext = {
    connection,
    workspace,
    diagnostics,
    idle: new IdleCollector(),
    outsideWatchers,
    roads: new RoadNetworkCache(),
    esminiRuns: new EsminiRuns(workspace),
    client: { canConfigure: false, canWatch: false, foldersChange: false, edits: NO_CLIENT_EDITS },
    indexed: Promise.resolve(),
  };
  registerHandlers(context);
  return workspace;
}
