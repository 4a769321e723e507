import { ServerContext } from './context';
import * as codeAction from './codeAction';
import * as codeLens from './codeLens';
import * as completion from './completion';
import * as definition from './definition';
import * as didChange from './didChange';
import * as didChangeConfiguration from './didChangeConfiguration';
import * as didChangeWatchedFiles from './didChangeWatchedFiles';
import * as didClose from './didClose';
import * as didOpen from './didOpen';
import * as documentSymbol from './documentSymbol';
import * as flattenToFile from './flattenToFile';
import * as flattenToText from './flattenToText';
import * as hover from './hover';
import * as initialize from './initialize';
import * as initialized from './initialized';
import * as pack from './pack';
import * as prepareRename from './prepareRename';
import * as references from './references';
import * as rename from './rename';
import * as scene from './scene';
import * as runEsmini from './runEsmini';
import * as structure from './structure';
import * as willRenameFiles from './willRenameFiles';
import * as workspaceSymbol from './workspaceSymbol';

/** One module per LSP method (or custom request); each registers its handler on the context's connection. */
const HANDLERS: { register(context: ServerContext): void }[] = [
  initialize,
  initialized,
  didChangeConfiguration,
  didChangeWatchedFiles,
  didOpen,
  didChange,
  didClose,
  definition,
  hover,
  completion,
  references,
  prepareRename,
  rename,
  willRenameFiles,
  codeAction,
  documentSymbol,
  workspaceSymbol,
  codeLens,
  flattenToText,
  flattenToFile,
  pack,
  structure,
  scene,
  runEsmini,
];

export function registerHandlers(context: ServerContext): void {
  for (const handler of HANDLERS) handler.register(context);
}
