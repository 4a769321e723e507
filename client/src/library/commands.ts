import * as vscode from 'vscode';
import { INSERT_LIBRARY_MODULE_COMMAND, type LibraryModuleSummary } from '../../../common/src/libraryProtocol';
import type { CommandReporter } from '../commands';
import type { ServerCommandClient } from '../languageClient';
import { LibraryDetail } from './detail';
import { LibraryDragController, LibraryDropProvider } from './dragAndDrop';
import { type AfterInsertRun, insertIntoMain, isInsertOptions, MainTracker } from './insert';
import { LANGUAGE_ID } from '../languageClient';
import { newFromTemplateCommand } from './templates';
import { LIBRARY_VIEW_ID, LibraryNode, LibraryTree } from './view';

/** The Scenario Library in the editor: what it shows, for callers and tests. */
export interface LibraryApi {
  readonly tree: LibraryTree;
  readonly detail: LibraryDetail;
  /** Reads the libraries again (the view's Refresh). */
  refresh(): Promise<void>;
  /** Dragging a module from the view, and dropping it onto a main. */
  readonly dragController: LibraryDragController;
  readonly dropProvider: LibraryDropProvider;
  /** Insert into Main's runs of the main in esmini, the latest last: whether each ran, and the notice it gave. */
  readonly afterInsertRuns: readonly AfterInsertRun[];
}

/** A module named by a tree node, a module summary or its name (`cut-in`, `library:cut-in`). */
function moduleOf(tree: LibraryTree, target: unknown): LibraryModuleSummary | undefined {
  if (typeof target === 'string') {
    const name = target.replace(/^library:/, '');
    return tree.current?.modules.find((module) => module.name === name);
  }
  if (typeof target === 'object' && target !== null) {
    const node = target as Partial<LibraryNode> & Partial<LibraryModuleSummary>;
    if (node.kind === 'module' && 'module' in node) return (node as { module: LibraryModuleSummary }).module;
    if (typeof node.name === 'string' && typeof node.file === 'string' && Array.isArray(node.parameters))
      return node as LibraryModuleSummary;
  }
  return undefined;
}

export function registerLibrary(context: vscode.ExtensionContext, server: ServerCommandClient, reporter: CommandReporter): LibraryApi {
  const tree = new LibraryTree();
  const tracker = new MainTracker();
  const dragController = new LibraryDragController();
  const view = vscode.window.createTreeView(LIBRARY_VIEW_ID, {
    treeDataProvider: tree,
    showCollapseAll: true,
    dragAndDropController: dragController,
  });
  const afterInsertRuns: AfterInsertRun[] = [];
  const insert = (module: LibraryModuleSummary, ...rest: unknown[]) =>
    insertIntoMain(server, reporter, tracker, module, rest.find(isInsertOptions) ?? {}, afterInsertRuns);
  const detail = new LibraryDetail((module) => insert(module));
  context.subscriptions.push(tree, tracker, view, detail);

  const describe = () => {
    const total = tree.current?.modules.length ?? 0;
    view.message = tree.filter ? `Filter '${tree.filter}': ${tree.visibleModules().length} of ${total} modules` : undefined;
    void vscode.commands.executeCommand('setContext', 'modular2simple.libraryFiltered', tree.filter !== '');
  };
  let loading: Promise<void> | undefined;
  const refresh = (): Promise<void> => {
    loading = (async () => {
      try {
        const listing = await vscode.window.withProgress({ location: { viewId: LIBRARY_VIEW_ID }, title: 'Reading the libraries' }, () =>
          server.libraryModules(),
        );
        for (const problem of listing.problems)
          reporter.log(`Scenario Library: ${problem.file}${problem.line ? `:${problem.line}` : ''}: ${problem.message}`);
        tree.show(listing);
        describe();
      } catch (error) {
        void reporter.failure('Scenario Library', error);
      }
    })();
    return loading;
  };
  /** The listing, read once when first needed. */
  const listed = async () => {
    if (!tree.current) await (loading ?? refresh());
  };
  const pickModule = async (title: string): Promise<LibraryModuleSummary | undefined> => {
    await listed();
    const picked = await vscode.window.showQuickPick(
      (tree.current?.modules ?? []).map((module) => ({
        label: module.title,
        description: `library:${module.name}`,
        detail: module.summary,
        module,
      })),
      { title, placeHolder: 'The library module', matchOnDescription: true, matchOnDetail: true },
    );
    return picked?.module;
  };
  const register = (name: string, run: (...args: unknown[]) => unknown) =>
    context.subscriptions.push(vscode.commands.registerCommand(name, run));

  context.subscriptions.push(
    view.onDidChangeVisibility((event) => {
      if (event.visible && !tree.current) void refresh();
    }),
    vscode.workspace.onDidChangeConfiguration((event) => {
      if (event.affectsConfiguration('modular2simple.library')) void refresh();
    }),
    // A saved module of a library changes what the view shows.
    vscode.workspace.onDidSaveTextDocument((document) => {
      if (tree.current?.libraries.some((library) => document.uri.fsPath.startsWith(library.folder))) void refresh();
    }),
  );
  if (view.visible) void refresh();

  const dropProvider = new LibraryDropProvider(server, reporter, tracker, async (name) => {
    await listed();
    return moduleOf(tree, name);
  });
  context.subscriptions.push(
    // Every drop into a scenario asks it; it answers only for what carries LIBRARY_MODULE_MIME (the metadata naming it is newer than our engine).
    vscode.languages.registerDocumentDropEditProvider({ language: LANGUAGE_ID }, dropProvider),
  );

  register('modular2simple.library.refresh', () => refresh());
  register('modular2simple.library.filter', async (text?: unknown) => {
    const filter =
      typeof text === 'string'
        ? text
        : await vscode.window.showInputBox({
            title: 'Filter the Scenario Library',
            prompt: 'Words that each module shown must contain (name, title, group, doc, actor or keys); empty shows all',
            value: tree.filter,
          });
    if (filter === undefined) return;
    await listed();
    tree.setFilter(filter);
    describe();
  });
  register('modular2simple.library.clearFilter', () => {
    tree.setFilter('');
    describe();
  });
  register('modular2simple.library.showModule', async (target?: unknown) => {
    await listed();
    const module = moduleOf(tree, target) ?? (await pickModule('Show Library Module'));
    if (module) detail.show(module);
    return module?.name;
  });
  // The view's Insert into Main, and the code action Insert library module here… (which passes InsertHereArguments, no module).
  register(INSERT_LIBRARY_MODULE_COMMAND, async (target?: unknown, ...rest: unknown[]) => {
    await listed();
    const module = moduleOf(tree, target) ?? (await pickModule('Insert Library Module into Main'));
    return module ? insert(module, target, ...rest) : undefined;
  });
  register('modular2simple.library.openModule', async (target?: unknown) => {
    const module = moduleOf(tree, target);
    if (module) await vscode.window.showTextDocument(vscode.Uri.file(module.file));
  });
  register('modular2simple.library.openExample', async (target?: unknown) => {
    const module = moduleOf(tree, target);
    if (module?.example) await vscode.window.showTextDocument(vscode.Uri.file(module.example));
    else if (module) void vscode.window.showInformationMessage(`library:${module.name} has no example main.`);
  });
  register('modular2simple.newFromTemplate', (clicked?: unknown, ...rest: unknown[]) =>
    newFromTemplateCommand(server, reporter, clicked, ...rest),
  );
  return { tree, detail, refresh, dragController, dropProvider, afterInsertRuns };
}
