import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { webviewNonce } from '../webviewNonce';
import { storyboardTimeline, type Timeline } from '../../../common/src/storyboardTimeline';
import {
  followStoryboard,
  type LiveTrace,
  parseTrace,
  STORYBOARD_EVENT,
  type StoryboardEventBody,
  type TraceRecord,
} from '../../../common/src/trace';
import { DEBUG_TYPE } from '../debugging';
import { packageEntryUri } from '../packageFileSystem';
import { isFromView, type FromView, type TimelineStats, type ToView } from './messages';
import { timelineHtml } from './page';

export const TIMELINE_VIEW_TYPE = 'modular2simple.timeline';
/** A live session's timeline is redrawn at most this often. */
const LIVE_REDRAW_MS = 150;

/** Where a trace came from: its records, a label, the run's end, and the folder its relative file names start from. */
export interface TraceSource {
  records: TraceRecord[];
  label: string;
  /** The run's end, s (when the trace's last record is earlier). */
  end?: number;
  /** The folders a relative `file` is looked up in, first found wins. */
  bases: string[];
}

/** The time shown in the bird's-eye view, both ways: the timeline's cursor follows it and a click on the timeline sets it. */
export interface SharedTime {
  setTime(time: number): void;
  readonly onDidChangeTime: vscode.Event<number>;
}

/** The storyboard timeline beside the editor: one at a time, of a finished run's trace or of the debug session running. */
export class TimelineView implements vscode.Disposable {
  private panel: vscode.WebviewPanel | undefined;
  private ready = false;
  private source: TraceSource | undefined;
  private timeline: Timeline | undefined;
  private live = false;
  /** The debug session the timeline follows or last followed, and its current run's trace. */
  private liveSession: string | undefined;
  private liveTrace: LiveTrace | undefined;
  private liveProgram = '';
  private time = 0;
  private redrawTimer: NodeJS.Timeout | undefined;
  private readonly disposables: vscode.Disposable[] = [];
  private readonly renderedListeners: ((stats: TimelineStats) => void)[] = [];
  /** What the view last reported drawing; for tests. */
  stats: TimelineStats | undefined;
  /** The source last opened from the view; for tests. */
  opened: vscode.Uri | undefined;

  constructor(
    private readonly extensionUri: vscode.Uri,
    private readonly log: (message: string) => void,
    private readonly shared?: SharedTime,
  ) {
    if (shared) this.disposables.push(shared.onDidChangeTime((time) => this.setTime(time)));
    this.disposables.push(
      // VS Code may deliver the session's first events (the Story's start at 0 s, sent while it launches) before it
      // says the session started: whichever comes first starts the session's timeline, the other keeps it.
      vscode.debug.onDidStartDebugSession((session) => {
        if (session.type === DEBUG_TYPE && session.id !== this.liveSession) this.startLive(session);
      }),
      vscode.debug.onDidReceiveDebugSessionCustomEvent((event) => {
        if (event.session.type !== DEBUG_TYPE || event.event !== STORYBOARD_EVENT) return;
        if (event.session.id !== this.liveSession) this.startLive(event.session);
        this.liveEvent(event.body as StoryboardEventBody);
      }),
      vscode.debug.onDidTerminateDebugSession((session) => {
        if (session.type === DEBUG_TYPE && session.id === this.liveSession && this.live) {
          this.live = false;
          // The run ends where the session last said it was (the adapter sends that time as it ends), not at its limit.
          if (this.source) this.source.end = this.time;
          this.redraw();
        }
      }),
    );
  }

  get isOpen(): boolean {
    return this.panel !== undefined && this.ready;
  }

  get hasTrace(): boolean {
    return this.source !== undefined;
  }

  /** Resolves with the next stats the view reports. */
  nextRender(): Promise<TimelineStats> {
    return new Promise((resolve) => this.renderedListeners.push(resolve));
  }

  /** Shows a finished run's trace, opening the view if needed. */
  show(source: TraceSource): void {
    this.source = source;
    this.live = false;
    this.timeline = storyboardTimeline(source.records, source.end);
    this.reveal();
    this.post({ type: 'timeline', timeline: this.timeline, label: source.label, live: false });
  }

