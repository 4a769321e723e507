import * as path from 'node:path';
import * as vscode from 'vscode';
import { webviewNonce } from '../webviewNonce';
import { writeFileAtomic } from '../../../common/src/atomic';
import type { DebugState } from '../../../common/src/debugState';
import { followStoryboard, type LiveTrace, type StoryboardEventBody } from '../../../common/src/trace';
import { RunTraceRequest, SceneRequest, type SceneResult } from '../../../common/src/sceneProtocol';
import { withTrace } from './eventList';
import { parseResolution } from './analysis';
import { programOf } from '../debugging';
import { packageEntryUri } from '../packageFileSystem';
import { appendDebugState, withSessionTrace } from './liveRun';
import { isFromView, type FromView, type RenderStats, type RunTracks, type ToView } from './messages';
import { birdsEyeHtml } from './page';
import { keptRunName, loadRun, type RunSource } from './runData';
import type { ServerCommandClient } from '../languageClient';

/** The scenario a debug session runs: its file, or the main.xosc of the .mosc package it names. */
function scenarioOfProgram(program: string): vscode.Uri {
  const file = vscode.Uri.file(program);
  return /\.mosc$/i.test(program) ? packageEntryUri(file, 'main.xosc') : file;
}

export const BIRDS_EYE_VIEW_TYPE = 'modular2simple.birdsEye';
const REFRESH_DELAY_MS = 300;
/** The webview beside the editor: one at a time, following the scenario it was opened on. */
export class BirdsEyeView implements vscode.Disposable {
  private panel: vscode.WebviewPanel | undefined;
  private source: vscode.Uri | undefined;
  private runSource: RunSource | undefined;
  private run: RunTracks | undefined;
  /** A second run compared with the first (another concrete scenario of the same logical one). */
  private compareSource: RunSource | undefined;
  private compareRun: RunTracks | undefined;
  private compareWatcher: vscode.FileSystemWatcher | undefined;
  private compareSideBySide = false;
  /** The resolution last chosen for a saved picture. */
  private exportSize = '1920x1080';
  private ready = false;
  private refreshTimer: NodeJS.Timeout | undefined;
  private runWatcher: vscode.FileSystemWatcher | undefined;
  private readonly disposables: vscode.Disposable[] = [];
  /** What the view last reported drawing; for tests and the status of a run. */
  stats: RenderStats | undefined;
  scene: SceneResult | undefined;
  private readonly renderedListeners: ((stats: RenderStats) => void)[] = [];
  private readonly exports = new Map<number, (data: string) => void>();
  private readonly timeChanged = new vscode.EventEmitter<number>();
  /** The time the view shows changed (the storyboard timeline's cursor follows it). */
  readonly onDidChangeTime = this.timeChanged.event;
  private exportCount = 0;

  constructor(
    private readonly extensionUri: vscode.Uri,
    private readonly server: ServerCommandClient,
    private readonly log: (message: string) => void,
  ) {
    const refreshSoon = (document: vscode.TextDocument) => {
      if (!this.panel || !/\.(xosc|mosc|xodr)$/i.test(document.uri.path)) return;
      clearTimeout(this.refreshTimer);
      this.refreshTimer = setTimeout(() => void this.refresh(), REFRESH_DELAY_MS);
    };
    this.disposables.push(
      vscode.workspace.onDidChangeTextDocument((change) => refreshSoon(change.document)),
      vscode.workspace.onDidSaveTextDocument(refreshSoon),
      vscode.workspace.onDidChangeConfiguration((change) => {
        if (change.affectsConfiguration('modular2simple.esmini.roadPath')) void this.refresh();
      }),
    );
  }

  get isOpen(): boolean {
    return this.panel !== undefined && this.ready;
  }

  /** Resolves with the next stats the view reports. */
  nextRender(): Promise<RenderStats> {
    return new Promise((resolve) => this.renderedListeners.push(resolve));
  }

  /**
   * A debug session's state (the adapter's custom event): the view, when open, draws the session's run so far at its
   * latest time, with the running elements highlighted. A new session starts a new run.
   */
  followDebug(sessionId: string, state: DebugState, program?: string): void {
    if (!this.panel) return;
    const shown = this.source && programOf(this.source);
    let elsewhere = program !== undefined && (!shown || path.normalize(shown) !== path.normalize(program));
    // A new session of another scenario than the one shown turns the view to it: its run drawn on its own roads and events.
    if (program !== undefined && elsewhere && this.live?.sessionId !== sessionId) {
      this.turning = this.show(scenarioOfProgram(program)).catch((error: unknown) =>
        this.log(`bird's-eye view of ${program}: ${(error as Error).stack ?? String(error)}`),
      );
      elsewhere = false;
    }
    const run = appendDebugState(this.live?.sessionId === sessionId ? this.live.run : undefined, state);
    this.live = { sessionId, run, running: state.running.map((element) => element.path), drawn: !elsewhere };
    // Turned to another scenario since: the session's run is not drawn on that one's roads.
    if (!elsewhere) this.postLive();
  }

