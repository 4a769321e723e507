import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { webviewNonce } from '../webviewNonce';
import { parseResultsCsv, ResultsCsvError } from '../../../common/src/variationsReport';
import { isFromView, type FromView, type ToView, type VariationsStats } from './messages';
import { variationsHtml } from './page';

export const VARIATIONS_VIEW_TYPE = 'modular2simple.variations';
const RELOAD_DELAY_MS = 300;

/** The files of one kept run (batch --keep-runs): DIR/runs/INDEX/. */
export function keptRun(resultsFolder: string, index: string): { csvPath: string; logPath: string; scenario: string } {
  const folder = path.join(resultsFolder, 'runs', index);
  return {
    csvPath: path.join(folder, 'trajectories.csv'),
    logPath: path.join(folder, 'esmini.log'),
    scenario: path.join(folder, 'scenario.xosc'),
  };
}

/** A results folder, or the folder of a results.csv. */
export function resultsFolderOf(target: string): string {
  return /\.csv$/i.test(target) ? path.dirname(target) : target;
}

/** The webview showing a batch's results: one at a time, following results.csv while the batch writes it. */
export class VariationsView implements vscode.Disposable {
  private panel: vscode.WebviewPanel | undefined;
  private ready = false;
  private csvWatcher: vscode.FileSystemWatcher | undefined;
  private reloadTimer: NodeJS.Timeout | undefined;
  private message: ToView | undefined;
  /** The results folder shown. */
  folder: string | undefined;
  /** What the view last reported drawing; for tests. */
  stats: VariationsStats | undefined;
  /** The run last opened from the view; for tests. */
  openedRun: string | undefined;
  /** Why the last click opened no run, as the view shows it (cleared by the next results); for tests. */
  lastNotice: string | undefined;

  constructor(
    private readonly extensionUri: vscode.Uri,
    private readonly log: (message: string) => void,
  ) {}

  get isOpen(): boolean {
    return this.panel !== undefined && this.ready;
  }

  /** Shows the results in `target` (a results folder or its results.csv). */
  async show(target: string): Promise<void> {
    const folder = resultsFolderOf(target);
    if (folder !== this.folder) {
      this.folder = folder;
      this.stats = undefined;
      this.csvWatcher?.dispose();
      this.csvWatcher = vscode.workspace.createFileSystemWatcher(new vscode.RelativePattern(vscode.Uri.file(folder), 'results.csv'));
      const reloadSoon = () => {
        clearTimeout(this.reloadTimer);
        this.reloadTimer = setTimeout(() => void this.load(), RELOAD_DELAY_MS);
      };
      this.csvWatcher.onDidChange(reloadSoon);
      this.csvWatcher.onDidCreate(reloadSoon);
    }
    if (!this.panel) this.createPanel();
    else this.panel.reveal(undefined, false);
    await this.load();
  }

  private async load(): Promise<void> {
    const folder = this.folder;
    if (!folder || !this.panel) return;
    const csvFile = path.join(folder, 'results.csv');
    let title = path.basename(folder);
    try {
      const identity = JSON.parse(await fs.promises.readFile(path.join(folder, '.batch.json'), 'utf8')) as { distribution?: unknown };
      if (typeof identity.distribution === 'string') title = `${path.basename(identity.distribution)} (${path.basename(folder)})`;
    } catch {
      // Without the batch's identity file the folder's name says enough.
    }
    this.panel.title = `Variations: ${title}`;
    try {
      const table = parseResultsCsv(await fs.promises.readFile(csvFile, 'utf8'));
      this.lastNotice = undefined;
      this.post({ type: 'results', title, table, runs: fs.existsSync(path.join(folder, 'runs')) });
    } catch (error) {
      const reason =
        (error as NodeJS.ErrnoException).code === 'ENOENT'
          ? 'no results.csv there (run modular2simple batch FILE --results DIR first)'
          : (error as Error).message;
      if (!(error instanceof ResultsCsvError) && (error as NodeJS.ErrnoException).code !== 'ENOENT')
        this.log(`variations view: ${(error as Error).stack ?? String(error)}`);
      this.post({ type: 'error', message: `${csvFile}: ${reason}` });
    }
  }

  /** Opens the run of one row in the bird's-eye view, as a click on the row or its point does. */
  async openRun(index: string): Promise<void> {
    if (!this.folder) return;
    const run = keptRun(this.folder, index);
    if (!fs.existsSync(run.csvPath)) {
      // In the view, not a toast: a toast would stay up after the next run, which keeps its runs.
      const notice: ToView = {
        type: 'notice',
        message: `Run ${index} was not kept: run the batch with --keep-runs (or the setting modular2simple.variations.keepRuns) to open its runs (${path.join(this.folder, 'runs', index)} does not exist).`,
      };
      this.lastNotice = notice.message;
      if (this.panel && this.ready) void this.panel.webview.postMessage(notice);
      return;
    }
    this.lastNotice = undefined;
    this.openedRun = index;
    await vscode.commands.executeCommand('modular2simple.birdsEye.showRun', run.csvPath, {
      logPath: run.logPath,
      scenario: vscode.Uri.file(run.scenario).toString(),
    });
  }

  private post(message: ToView): void {
    this.message = message;
    if (this.panel && this.ready) void this.panel.webview.postMessage(message);
  }

  private createPanel(): void {
    const scriptRoot = vscode.Uri.joinPath(this.extensionUri, 'dist');
    const panel = vscode.window.createWebviewPanel(VARIATIONS_VIEW_TYPE, 'Variations', vscode.ViewColumn.Active, {
      enableScripts: true,
      retainContextWhenHidden: true,
      localResourceRoots: [scriptRoot],
    });
    this.panel = panel;
    this.ready = false;
    panel.webview.html = variationsHtml(
      panel.webview.cspSource,
      panel.webview.asWebviewUri(vscode.Uri.joinPath(scriptRoot, 'variations.js')).toString(),
      webviewNonce(),
    );
    panel.webview.onDidReceiveMessage((message: unknown) => {
      if (isFromView(message))
        void this.receive(message).catch((error: unknown) => this.log(`variations view: ${(error as Error).stack ?? String(error)}`));
    });
    panel.onDidDispose(() => {
      this.panel = undefined;
      this.ready = false;
      this.stats = undefined;
      this.folder = undefined;
      this.csvWatcher?.dispose();
      this.csvWatcher = undefined;
    });
  }

  private async receive(message: FromView): Promise<void> {
    switch (message.type) {
      case 'ready':
        this.ready = true;
        if (this.message) this.post(this.message);
        return;
      case 'openRun':
        await this.openRun(message.index);
        return;
      case 'rendered':
        this.stats = message.stats;
        return;
    }
  }

  dispose(): void {
    clearTimeout(this.reloadTimer);
    this.csvWatcher?.dispose();
    this.panel?.dispose();
  }
}