  /** Keeps the trace of a run (made in the background) for when the timeline is asked for; shown at once when the view is open. */
  offer(source: TraceSource): void {
    if (this.panel) this.show(source);
    else {
      this.source = source;
      this.live = false;
      this.timeline = storyboardTimeline(source.records, source.end);
      void vscode.commands.executeCommand('setContext', 'modular2simple.hasTimeline', true);
    }
  }

  /** Opens the view on what it holds (the last run's or session's trace); false when it holds none. */
  showLast(): boolean {
    if (!this.source) return false;
    this.reveal();
    this.redraw();
    return true;
  }

  /** Reads a `run --trace` file; an unreadable or malformed file is said, naming its line. */
  async showFile(file: string): Promise<void> {
    const text = await fs.promises.readFile(file, 'utf8');
    const folders = (vscode.workspace.workspaceFolders ?? []).map((folder) => folder.uri.fsPath);
    // run --trace writes files relative to where it ran: the workspace's folders, else the trace's own folder.
    this.show({ records: parseTrace(text, file), label: path.basename(file), bases: [...folders, path.dirname(file)] });
  }

  setTime(time: number): void {
    this.time = time;
    this.post({ type: 'time', time });
  }

  private startLive(session: vscode.DebugSession): void {
    const program = typeof session.configuration.program === 'string' ? session.configuration.program : session.name;
    this.liveProgram = path.basename(program);
    this.source = { records: [], label: `debugging ${this.liveProgram}`, bases: [] };
    this.liveSession = session.id;
    this.liveTrace = undefined;
    this.live = true;
    this.timeline = storyboardTimeline([]);
    this.redraw();
  }

  private liveEvent(body: StoryboardEventBody): void {
    if (!this.source || !this.live || !Array.isArray(body?.records)) return;
    const previous = this.liveTrace;
    this.liveTrace = followStoryboard(previous, body);
    // A restarted session: its new run alone, said in the title, never mixed with the run before.
    const restarted = previous !== undefined && this.liveTrace !== previous;
    if (restarted || !previous)
      this.source = {
        records: this.liveTrace.records,
        label: `debugging ${this.liveProgram}${this.liveTrace.run > 1 ? `, run ${this.liveTrace.run} (restarted)` : ''}`,
        bases: [],
      };
    this.time = this.liveTrace.time;
    clearTimeout(this.redrawTimer);
    // Redrawn after a burst of steps, and at once when the session stops (no records) or restarts.
    if (body.records.length === 0 || restarted) this.redraw();
    else this.redrawTimer = setTimeout(() => this.redraw(), LIVE_REDRAW_MS);
  }

  private redraw(): void {
    if (!this.source) return;
    // The editor title offers the timeline once there is one to show.
    void vscode.commands.executeCommand('setContext', 'modular2simple.hasTimeline', true);
    this.timeline = storyboardTimeline(this.source.records, this.live ? this.time : this.source.end);
    this.post({ type: 'timeline', timeline: this.timeline, label: this.source.label, live: this.live });
    this.post({ type: 'time', time: this.time });
  }

  private reveal(): void {
    if (!this.panel) this.createPanel();
    else this.panel.reveal(vscode.ViewColumn.Beside, true);
  }

  private post(message: ToView): void {
    if (this.panel && this.ready) void this.panel.webview.postMessage(message);
  }

