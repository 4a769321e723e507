import { ServerContext } from './context';
import * as diagnostic from './diagnostic';
import * as didChange from './didChange';
import * as didChangeConfiguration from './didChangeConfiguration';
import * as didChangeWatchedFiles from './didChangeWatchedFiles';
import * as didClose from './didClose';
import * as didOpen from './didOpen';
import * as didSave from './didSave';
import * as extractGroup from './extractGroup';
import * as formatting from './formatting';
import * as initialize from './initialize';
import * as initialized from './initialized';
import { REQUESTS } from './requests';
import * as workspaceDiagnostic from './workspaceDiagnostic';

/**
 * The handlers that do more than find the open document and call a feature, one module each: the
 * lifecycle, the document notifications, the diagnostics reports, Format Document (whose edits Format
 * Selection shares) and Extract to a simple scenario (which checks its parameters); each registers its
 * handler on the context's connection.
 */
const HANDLERS: { register(context: ServerContext): void }[] = [
  initialize,
  initialized,
  didChangeConfiguration,
  didChangeWatchedFiles,
  didOpen,
  didChange,
  didSave,
  didClose,
  extractGroup,
  formatting,
  diagnostic,
  workspaceDiagnostic,
];

/** Registers every handler: the modules above, then one per row of the table of requests (handlers/requests.ts). */
export function registerHandlers(context: ServerContext): void {
  for (const handler of HANDLERS) handler.register(context);
  for (const [method, register] of Object.entries(REQUESTS)) register(context, method);
}
