import * as path from 'node:path';
import {
  CodeActionKind,
  Connection,
  DidChangeConfigurationNotification,
  DidChangeWatchedFilesNotification,
  FileChangeType,
  InitializeParams,
  InitializeResult,
  ResponseError,
  TextDocuments,
  TextDocumentSyncKind,
} from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { refId, SourceRef } from './core/sources';
import { ServerCommands } from './protocol';
import { codeActions } from './features/codeActions';
import { flattenToFile, flattenToText, structure } from './features/commands';
import { complete } from './features/completion';
import { definitionPlaces, toLocations } from './features/definition';
import { DiagnosticsScheduler } from './features/diagnostics';
import { hover } from './features/hover';
import { fileRenameEdits, placesToLocations, renameGroup, targetAt, usagesOf } from './features/references';
import { codeLenses, documentSymbols, workspaceSymbols } from './features/symbols';
import { packCommand } from './features/pack';
import { formattingCapabilities, register as registerFormatting } from './features/formatting';
import { IdleCollector } from './idleCollector';
import { filePathOf } from './uris';
import { readSettings, Workspace } from './workspace';

export const CONFIGURATION_SECTION = 'modular2simple';

/** Wires every feature to a connection; the caller calls `connection.listen()`. */
export function startServer(connection: Connection): Workspace {
  const workspace = new Workspace();
  const documents = new TextDocuments(TextDocument);
  const diagnostics = new DiagnosticsScheduler(connection, workspace);
  const refs = new Map<string, Promise<SourceRef | undefined>>();
  let canConfigure = false;
  let canWatch = false;
  let initialFolders: string[] = [];
  let indexed: Promise<void> = Promise.resolve();
  const idle = new IdleCollector();

  /** Runs a handler; a failure is logged and answered with `fallback`, never left to crash the server. */
  const guard = async <T>(name: string, fallback: T, run: () => Promise<T>): Promise<T> => {
    try {
      return await run();
    } catch (error) {
      // A deliberate answer (such as "cannot rename this") reaches the client as it is.
      if (error instanceof ResponseError) throw error;
      connection.console.error(`${name} failed: ${(error as Error)?.stack ?? String(error)}`);
      return fallback;
    }
  };

  const open = async (uri: string): Promise<{ ref: SourceRef; document: TextDocument } | undefined> => {
    const document = documents.get(uri);
    const ref = await refs.get(uri);
    return document && ref ? { ref, document } : undefined;
  };

  connection.onInitialize((params: InitializeParams): InitializeResult => {
    const capabilities = params.capabilities;
    canConfigure = Boolean(capabilities.workspace?.configuration);
    canWatch = Boolean(capabilities.workspace?.didChangeWatchedFiles?.dynamicRegistration);
    const folderUris = params.workspaceFolders?.map((folder) => folder.uri) ?? (params.rootUri ? [params.rootUri] : []);
    initialFolders = folderUris.map((uri) => filePathOf(uri)).filter((folder): folder is string => folder !== undefined);
    if (initialFolders.length === 0 && params.rootPath) initialFolders = [path.resolve(params.rootPath)];
    const initializationOptions = params.initializationOptions as Record<string, unknown> | undefined;
    workspace.configure(initialFolders, readSettings(initializationOptions?.settings ?? initializationOptions));
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
        ...formattingCapabilities,
        executeCommandProvider: { commands: Object.values(ServerCommands) },
        workspace: {
          workspaceFolders: { supported: true },
          fileOperations: {
            willRename: {
              filters: [{ pattern: { glob: '**/*.{xosc,mosc}', matches: 'file' } }, { pattern: { glob: '**/*', matches: 'folder' } }],
            },
          },
        },
      },
      serverInfo: { name: 'modular2simple-language-server', version: '0.1.0' },
    };
  });

  const loadSettings = async () => {
    if (!canConfigure) return;
    const value: unknown = await connection.workspace.getConfiguration(CONFIGURATION_SECTION);
    workspace.configure(workspace.folders, readSettings(value));
  };

  const index = async () => {
    const progress = await connection.window.createWorkDoneProgress();
    progress.begin('Indexing scenarios', 0, 'listing files', false);
    const started = Date.now();
    const count = await workspace.indexAll((done, total) => progress.report(Math.round((done / Math.max(1, total)) * 100), `${done}/${total} files`));
    progress.done();
    connection.console.info(`indexed ${count} scenario files in ${Date.now() - started} ms`);
  };

  connection.onInitialized(() => {
    indexed = (async () => {
      await guard('settings', undefined, loadSettings);
      if (canConfigure) await guard('register', undefined, async () => void (await connection.client.register(DidChangeConfigurationNotification.type, { section: CONFIGURATION_SECTION })));
      if (canWatch) {
        await guard('register', undefined, async () =>
          void (await connection.client.register(DidChangeWatchedFilesNotification.type, {
            watchers: [{ globPattern: '**/*.xosc' }, { globPattern: '**/*.mosc' }],
          })),
        );
      }
      await guard('index', undefined, index);
      diagnostics.all();
      idle.touch();
    })();
  });

  connection.onDidChangeConfiguration((change) => {
    void guard('configuration', undefined, async () => {
      if (canConfigure) await loadSettings();
      else workspace.configure(workspace.folders, readSettings((change.settings as Record<string, unknown> | undefined)?.[CONFIGURATION_SECTION]));
      diagnostics.all();
    });
  });

  connection.onDidChangeWatchedFiles((params) => {
    void guard('watched files', undefined, async () => {
      const changed: string[] = [];
      for (const change of params.changes) {
        const filePath = filePathOf(change.uri);
        if (!filePath) continue;
        workspace.fileChanged(filePath, change.type !== FileChangeType.Changed);
        changed.push(filePath);
        if (change.type !== FileChangeType.Deleted && /\.(xosc|mosc)$/i.test(filePath)) await workspace.indexFile(filePath).catch(() => undefined);
      }
      // A file appearing can change how a name resolves anywhere, so every open file is checked again.
      if (params.changes.some((change) => change.type !== FileChangeType.Changed)) diagnostics.all();
      else diagnostics.changed(changed);
    });
  });

  documents.onDidOpen(({ document }) => {
    const pending = workspace.uris.toRef(document.uri).catch(() => undefined);
    refs.set(document.uri, pending);
    void guard('open', undefined, async () => {
      const ref = await pending;
      if (!ref) {
        connection.console.warn(`cannot read ${document.uri} as a scenario file`);
        return;
      }
      workspace.open(document.uri, ref, document);
      diagnostics.changed([refId(ref)]);
    });
  });

  documents.onDidChangeContent(({ document }) => {
    idle.touch();
    void guard('change', undefined, async () => {
      const ref = await refs.get(document.uri);
      if (!ref || !workspace.documents.has(refId(ref))) return;
      workspace.update(ref, document);
      diagnostics.changed([refId(ref)]);
    });
  });

  documents.onDidClose(({ document }) => {
    idle.touch();
    void guard('close', undefined, async () => {
      const ref = await refs.get(document.uri);
      refs.delete(document.uri);
      if (!ref) return;
      workspace.close(ref);
      diagnostics.closed(ref, document.uri);
      diagnostics.changed([refId(ref)]);
    });
  });

  connection.onDefinition((params) =>
    guard('definition', [], async () => {
      const target = await open(params.textDocument.uri);
      if (!target) return [];
      return toLocations(workspace, await definitionPlaces(workspace, target.ref, target.document.offsetAt(params.position)));
    }),
  );

  connection.onHover((params) =>
    guard('hover', null, async () => {
      const target = await open(params.textDocument.uri);
      return target ? hover(workspace, target.ref, target.document.offsetAt(params.position)) : null;
    }),
  );

  connection.onCompletion((params) =>
    guard('completion', [], async () => {
      const target = await open(params.textDocument.uri);
      return target ? complete(workspace, target.ref, target.document, target.document.offsetAt(params.position)) : [];
    }),
  );

  connection.onReferences((params) =>
    guard('references', [], async () => {
      await indexed;
      const target = await open(params.textDocument.uri);
      const subject = target ? await targetAt(workspace, target.ref, target.document.offsetAt(params.position)) : undefined;
      if (!subject) return [];
      const places = (await usagesOf(workspace, subject)).map((usage) => usage.place);
      if (params.context.includeDeclaration) places.unshift(subject.declaration);
      return placesToLocations(workspace, places);
    }),
  );

  connection.onPrepareRename((params) =>
    guard('prepareRename', null, async () => {
      const target = await open(params.textDocument.uri);
      const subject = target ? await targetAt(workspace, target.ref, target.document.offsetAt(params.position)) : undefined;
      if (!subject || subject.kind !== 'group') return null;
      const here = target && refId(subject.ref) === refId(target.ref) ? subject.declaration.range : undefined;
      if (here) return { range: here, placeholder: subject.name };
      const source = target ? await workspace.source(target.ref) : undefined;
      const lines = source?.original?.document.lines;
      const offset = target?.document.offsetAt(params.position) ?? 0;
      const text = source?.original?.document.text ?? '';
      // The reference under the cursor: the whole maneuverGroupName value.
      let start = offset;
      let end = offset;
      while (start > 0 && !/["']/.test(text[start - 1])) start--;
      while (end < text.length && !/["']/.test(text[end])) end++;
      return lines ? { range: lines.range(start, end), placeholder: text.slice(start, end) } : null;
    }),
  );

  connection.onRenameRequest((params) =>
    guard('rename', null, async () => {
      await indexed;
      const target = await open(params.textDocument.uri);
      const subject = target ? await targetAt(workspace, target.ref, target.document.offsetAt(params.position)) : undefined;
      if (!subject || subject.kind !== 'group') throw new ResponseError(-32803, 'only ManeuverGroup names can be renamed');
      if (subject.ref.entries.length > 0 && !workspace.editablePackages) {
        throw new ResponseError(-32803, 'the group is inside a .mosc package, and this editor cannot write into packages');
      }
      const newName = params.newName.includes('.') ? params.newName.slice(params.newName.lastIndexOf('.') + 1) : params.newName;
      return renameGroup(workspace, subject, newName);
    }).then((result) => {
      if (result === null) throw new ResponseError(-32803, 'nothing to rename here');
      return result;
    }),
  );

  connection.workspace.onWillRenameFiles((params) =>
    guard('willRenameFiles', null, async () => {
      await indexed;
      return fileRenameEdits(workspace, params.files);
    }),
  );

  connection.onCodeAction((params) =>
    guard('codeAction', [], async () => {
      const target = await open(params.textDocument.uri);
      return target ? codeActions(workspace, params.textDocument.uri, target.ref, target.document, params.range, params.context.diagnostics) : [];
    }),
  );

  connection.onDocumentSymbol((params) =>
    guard('documentSymbol', [], async () => {
      const target = await open(params.textDocument.uri);
      const source = target ? await workspace.source(target.ref) : undefined;
      return source?.original ? documentSymbols(source.original.document) : [];
    }),
  );

  connection.onWorkspaceSymbol((params) =>
    guard('workspaceSymbol', [], async () => {
      await indexed;
      return workspaceSymbols(workspace, params.query);
    }),
  );

  connection.onCodeLens((params) =>
    guard('codeLens', [], async () => {
      const target = await open(params.textDocument.uri);
      return target ? codeLenses(workspace, params.textDocument.uri, target.ref) : [];
    }),
  );

  connection.onExecuteCommand(async (params) => {
    const args = params.arguments ?? [];
    try {
      switch (params.command) {
        case ServerCommands.flattenToText:
          return await flattenToText(workspace, args[0], args[1]);
        case ServerCommands.flattenToFile:
          return await flattenToFile(workspace, args[0], args[1], args[2]);
        case ServerCommands.pack:
          return await packCommand(workspace, args[0], args[1]);
        case ServerCommands.structure:
          return await structure(workspace, args[0]);
        default:
          throw new ResponseError(-32601, `unknown command ${params.command}`);
      }
    } catch (error) {
      if (error instanceof ResponseError) throw error;
      connection.console.error(`${params.command} failed: ${(error as Error)?.stack ?? String(error)}`);
      throw new ResponseError(-32603, `${params.command} failed: ${(error as Error)?.message ?? String(error)}`);
    }
  });

  registerFormatting(connection, {
    documents,
    workspace,
    parsed: async (uri) => {
      const target = await open(uri);
      return target ? (await workspace.source(target.ref)).original?.document : undefined;
    },
  });

  documents.listen(connection);
  return workspace;
}