  /** A debug session's storyboard transitions (the adapter's other custom event), kept for the starts of the events it shows. */
  followStoryboard(sessionId: string, body: StoryboardEventBody): void {
    if (!Array.isArray(body?.records)) return;
    const trace = followStoryboard(this.sessionTrace?.sessionId === sessionId ? this.sessionTrace.trace : undefined, body);
    this.sessionTrace = { sessionId, trace };
    if (body.records.length > 0 && this.panel && this.live?.sessionId === sessionId && this.live.drawn) this.postLive();
  }

  private postLive(): void {
    if (!this.live) return;
    const trace = this.sessionTrace?.sessionId === this.live.sessionId ? this.sessionTrace.trace : undefined;
    const run = withSessionTrace(this.live.run, trace);
    this.run = run;
    const message: ToView = { type: 'live', run, running: this.live.running };
    // After the turn's scene, in the order the states came.
    void this.turning.then(() => this.post(message));
  }
  private live: { sessionId: string; run: RunTracks; running: string[]; drawn: boolean } | undefined;
  private sessionTrace: { sessionId: string; trace: LiveTrace } | undefined;
  private turning: Promise<void> = Promise.resolve();

  async show(source: vscode.Uri): Promise<void> {
    if (this.source?.toString() !== source.toString()) {
      this.source = source;
      this.scene = undefined;
      // What the view drew of another scenario says nothing about this one.
      this.stats = undefined;
      // A run belongs to the scenario it was made from.
      if (this.run || this.runSource) {
        this.run = undefined;
        this.runSource = undefined;
        this.runWatcher?.dispose();
        this.runWatcher = undefined;
        this.endComparison();
        this.post({ type: 'run', run: undefined });
      }
    }
    if (!this.panel) this.createPanel();
    else this.panel.reveal(vscode.ViewColumn.Beside, true);
    this.panel!.title = `Bird's-Eye: ${(source.scheme === 'file' && keptRunName(source.fsPath)) || path.posix.basename(source.path)}`;
    await this.refresh();
  }

  /**
   * Shows a run's trajectories (e.g. handed over by the esmini run command); opens the view if needed.
   * With `compare`, the run is a second one, drawn over the first (dashed, 'overlay') or beside it
   * ('side'), on the scenario shown.
   */
  async showRun(run: RunSource, scenario?: vscode.Uri, compare?: 'overlay' | 'side'): Promise<void> {
    if (compare && this.run) {
      this.compareSideBySide = compare === 'side';
      return this.showComparison(run);
    }
    const target = scenario ?? this.source ?? vscode.window.activeTextEditor?.document.uri;
    if (target && (!this.panel || target.toString() !== this.source?.toString())) await this.show(target);
    if (!this.panel) this.createPanel();
    this.endComparison();
    this.runSource = run;
    this.runWatcher?.dispose();
    this.runWatcher = vscode.workspace.createFileSystemWatcher(
      new vscode.RelativePattern(vscode.Uri.file(path.dirname(run.csvPath)), path.basename(run.csvPath)),
    );
    this.runWatcher.onDidChange(() => void this.reloadRun());
    this.runWatcher.onDidCreate(() => void this.reloadRun());
    await this.reloadRun();
  }

  private async showComparison(run: RunSource): Promise<void> {
    this.compareSource = run;
    this.compareWatcher?.dispose();
    this.compareWatcher = vscode.workspace.createFileSystemWatcher(
      new vscode.RelativePattern(vscode.Uri.file(path.dirname(run.csvPath)), path.basename(run.csvPath)),
    );
    this.compareWatcher.onDidChange(() => void this.reloadComparison());
    this.compareWatcher.onDidCreate(() => void this.reloadComparison());
    await this.reloadComparison();
  }

  private async reloadComparison(): Promise<void> {
    if (!this.compareSource) return;
    try {
      this.compareRun = await this.readRun(this.compareSource);
    } catch (error) {
      this.compareRun = undefined;
      this.post({ type: 'error', message: `the run ${this.compareSource.csvPath} could not be read: ${(error as Error).message}` });
      this.log(`bird's-eye view: ${(error as Error).stack ?? String(error)}`);
      return;
    }
    this.post({ type: 'compare', run: this.compareRun, sideBySide: this.compareSideBySide });
  }

