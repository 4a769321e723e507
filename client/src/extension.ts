import * as path from 'node:path';
import * as vscode from 'vscode';
import type { ServerCapabilities } from 'vscode-languageclient';
import { DidChangeWatchedFilesNotification, FileChangeType } from 'vscode-languageclient';
import { EXPORT_FOR_CARLA_COMMAND, EXTRACT_GROUP_COMMAND, PACKAGE_SCHEME, type StructureNode } from '../../common/src/protocol';
import { registerBirdsEye } from './birdsEye/commands';
import { CarlaCommands } from './carla/commands';
import { PlacedDiagnostics } from './placedDiagnostics';
import type { BirdsEyeView } from './birdsEye/panel';
import { CommandReporter, commandTargets, exportForCarlaCommand, flattenCommand, mainFileOf, packCommand } from './commands';
import { ChangeFollower } from './followChanges';
import { LANGUAGE_ID, ServerCommandClient, createLanguageClient } from './languageClient';
import { ServerLifecycle } from './serverLifecycle';
import { newScenarioCommand } from './newScenario';
import { PackageFileSystem } from './packageFileSystem';
import { PACKAGE_VIEW_TYPE, PackageViewProvider } from './packageView';
import { FlattenedPreview, isPreviewPlace, PREVIEW_SCHEME, previewSource } from './preview';
import { ScenarioPathWatchers } from './scenarioPathWatchers';
import { STRUCTURE_VIEW_ID, StructureTree } from './structureView';
import { registerTagClosing } from './tagClosingEditor';
import { EsminiRunner, type EsminiRunEvent } from './esminiRun';
import { RUN_VARIATIONS_COMMAND, VariationsRunner } from './runVariations';
import { registerVariations } from './variations/commands';
import type { VariationsView } from './variations/panel';
import { extractGroupCommand } from './extractGroup';
import { followDebugSessions, registerDebugging } from './debugging';
import { registerTimeline, type TimelineView } from './timeline/panel';
import { registerLibrary, type LibraryApi } from './library/commands';

/** What the extension hands to other extensions and to its own tests. */
export interface Modular2SimpleApi {
  /** Settles when the language server has started (or failed to). */
  readonly serverReady: Promise<void>;
  readonly structure: () => StructureNode | undefined;
  /** What the running server offers (undefined before it started): lets callers and tests see which features exist. */
  readonly serverCapabilities: () => ServerCapabilities | undefined;
  /** The bird's-eye view: what it shows and last drew. */
  readonly birdsEye: BirdsEyeView;
  /** The storyboard timeline (issue 29): a run's or a debug session's storyboard transitions. */
  readonly timeline: TimelineView;
  /** The Variations view (a batch's results): what it shows and last drew. */
  readonly variations: VariationsView;
  /** *Check in CARLA ScenarioRunner* and *Run in CARLA*: the last check's result and its diagnostics. */
  readonly carla: CarlaCommands;
  /** The last *Export for CARLA…*'s losses as diagnostics. */
  readonly carlaExportLosses: vscode.DiagnosticCollection;
  /** The latest Run in esmini, and an event after each (for views of its trajectories). */
  readonly lastEsminiRun: () => EsminiRunEvent | undefined;
  readonly onDidRunEsmini: vscode.Event<EsminiRunEvent>;
  /** The Scenario Library view and its module page. */
  readonly library: LibraryApi;
}

let serverLifecycle: ServerLifecycle | undefined;

