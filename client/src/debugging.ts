import * as path from 'node:path';
import * as vscode from 'vscode';
import { DEBUG_CODE_CACHE_ENV, DEBUG_STATE_EVENT, type DebugState, isDebugState } from '../../common/src/debugState';
import { PACKAGE_SCHEME } from '../../common/src/protocol';
import { STORYBOARD_EVENT, type StoryboardEventBody } from '../../common/src/trace';

/** The launch configuration type (package.json `debuggers`); the adapter is server/src/debug/adapter.ts. */
export const DEBUG_TYPE = 'modular2simple';

/** The scenario file a document stands for: a .xosc on disk, or the .mosc on disk holding a package entry. */
export function programOf(uri: vscode.Uri): string | undefined {
  if (uri.scheme === 'file') return uri.fsPath;
  if (uri.scheme === PACKAGE_SCHEME) {
    const index = uri.path.toLowerCase().indexOf('.mosc');
    return index >= 0 ? uri.path.slice(0, index + '.mosc'.length) : undefined;
  }
  return undefined;
}

/**
 * F5 on a scenario with no launch.json: the active file, with the folder's road path and scenario path settings.
 * A configuration that names its own program keeps it; the settings fill only what it leaves out.
 */
class ScenarioConfigurations implements vscode.DebugConfigurationProvider {
  provideDebugConfigurations(): vscode.DebugConfiguration[] {
    return [{ type: DEBUG_TYPE, request: 'launch', name: 'Debug scenario in esmini', program: '${file}' }];
  }

  resolveDebugConfiguration(
    folder: vscode.WorkspaceFolder | undefined,
    config: vscode.DebugConfiguration,
  ): vscode.DebugConfiguration | undefined {
    if (!config.type && !config.request && !config.name) {
      const active = vscode.window.activeTextEditor?.document.uri;
      const program = active ? programOf(active) : undefined;
      if (!program || !/\.(xosc|mosc)$/i.test(program)) {
        void vscode.window.showInformationMessage(
          'Open a .xosc or .mosc scenario to debug it in esmini (or add a modular2simple launch configuration).',
        );
        return undefined;
      }
      config = { type: DEBUG_TYPE, request: 'launch', name: `Debug ${path.basename(program)}`, program };
    }
    const scope = folder?.uri ?? (typeof config.program === 'string' ? vscode.Uri.file(config.program) : undefined);
    const settings = vscode.workspace.getConfiguration('modular2simple', scope);
    const base = folder?.uri.fsPath;
    const resolve = (entries: string[]) => entries.map((entry) => (base ? path.resolve(base, entry) : entry));
    config.roadPath ??= resolve(settings.get<string[]>('esmini.roadPath') ?? []);
    config.scenarioPath ??= resolve(settings.get<string[]>('scenarioPath') ?? []);
    config.esminiLibrary ??= libraryBesideEsmini(settings.get<string>('esmini.path'), base);
    if (base) config.cwd ??= base;
    return config;
  }
}

/** Hover and Watch on a `$name` while paused: the whole name, `$` included, is the expression. */
class ParameterExpressions implements vscode.EvaluatableExpressionProvider {
  provideEvaluatableExpression(document: vscode.TextDocument, position: vscode.Position): vscode.EvaluatableExpression | undefined {
    const range = document.getWordRangeAtPosition(position, /\$\{[^}]*\}|\$?[A-Za-z_][\w]*(\.[A-Za-z_]\w*)?/);
    return range ? new vscode.EvaluatableExpression(range, document.getText(range)) : undefined;
  }
}

/** The folder `esminiLibrary` is looked for in from the esmini.path setting: `lib/` beside its `bin/esmini` (esmini's build layout). */
function libraryBesideEsmini(esminiPath: string | undefined, base: string | undefined): string | undefined {
  if (!esminiPath?.trim()) return undefined;
  const resolved = base ? path.resolve(base, esminiPath.trim()) : esminiPath.trim();
  const name = path.basename(resolved).toLowerCase();
  if (name === 'esmini' || name === 'esmini.exe') return path.dirname(path.dirname(resolved));
  return name === 'bin' ? path.dirname(resolved) : resolved;
}