  /**
   * A run as the view draws it: its CSV, the road file its log names, and when each storyboard element started: from
   * the trace given (Run in esmini's), else from the log read by the language server on the scenario shown, which
   * places every line on its flattened element (each copy of a reused group its own time). A log that cannot be read
   * so leaves the run without event times, with a note saying why.
   */
  private async readRun(source: RunSource): Promise<RunTracks> {
    const loaded = await loadRun(source);
    const run = this.withAbsoluteRoad(loaded.tracks);
    if (source.trace) return withTrace(run, source.trace);
    const scenario = this.source;
    if (loaded.log === undefined || !scenario) {
      const why = loaded.log === undefined ? 'no esmini log was found beside the CSV' : 'no scenario is shown';
      return { ...run, notes: [...run.notes, `the events' start times are not known: ${why}`] };
    }
    try {
      const client = await this.server.running();
      return withTrace(run, await client.sendRequest(RunTraceRequest, { uri: scenario.toString(), log: loaded.log }));
    } catch (error) {
      this.log(`bird's-eye view: reading the log of ${source.csvPath}: ${(error as Error).stack ?? String(error)}`);
      return { ...run, notes: [...run.notes, `the events' start times could not be read from the log: ${(error as Error).message}`] };
    }
  }

  /** esmini logs the road file as the scenario wrote it (`../xodr/x.xodr`): relative to the scenario's folder, as esmini reads it. */
  private withAbsoluteRoad(run: RunTracks): RunTracks {
    if (!run.roadFile || path.isAbsolute(run.roadFile) || this.source?.scheme !== 'file') return run;
    return { ...run, roadFile: path.resolve(path.dirname(this.source.fsPath), run.roadFile) };
  }

  private endComparison(): void {
    this.compareSource = undefined;
    this.compareRun = undefined;
    this.compareWatcher?.dispose();
    this.compareWatcher = undefined;
  }

  /** Shows the run at this time, s (from the storyboard timeline). */
  setTime(time: number): void {
    this.post({ type: 'time', time });
  }

  /** Follows and plots an entity of the run (undefined: none). */
  choose(entity: string | undefined): void {
    this.post({ type: 'choose', entity });
  }

  private async reloadRun(): Promise<void> {
    if (!this.runSource) return;
    try {
      this.run = await this.readRun(this.runSource);
    } catch (error) {
      this.run = undefined;
      this.post({ type: 'error', message: `the run ${this.runSource.csvPath} could not be read: ${(error as Error).message}` });
      this.log(`bird's-eye view: ${(error as Error).stack ?? String(error)}`);
      return;
    }
    this.post({ type: 'run', run: this.run });
  }

  private async refresh(): Promise<void> {
    const source = this.source;
    if (!source || !this.panel) return;
    try {
      const client = await this.server.running();
      const roadPath = vscode.workspace.getConfiguration('modular2simple', source).get<string[]>('esmini.roadPath', []);
      const folder = vscode.workspace.getWorkspaceFolder(source)?.uri.fsPath ?? vscode.workspace.workspaceFolders?.[0]?.uri.fsPath;
      const resolvedRoadPath = roadPath
        .filter((entry) => typeof entry === 'string' && entry)
        .map((entry) => (folder ? path.resolve(folder, entry) : entry));
      const scene = await client.sendRequest(SceneRequest, { uri: source.toString(), roadPath: resolvedRoadPath });
      if (source !== this.source) return;
      this.scene = scene;
      this.post({ type: 'scene', scene });
    } catch (error) {
      this.log(`bird's-eye view of ${source.toString()}: ${(error as Error).stack ?? String(error)}`);
      this.post({ type: 'error', message: (error as Error).message });
    }
  }

  private post(message: ToView): void {
    if (this.panel && this.ready) void this.panel.webview.postMessage(message);
  }