  private createPanel(): void {
    const scriptRoot = vscode.Uri.joinPath(this.extensionUri, 'dist');
    const panel = vscode.window.createWebviewPanel(
      TIMELINE_VIEW_TYPE,
      'Storyboard Timeline',
      { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
      { enableScripts: true, retainContextWhenHidden: true, localResourceRoots: [scriptRoot] },
    );
    this.panel = panel;
    this.ready = false;
    panel.webview.html = timelineHtml(
      panel.webview.cspSource,
      panel.webview.asWebviewUri(vscode.Uri.joinPath(scriptRoot, 'timeline.js')).toString(),
      webviewNonce(),
    );
    panel.webview.onDidReceiveMessage((message: unknown) => {
      if (isFromView(message))
        void this.receive(message).catch((error: unknown) => this.log(`storyboard timeline: ${(error as Error).stack ?? String(error)}`));
    });
    panel.onDidDispose(() => {
      this.panel = undefined;
      this.ready = false;
      this.stats = undefined;
    });
  }

  private async receive(message: FromView): Promise<void> {
    switch (message.type) {
      case 'ready':
        this.ready = true;
        this.redraw();
        return;
      case 'open':
        return this.open(message.element);
      case 'time':
        this.setTime(message.time);
        this.shared?.setTime(message.time);
        return;
      case 'rendered':
        this.stats = message.stats;
        for (const listener of this.renderedListeners.splice(0)) listener(message.stats);
        return;
    }
  }

  /** Opens a row's element where it is written (the simple scenario for an imported group). */
  private async open(element: string): Promise<void> {
    const row = this.timeline?.rows.find((candidate) => candidate.element === element);
    if (!row?.file) {
      void vscode.window.showInformationMessage(`The trace does not say where ${element} is written.`);
      return;
    }
    const uri = this.uriOf(row.file);
    if (!uri) {
      void vscode.window.showErrorMessage(
        `Storyboard timeline: ${row.file} (of ${element}) is not found${this.source?.bases.length ? ` in ${this.source.bases.join(', ')}` : ''}.`,
      );
      return;
    }
    const position = new vscode.Position(Math.max(0, (row.line ?? 1) - 1), 0);
    this.opened = uri;
    await vscode.window.showTextDocument(uri, { viewColumn: vscode.ViewColumn.One, selection: new vscode.Range(position, position) });
  }

  /** A trace's `file`: a path, or a path inside a .mosc (`pkg.mosc/main.xosc`), absolute or relative to one of the bases. */
  private uriOf(file: string): vscode.Uri | undefined {
    const candidates = path.isAbsolute(file) ? [file] : (this.source?.bases ?? []).map((base) => path.resolve(base, file));
    for (const candidate of candidates) {
      const inPackage = /^(.*?\.mosc)[\\/](.+)$/i.exec(candidate);
      if (inPackage && fs.existsSync(inPackage[1]))
        return packageEntryUri(vscode.Uri.file(inPackage[1]), inPackage[2].replaceAll('\\', '/'));
      if (fs.existsSync(candidate)) return vscode.Uri.file(candidate);
    }
    return undefined;
  }

  dispose(): void {
    clearTimeout(this.redrawTimer);
    this.panel?.dispose();
    for (const disposable of this.disposables) disposable.dispose();
  }
}

/** Registers the timeline and its command; returns the view (for the extension's API). */
export function registerTimeline(context: vscode.ExtensionContext, log: (message: string) => void, shared?: SharedTime): TimelineView {
  const view = new TimelineView(context.extensionUri, log, shared);
  context.subscriptions.push(
    view,
    // args: a run --trace file (path or URI); without one, the active .jsonl, else the last run's or session's trace, else asks for a file.
    vscode.commands.registerCommand('modular2simple.showTimeline', async (target?: unknown) => {
      let file = typeof target === 'string' ? target : target instanceof vscode.Uri && target.scheme === 'file' ? target.fsPath : undefined;
      const active = vscode.window.activeTextEditor?.document.uri;
      if (!file && active?.scheme === 'file' && /\.jsonl$/i.test(active.path)) file = active.fsPath;
      if (!file && view.showLast()) return true;
      if (!file) {
        const picked = await vscode.window.showOpenDialog({
          canSelectMany: false,
          filters: { 'Storyboard trace (run --trace)': ['jsonl'] },
          title: 'Open a storyboard trace (modular2simple run SCENARIO --trace OUT.jsonl), or Run in esmini / debug a scenario first',
        });
        file = picked?.[0]?.fsPath;
        if (!file) return false;
      }
      try {
        await view.showFile(file);
        return true;
      } catch (error) {
        log(`storyboard timeline: ${(error as Error).stack ?? String(error)}`);
        void vscode.window.showErrorMessage(`Storyboard timeline: ${(error as Error).message}`);
        return false;
      }
    }),
  );
  return view;
}