/**
 * Watches a session's adapter: when its process ends before it said the session ended, says so with the scenario, the
 * simulated time reached and how it ended; VS Code itself says only that the adapter terminated. esmini crashing takes
 * down only the adapter's child, and the adapter says so itself (server/src/debug/supervisor.ts): this is for the
 * adapter's own process being killed.
 */
class CrashReporter implements vscode.DebugAdapterTracker {
  private ended = false;
  private lastTime: string | undefined;

  constructor(private readonly session: vscode.DebugSession) {}

  /** Stop or Disconnect: the adapter may then be ended by the editor, which is no crash. */
  onWillReceiveMessage(message: { type?: string; command?: string }): void {
    if (message.type === 'request' && (message.command === 'disconnect' || message.command === 'terminate')) this.ended = true;
  }

  onDidSendMessage(message: { type?: string; event?: string; body?: { output?: string } }): void {
    if (message.type !== 'event') return;
    if (message.event === 'terminated' || message.event === 'exited') this.ended = true;
    // The Debug Console's transition lines start with their simulated time: `[6.50] Event CutInEvent running`.
    const time = message.event === 'output' ? /^\[([\d.]+)\]/.exec(message.body?.output ?? '') : null;
    if (time) this.lastTime = time[1];
  }

  onExit(code: number | undefined, signal: string | undefined): void {
    if (this.ended || (code === 0 && !signal)) return;
    const program =
      typeof this.session.configuration.program === 'string' ? path.basename(this.session.configuration.program) : 'the scenario';
    // VS Code gives no signal for an executable adapter, and no code when a signal ended it.
    const how = signal
      ? `was killed by ${signal}`
      : typeof code === 'number'
        ? `exited with code ${code}`
        : 'was killed by a signal (as a crash in esmini ends it)';
    const when = this.lastTime === undefined ? 'before its first storyboard transition' : `after ${this.lastTime} s of simulated time`;
    void vscode.window.showErrorMessage(
      `The debug session of ${program} ended: esmini's process ${how} ${when}. The editor is unaffected; ` +
        `the Debug Console keeps the run's last lines. Run in esmini runs the same scenario in esmini's own program, which says more when it fails.`,
    );
  }
}

/** Debugging scenarios in esmini's library: the adapter runs in a process of its own, so an esmini crash ends only the session. */
export function registerDebugging(context: vscode.ExtensionContext): void {
  const adapter = context.asAbsolutePath(path.join('dist', 'debugAdapter.js'));
  context.subscriptions.push(
    vscode.debug.registerDebugAdapterDescriptorFactory(DEBUG_TYPE, {
      // The editor's own Node runtime (Electron's, run as Node), so that no Node on PATH is needed.
      // The session keeps V8's code cache of its bundle for this runtime in the extension's storage (debug/codeCache.ts).
      createDebugAdapterDescriptor: () =>
        new vscode.DebugAdapterExecutable(process.execPath, [adapter], {
          env: { ELECTRON_RUN_AS_NODE: '1', [DEBUG_CODE_CACHE_ENV]: path.join(context.globalStorageUri.fsPath, 'debug-code-cache') },
        }),
    }),
    vscode.debug.registerDebugConfigurationProvider(DEBUG_TYPE, new ScenarioConfigurations()),
    vscode.languages.registerEvaluatableExpressionProvider({ language: 'xosc' }, new ParameterExpressions()),
    vscode.debug.registerDebugAdapterTrackerFactory(DEBUG_TYPE, { createDebugAdapterTracker: (session) => new CrashReporter(session) }),
  );
}

/** The bird's-eye view follows every scenario debug session: the adapter's state and storyboard events go to it (it draws them when open). */
export function followDebugSessions(view: {
  followDebug(sessionId: string, state: DebugState, program?: string): void;
  followStoryboard(sessionId: string, body: StoryboardEventBody): void;
}): vscode.Disposable {
  return vscode.debug.onDidReceiveDebugSessionCustomEvent((event) => {
    if (event.session.type !== DEBUG_TYPE) return;
    if (event.event === STORYBOARD_EVENT) view.followStoryboard(event.session.id, event.body as StoryboardEventBody);
    if (event.event !== DEBUG_STATE_EVENT || !isDebugState(event.body)) return;
    const program: unknown = event.session.configuration.program;
    view.followDebug(event.session.id, event.body, typeof program === 'string' && path.isAbsolute(program) ? program : undefined);
  });
}