  private createPanel(): void {
    const scriptRoot = vscode.Uri.joinPath(this.extensionUri, 'dist');
    const panel = vscode.window.createWebviewPanel(
      BIRDS_EYE_VIEW_TYPE,
      "Bird's-Eye View",
      { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
      {
        enableScripts: true,
        retainContextWhenHidden: true,
        localResourceRoots: [scriptRoot],
      },
    );
    this.panel = panel;
    this.ready = false;
    panel.webview.html = birdsEyeHtml(
      panel.webview.cspSource,
      panel.webview.asWebviewUri(vscode.Uri.joinPath(scriptRoot, 'birdsEye.js')).toString(),
      webviewNonce(),
    );
    panel.webview.onDidReceiveMessage((message: unknown) => {
      if (isFromView(message))
        void this.receive(message).catch((error: unknown) => this.log(`bird's-eye view: ${(error as Error).stack ?? String(error)}`));
    });
    panel.onDidDispose(() => {
      this.panel = undefined;
      this.ready = false;
      this.stats = undefined;
      this.runWatcher?.dispose();
      this.runWatcher = undefined;
    });
  }

  private async receive(message: FromView): Promise<void> {
    switch (message.type) {
      case 'ready':
        this.ready = true;
        if (this.scene) this.post({ type: 'scene', scene: this.scene });
        else await this.refresh();
        if (this.run) this.post({ type: 'run', run: this.run });
        if (this.compareRun) this.post({ type: 'compare', run: this.compareRun, sideBySide: this.compareSideBySide });
        return;
      case 'open': {
        const position = new vscode.Position(message.source.line, message.source.character);
        await vscode.window.showTextDocument(vscode.Uri.parse(message.source.uri), {
          viewColumn: vscode.ViewColumn.One,
          selection: new vscode.Range(position, position),
        });
        return;
      }
      case 'loadRun': {
        const picked = await vscode.window.showOpenDialog({
          canSelectMany: false,
          filters: { 'esmini CSV log': ['csv'] },
          title: 'Load an esmini run (--csv_logger output)',
        });
        if (picked?.[0]) await this.showRun({ csvPath: picked[0].fsPath }, undefined, message.compare ? 'overlay' : undefined);
        return;
      }
      case 'saveAs': {
        const size = await this.askResolution();
        if (size) await this.saveTo(message.format, undefined, size);
        return;
      }
      case 'save': {
        const exported = message.id === undefined ? undefined : this.exports.get(message.id);
        if (exported) {
          this.exports.delete(message.id!);
          exported(message.data);
        } else await this.save(message.format, message.data);
        return;
      }
      case 'time':
        this.timeChanged.fire(message.time);
        return;
      case 'rendered':
        this.stats = message.stats;
        for (const listener of this.renderedListeners.splice(0)) listener(message.stats);
        return;
    }
  }

  /**
   * Saves the picture as shown to `target` (asking where when not given); for a command or a script.
   * Resolves with the file written, or undefined when no view is open or nothing was chosen.
   */
  async saveTo(format: 'png' | 'svg', target?: vscode.Uri, size?: { width: number; height: number }): Promise<vscode.Uri | undefined> {
    if (!this.isOpen) return undefined;
    const id = ++this.exportCount;
    const data = await new Promise<string>((resolve) => {
      this.exports.set(id, resolve);
      this.post({ type: 'export', format, id, ...size });
    });
    return this.save(format, data, target);
  }

  /** Asks for the picture's width x height; remembers the answer for the next save. */
  private async askResolution(): Promise<{ width: number; height: number } | undefined> {
    const answer = await vscode.window.showInputBox({
      title: "Save the bird's-eye view",
      prompt: 'Resolution of the picture, width x height in pixels (the map, then a band with the time, a legend and a scale bar)',
      value: this.exportSize,
      validateInput: (text) => (parseResolution(text) ? undefined : 'write it as WIDTHxHEIGHT, e.g. 1920x1080 (16 to 16384 pixels each)'),
    });
    const size = answer === undefined ? undefined : parseResolution(answer);
    if (!size) return undefined;
    this.exportSize = `${size[0]}x${size[1]}`;
    return { width: size[0], height: size[1] };
  }

  private async save(format: 'png' | 'svg', data: string, given?: vscode.Uri): Promise<vscode.Uri | undefined> {
    const base = this.source ? this.source.path.replace(/\.(xosc|mosc)$/i, '') : 'birds-eye';
    const suggested = vscode.Uri.file(
      `${this.source?.scheme === 'file' ? base : path.join(vscode.workspace.workspaceFolders?.[0]?.uri.fsPath ?? '', path.posix.basename(base))}.birds-eye.${format}`,
    );
    const target =
      given ??
      (await vscode.window.showSaveDialog({
        defaultUri: suggested,
        filters: format === 'png' ? { 'PNG image': ['png'] } : { 'SVG image': ['svg'] },
      }));
    if (!target) return undefined;
    const bytes = format === 'png' ? Buffer.from(data.replace(/^data:image\/png;base64,/, ''), 'base64') : Buffer.from(data, 'utf8');
    if (target.scheme === 'file') await writeFileAtomic(target.fsPath, bytes);
    else await vscode.workspace.fs.writeFile(target, bytes);
    if (!given) void vscode.window.showInformationMessage(`Saved the bird's-eye view as ${target.fsPath}`);
    return target;
  }

  dispose(): void {
    clearTimeout(this.refreshTimer);
    this.timeChanged.dispose();
    this.runWatcher?.dispose();
    this.compareWatcher?.dispose();
    this.panel?.dispose();
    for (const disposable of this.disposables) disposable.dispose();
  }
}
