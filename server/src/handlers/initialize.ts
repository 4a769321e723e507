import * as path from 'node:path';
import {
  CodeActionKind,
  InitializeParams,
  InitializeResult,
  ResourceOperationKind,
  TextDocumentSyncKind,
} from 'vscode-languageserver/node';
import { SEMANTIC_TOKENS_LEGEND } from '../features/semanticTokens';
import { CUSTOM_REQUESTS } from '../../../common/src/protocol';
import { filePathOf } from '../uris';
import { readSettings } from '../settings';
import { ServerContext } from './context';

/** `initialize`: reads the client's capabilities, folders and first settings; announces what the server does. */
export function register(context: ServerContext): void {
  const { connection, workspace } = context;
  connection.onInitialize((params: InitializeParams): InitializeResult => {
    const capabilities = params.capabilities;
    context.client.canConfigure = Boolean(capabilities.workspace?.configuration);
    context.client.canWatch = Boolean(capabilities.workspace?.didChangeWatchedFiles?.dynamicRegistration);
    context.outsideWatchers.supported =
      context.client.canWatch && Boolean(capabilities.workspace?.didChangeWatchedFiles?.relativePatternSupport);
    context.client.foldersChange = Boolean(capabilities.workspace?.workspaceFolders);
    // A client that pulls diagnostics gets them for the whole workspace and none pushed, so nothing shows twice.
    const pulls = Boolean(capabilities.textDocument?.diagnostic);
    context.diagnostics.mode = !pulls ? 'push' : capabilities.workspace?.diagnostics?.refreshSupport ? 'refresh' : 'pull';
    const workspaceEdit = capabilities.workspace?.workspaceEdit;
    const initializationOptions = params.initializationOptions as Record<string, unknown> | undefined;
    context.client.edits = {
      documentChanges: Boolean(workspaceEdit?.documentChanges),
      createFiles: Boolean(workspaceEdit?.resourceOperations?.includes(ResourceOperationKind.Create)),
      extractPicker: initializationOptions?.extractPicker === true,
      libraryPicker: initializationOptions?.libraryPicker === true,
    };
    const folderUris = params.workspaceFolders?.map((folder) => folder.uri) ?? (params.rootUri ? [params.rootUri] : []);
    let folders = folderUris.map((uri) => filePathOf(uri)).filter((folder): folder is string => folder !== undefined);
    if (folders.length === 0 && params.rootPath) folders = [path.resolve(params.rootPath)];
    workspace.configure(folders, readSettings(initializationOptions?.settings ?? initializationOptions));
    workspace.editablePackages = initializationOptions?.packageFileSystem === true;
    return {
      capabilities: {
        textDocumentSync: { openClose: true, change: TextDocumentSyncKind.Incremental, save: { includeText: false } },
        completionProvider: { triggerCharacters: ['"', "'", ',', '<', '.', '$'], resolveProvider: false },
        inlayHintProvider: true,
        semanticTokensProvider: { legend: SEMANTIC_TOKENS_LEGEND, full: true, range: true },
        hoverProvider: true,
        definitionProvider: true,
        referencesProvider: true,
        renameProvider: { prepareProvider: true },
        codeActionProvider: {
          codeActionKinds: [
            CodeActionKind.QuickFix,
            CodeActionKind.RefactorRewrite,
            CodeActionKind.RefactorExtract,
            CodeActionKind.RefactorInline,
          ],
        },
        documentSymbolProvider: true,
        workspaceSymbolProvider: true,
        codeLensProvider: { resolveProvider: false },
        documentLinkProvider: { resolveProvider: false },
        documentFormattingProvider: true,
        documentRangeFormattingProvider: true,
        ...(pulls ? { diagnosticProvider: { identifier: 'modular2simple', interFileDependencies: true, workspaceDiagnostics: true } } : {}),
        workspace: {
          workspaceFolders: { supported: true, changeNotifications: true },
          fileOperations: {
            willRename: {
              filters: [{ pattern: { glob: '**/*.{xosc,mosc}', matches: 'file' } }, { pattern: { glob: '**/*', matches: 'folder' } }],
            },
          },
        },
        // The custom requests of protocol.ts, so a client can tell which this server answers.
        experimental: { requests: CUSTOM_REQUESTS },
      },
      serverInfo: { name: 'modular2simple-language-server', version: '0.1.0' },
    };
  });
}
