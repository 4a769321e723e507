import * as fs from 'node:fs';
import { createConnection, ProposedFeatures } from 'vscode-languageserver/node';
import { startServer } from './languageServer';

// createConnection reads the transport from the command line (--stdio, --node-ipc, --socket=N);
// without one, a parent that gave us an IPC channel gets node IPC and anyone else gets stdio.
if (!process.argv.some((argument) => /^--(stdio|node-ipc|socket|pipe)/.test(argument)))
  process.argv.push(process.send ? '--node-ipc' : '--stdio');
const connection = createConnection(ProposedFeatures.all);
// A test driving a real editor cannot read its output channel, so it may name a file that collects the errors too.
const errorLog = process.env.MODULAR2SIMPLE_SERVER_ERROR_LOG;
if (errorLog) {
  const logError = connection.console.error.bind(connection.console);
  connection.console.error = (message: string) => {
    fs.appendFileSync(errorLog, `${message}\n`);
    logError(message);
  };
}
process.on('uncaughtException', (error) => connection.console.error(`uncaught: ${error.stack ?? error.message}`));
process.on('unhandledRejection', (reason) =>
  connection.console.error(`unhandled rejection: ${(reason as Error)?.stack ?? String(reason)}`),
);
startServer(connection);
connection.listen();
