import { ServerContext } from './context';
import * as codeAction from './codeAction';
import * as codeLens from './codeLens';
import * as completion from './completion';
import * as definition from './definition';
import * as diagnostic from './diagnostic';
import * as didChange from './didChange';
import * as didChangeConfiguration from './didChangeConfiguration';
import * as didChangeWatchedFiles from './didChangeWatchedFiles';
import * as didClose from './didClose';
import * as didOpen from './didOpen';
import * as didSave from './didSave';
import * as documentLink from './documentLink';
import * as documentSymbol from './documentSymbol';
import * as extractGroup from './extractGroup';
import * as flattenToFile from './flattenToFile';
import * as flattenToText from './flattenToText';
import * as formatting from './formatting';
import * as hover from './hover';
import * as initialize from './initialize';
import * as initialized from './initialized';
import * as inlayHint from './inlayHint';
import * as newScenario from './newScenario';
import * as semanticTokens from './semanticTokens';
import * as pack from './pack';
import * as prepareRename from './prepareRename';
import * as preview from './preview';
import * as rangeFormatting from './rangeFormatting';
import * as references from './references';
import * as rename from './rename';
import * as scene from './scene';
import * as runEsmini from './runEsmini';
import * as structure from './structure';
import * as willRenameFiles from './willRenameFiles';
import * as workspaceDiagnostic from './workspaceDiagnostic';
import * as workspaceSymbol from './workspaceSymbol';

/** One module per LSP method (or custom request); each registers its handler on the context's connection. */
const HANDLERS: { register(context: ServerContext): void }[] = [
  initialize,
  initialized,
  didChangeConfiguration,
  didChangeWatchedFiles,
  didOpen,
  didChange,
  didSave,
  didClose,
  definition,
  hover,
  completion,
  references,
  prepareRename,
  rename,
  willRenameFiles,
  codeAction,
  extractGroup,
  documentSymbol,
  workspaceSymbol,
  codeLens,
  documentLink,
  formatting,
  rangeFormatting,
  inlayHint,
  semanticTokens,
  diagnostic,
  workspaceDiagnostic,
  flattenToText,
  flattenToFile,
  pack,
  structure,
  preview,
  scene,
  runEsmini,
  newScenario,
];

export function registerHandlers(context: ServerContext): void {
  for (const handler of HANDLERS) handler.register(context);
}
