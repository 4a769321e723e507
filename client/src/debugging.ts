import * as path from 'node:path';
import * as vscode from 'vscode';
import { PACKAGE_SCHEME } from '../../common/src/protocol';

/** The launch configuration type (package.json `debuggers`); the adapter is server/src/debug/adapter.ts. */
export const DEBUG_TYPE = 'modular2simple';

/** The scenario file a document stands for: a .xosc on disk, or the .mosc on disk holding a package entry. */
function programOf(uri: vscode.Uri): string | undefined {
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

/** Debugging scenarios in esmini's library: the adapter runs in a process of its own, so an esmini crash ends only the session. */
export function registerDebugging(context: vscode.ExtensionContext): void {
  const adapter = context.asAbsolutePath(path.join('dist', 'debugAdapter.js'));
  context.subscriptions.push(
    vscode.debug.registerDebugAdapterDescriptorFactory(DEBUG_TYPE, {
      // The editor's own Node runtime (Electron's, run as Node), so that no Node on PATH is needed.
      createDebugAdapterDescriptor: () =>
        new vscode.DebugAdapterExecutable(process.execPath, [adapter], { env: { ELECTRON_RUN_AS_NODE: '1' } }),
    }),
    vscode.debug.registerDebugConfigurationProvider(DEBUG_TYPE, new ScenarioConfigurations()),
    vscode.languages.registerEvaluatableExpressionProvider({ language: 'xosc' }, new ParameterExpressions()),
  );
}
