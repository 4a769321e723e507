import * as path from 'node:path';
import { CodeActionKind, InitializeParams, InitializeResult, TextDocumentSyncKind } from 'vscode-languageserver/node';
import { CUSTOM_REQUESTS } from '../protocol';
import { filePathOf } from '../uris';
import { readSettings } from '../workspace';
import { ServerContext } from './context';

/** `initialize`: reads the client's capabilities, folders and first settings; announces what the server does. */
export function register(context: ServerContext): void {
  const { connection, workspace } = context;
  connection.onInitialize((params: InitializeParams): InitializeResult => {
    const capabilities = params.capabilities;
    context.client.canConfigure = Boolean(capabilities.workspace?.configuration);
    context.client.canWatch = Boolean(capabilities.workspace?.didChangeWatchedFiles?.dynamicRegistration);
    const folderUris = params.workspaceFolders?.map((folder) => folder.uri) ?? (params.rootUri ? [params.rootUri] : []);
    let folders = folderUris.map((uri) => filePathOf(uri)).filter((folder): folder is string => folder !== undefined);
    if (folders.length === 0 && params.rootPath) folders = [path.resolve(params.rootPath)];
    const initializationOptions = params.initializationOptions as Record<string, unknown> | undefined;
    workspace.configure(folders, readSettings(initializationOptions?.settings ?? initializationOptions));
    workspace.editablePackages = initializationOptions?.packageFileSystem === true;
    return {
      capabilities: {
        textDocumentSync: { openClose: true, change: TextDocumentSyncKind.Incremental, save: { includeText: false } },
        completionProvider: { triggerCharacters: ['"', "'", ',', '<', '.'], resolveProvider: false },
        hoverProvider: true,
        definitionProvider: true,
        referencesProvider: true,
        renameProvider: { prepareProvider: true },
        codeActionProvider: { codeActionKinds: [CodeActionKind.QuickFix] },
        documentSymbolProvider: true,
        workspaceSymbolProvider: true,
        codeLensProvider: { resolveProvider: false },
        workspace: {
          workspaceFolders: { supported: true },
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
