import * as path from 'node:path';
import * as vscode from 'vscode';
import { splitScenarioPath } from '../../common/src/scenarioPath';

const SCENARIO_GLOB = '**/*.{xosc,mosc}';

/** The folders searched through SCENARIO_PATH and each workspace folder's `scenarioPath` setting (read for that folder, relative to it). */
export function scenarioPathFolders(): string[] {
  const folders = new Set<string>(splitScenarioPath(process.env.SCENARIO_PATH));
  for (const folder of vscode.workspace.workspaceFolders ?? []) {
    if (folder.uri.scheme !== 'file') continue;
    const entries = vscode.workspace.getConfiguration('modular2simple', folder.uri).get<string[]>('scenarioPath') ?? [];
    for (const entry of entries) if (typeof entry === 'string' && entry.trim()) folders.add(path.resolve(folder.uri.fsPath, entry));
  }
  return [...folders];
}

function inside(child: string, parent: string): boolean {
  const relative = path.relative(parent, child);
  return relative === '' || (!relative.startsWith('..') && !path.isAbsolute(relative));
}

/** The scenario-path folders that no workspace folder holds: the editor watches only the workspace, so these need watchers of their own. */
export function foldersOutsideWorkspace(folders: string[], workspaceFolders: string[]): string[] {
  return folders.filter((folder) => !workspaceFolders.some((root) => inside(folder, root)));
}

/**
 * One file system watcher per scenario-path folder outside the workspace, made again when the
 * setting or the workspace folders change; each event is handed on (to the language server).
 */
export class ScenarioPathWatchers implements vscode.Disposable {
  private watchers: vscode.FileSystemWatcher[] = [];
  private readonly subscriptions: vscode.Disposable[] = [];
  watched: string[] = [];

  constructor(private readonly onEvent: (uri: vscode.Uri, kind: 'created' | 'changed' | 'deleted') => void) {
    this.subscriptions.push(
      vscode.workspace.onDidChangeConfiguration((event) => {
        if (event.affectsConfiguration('modular2simple.scenarioPath')) this.update();
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
