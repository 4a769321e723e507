import * as path from 'node:path';
import * as vscode from 'vscode';
import { insideFolders } from '../../common/src/paths';
import { splitScenarioPath } from '../../common/src/scenarioPath';

// Road files too: the road-file check looks for a LogicFile's road in these folders (core/semantics/roadFiles.ts).
const SCENARIO_GLOB = '**/*.{xosc,mosc,xodr}';
/** The settings that name searched folders: scenarios and catalogs; road files and catalogs. */
const FOLDER_SETTINGS = ['modular2simple.scenarioPath', 'modular2simple.esmini.roadPath'];

/**
 * The folders searched through SCENARIO_PATH, each workspace folder's `scenarioPath` setting and its
 * `esmini.roadPath` setting (read for that folder, relative to it).
 */
export function scenarioPathFolders(): string[] {
  const folders = new Set<string>(splitScenarioPath(process.env.SCENARIO_PATH));
  for (const folder of vscode.workspace.workspaceFolders ?? []) {
    if (folder.uri.scheme !== 'file') continue;
    const entries = FOLDER_SETTINGS.flatMap((setting) => {
      const [section, key] = [setting.slice(0, setting.lastIndexOf('.')), setting.slice(setting.lastIndexOf('.') + 1)];
      return vscode.workspace.getConfiguration(section, folder.uri).get<unknown[]>(key) ?? [];
    });
    for (const entry of entries) if (typeof entry === 'string' && entry.trim()) folders.add(path.resolve(folder.uri.fsPath, entry));
  }
  return [...folders];
}

/** The searched folders that no workspace folder holds: the editor watches only the workspace, so these need watchers of their own. */
export function foldersOutsideWorkspace(folders: string[], workspaceFolders: string[]): string[] {
  return folders.filter((folder) => !insideFolders(folder, workspaceFolders));
}

/**
 * One file system watcher per searched folder (scenario path, road path) outside the workspace, made again when
 * those settings or the workspace folders change; each event is handed on (to the language server).
 */
export class ScenarioPathWatchers implements vscode.Disposable {
  private watchers: vscode.FileSystemWatcher[] = [];
  private readonly subscriptions: vscode.Disposable[] = [];
  watched: string[] = [];

  constructor(private readonly onEvent: (uri: vscode.Uri, kind: 'created' | 'changed' | 'deleted') => void) {
    this.subscriptions.push(
      vscode.workspace.onDidChangeConfiguration((event) => {
        if (FOLDER_SETTINGS.some((setting) => event.affectsConfiguration(setting))) this.update();
      }),
      vscode.workspace.onDidChangeWorkspaceFolders(() => this.update()),
    );
    this.update();
  }

  private update(): void {
    for (const watcher of this.watchers) watcher.dispose();
    const roots = (vscode.workspace.workspaceFolders ?? [])
      .filter((folder) => folder.uri.scheme === 'file')
      .map((folder) => folder.uri.fsPath);
    this.watched = foldersOutsideWorkspace(scenarioPathFolders(), roots);
    this.watchers = this.watched.map((folder) => {
      const watcher = vscode.workspace.createFileSystemWatcher(new vscode.RelativePattern(vscode.Uri.file(folder), SCENARIO_GLOB));
      watcher.onDidCreate((uri) => this.onEvent(uri, 'created'));
      watcher.onDidChange((uri) => this.onEvent(uri, 'changed'));
      watcher.onDidDelete((uri) => this.onEvent(uri, 'deleted'));
      return watcher;
    });
  }

  dispose(): void {
    for (const watcher of this.watchers) watcher.dispose();
    for (const subscription of this.subscriptions) subscription.dispose();
  }
}