export function activate(context: vscode.ExtensionContext): Modular2SimpleApi {
  const output = vscode.window.createOutputChannel('Modular2Simple');
  const reporter = new CommandReporter(output);
  const log = (message: string): void => reporter.log(message);
  context.subscriptions.push(output);

  const packages = new PackageFileSystem(log);
  context.subscriptions.push(
    packages,
    vscode.workspace.registerFileSystemProvider(PACKAGE_SCHEME, packages, { isCaseSensitive: true }),
    vscode.window.registerCustomEditorProvider(PACKAGE_VIEW_TYPE, new PackageViewProvider(log)),
  );

  // Fired once the server has been sent an edit or a file event: the views that show its answers ask again.
  const serverHasChanges = new vscode.EventEmitter<void>();
  context.subscriptions.push(serverHasChanges);
  const client = createLanguageClient(
    context,
    () => serverHasChanges.fire(),
    () => lifecycle.closing,
  );
  const lifecycle = new ServerLifecycle(client, {
    failed: (error) => {
      log(`the language server did not start: ${(error as Error).stack ?? String(error)}`);
      void vscode.window
        .showErrorMessage(
          'Modular2Simple: the language server did not start; editing works, but checks, completion and preview do not. See the output for details.',
          'Show Details',
        )
        .then((choice) => {
          if (choice) output.show(true);
        });
    },
    note: (message) => {
      try {
        log(message);
      } catch {
        // VS Code disposes the output channel right after calling deactivate: the note is dropped then.
      }
    },
  });
  serverLifecycle = lifecycle;
  const server = new ServerCommandClient(client, lifecycle);
  const serverReady = lifecycle.startAtActivation();

  const esmini = new EsminiRunner(server);
  context.subscriptions.push(esmini);
  registerDebugging(context);

  const preview = new FlattenedPreview((source) => server.preview(source), log);
  const structure = new StructureTree();
  // Scenario-path folders outside the workspace get watchers of their own; their events reach the server as the workspace's do.
  const FILE_CHANGE: Record<'created' | 'changed' | 'deleted', FileChangeType> = {
    created: FileChangeType.Created,
    changed: FileChangeType.Changed,
    deleted: FileChangeType.Deleted,
  };
  const scenarioPathWatchers = new ScenarioPathWatchers((uri, kind) => {
    if (!client.isRunning()) return;
    client.sendNotification(DidChangeWatchedFilesNotification.type, { changes: [{ uri: uri.toString(), type: FILE_CHANGE[kind] }] }).then(
      () => serverHasChanges.fire(),
      (error: unknown) => log(`sending a file event: ${(error as Error).message}`),
    );
  });
  context.subscriptions.push(
    preview,
    structure,
    scenarioPathWatchers,
    serverHasChanges.event(() => preview.refreshAll()),
    vscode.workspace.registerTextDocumentContentProvider(PREVIEW_SCHEME, preview),
    vscode.window.createTreeView(STRUCTURE_VIEW_ID, { treeDataProvider: structure, showCollapseAll: true }),
    registerTagClosing(),
  );

  const register = (name: string, run: (...args: unknown[]) => unknown): void => {
    context.subscriptions.push(vscode.commands.registerCommand(name, run));
  };
  const variationsRunner = new VariationsRunner(context.asAbsolutePath('dist/cli.js'));
  context.subscriptions.push(variationsRunner);
  register(RUN_VARIATIONS_COMMAND, (clicked) => variationsRunner.run(clicked));
  register('modular2simple.pack', (clicked, selected, ...rest) => packCommand(server, reporter, clicked, selected, ...rest));
  register('modular2simple.flatten', (clicked, selected, ...rest) => flattenCommand(server, reporter, clicked, selected, ...rest));
  // The last export's losses at their source lines, replaced by the next export's.
  const carlaLosses = new PlacedDiagnostics('carla-export', 'Export for CARLA');
  context.subscriptions.push(carlaLosses);
  register(EXPORT_FOR_CARLA_COMMAND, (clicked, selected, ...rest) =>
    exportForCarlaCommand(server, reporter, carlaLosses, clicked, selected, ...rest),
  );
  const carla = new CarlaCommands(server, reporter, carlaLosses, context.storageUri ?? context.globalStorageUri);
  context.subscriptions.push(carla);
  register('modular2simple.newScenario', (clicked, ...rest) => newScenarioCommand(server, reporter, clicked, ...rest));
  register(EXTRACT_GROUP_COMMAND, (args) => extractGroupCommand(server, reporter, args));
  register('modular2simple.openPreview', async (clicked, at) => {
    let [source] = commandTargets(clicked, undefined);
    if (source?.scheme === PREVIEW_SCHEME) source = previewSource(source);
    if (!source) {
      void vscode.window.showErrorMessage('Open Flattened Preview: open a main.xosc (or a file inside a .mosc) first.');
      return undefined;
    }
    // A CodeLens names the reference's line; otherwise the preview opens at the cursor's group.
    return preview.open(mainFileOf(source), isPreviewPlace(at) ? at : undefined);
  });
  // The structure shown follows every change the server is sent (edits, file events) and saves, as the Outline does.
  let structureSource: vscode.Uri | undefined;
  const loadStructure = async (source: vscode.Uri, quietly = false): Promise<StructureNode | undefined> => {
    const root = quietly
      ? await server.structure(source)
      : await vscode.window.withProgress({ location: { viewId: STRUCTURE_VIEW_ID }, title: 'Reading the references' }, () =>
          server.structure(source),
        );
    structureSource = source;
    structure.show(root ?? undefined);
    return root ?? undefined;
  };
  const structureFollower = new ChangeFollower(async () => {
    if (structureSource) await loadStructure(structureSource, true);
  }, log);
  context.subscriptions.push(
    structureFollower,
    serverHasChanges.event(() => structureFollower.schedule()),
    vscode.workspace.onDidSaveTextDocument((document) => {
      if (document.languageId === LANGUAGE_ID) structureFollower.schedule();
    }),
  );
  register('modular2simple.showStructure', async (clicked) => {
    const [source] = commandTargets(clicked, undefined);
    if (!source) {
      void vscode.window.showErrorMessage('Show Structure: open a main.xosc, a .mosc or a scenario first.');
      return undefined;
    }
    try {
      const root = await loadStructure(mainFileOf(source));
      await vscode.commands.executeCommand(`${STRUCTURE_VIEW_ID}.focus`);
      if (!root) void vscode.window.showInformationMessage(`${path.posix.basename(source.path)} holds no scenario references to show.`);
      return root;
    } catch (error) {
      await reporter.failure('Show Structure', error);
      return undefined;
    }
  });
  register('modular2simple.refreshStructure', async () => {
    if (!structureSource) return vscode.commands.executeCommand('modular2simple.showStructure');
    try {
      return await loadStructure(structureSource);
    } catch (error) {
      await reporter.failure('Show Structure', error);
      return undefined;
    }
  });

  const library = registerLibrary(context, server, reporter);
  const birdsEye = registerBirdsEye(context, server, log);
  const timeline = registerTimeline(context, log, birdsEye);
  context.subscriptions.push(followDebugSessions(birdsEye));
  const variations = registerVariations(context, log);
  // A finished run goes straight into the picture: its trajectories beside the scenario.
  context.subscriptions.push(
    esmini.onDidRun((event) => {
      // Its storyboard transitions, read from esmini's log, for the timeline (shown at once when it is open).
      if (event.result.trace?.length)
        timeline.offer({
          records: event.result.trace,
          label: `run of ${path.posix.basename(event.source.path)}`,
          end: event.result.simulatedTime,
          bases: [],
        });
      if (event.result.csvFile)
        void vscode.commands.executeCommand('modular2simple.birdsEye.showRun', event.result.csvFile, {
          logText: event.result.log,
          trace: event.result.trace,
          // Named by what ran and when: two runs compared are told apart (each is a trajectories.csv).
          label: `esmini run of ${path.posix.basename(event.source.path)}, ${new Date().toTimeString().slice(0, 8)}`,
          until: event.result.duration,
          ...(event.result.collisions ? { collisions: event.result.collisions } : {}),
          // A distribution file's run is drawn on its ScenarioFile: the distribution has no roads or entities.
          scenario: event.result.scenarioOf ? vscode.Uri.parse(event.result.scenarioOf) : event.source,
          // A road packed with the scenario: esmini loaded its copy in the run folder; the view names the package entry it draws.
          ...(event.result.roadFile?.packaged ? { roadFile: event.result.roadFile.packaged } : {}),
        });
    }),
  );

  return {
    serverReady,
    structure: () => structure.current,
    serverCapabilities: () => client.initializeResult?.capabilities,
    lastEsminiRun: () => esmini.last,
    onDidRunEsmini: esmini.onDidRun,
    birdsEye,
    timeline,
    variations,
    carla,
    carlaExportLosses: carlaLosses.collection,
    library,
  };
}

export async function deactivate(): Promise<void> {
  await serverLifecycle?.close();
}
