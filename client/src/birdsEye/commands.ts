import * as vscode from 'vscode';
import type { LanguageClient } from 'vscode-languageclient/node';
import { commandTargets } from '../commands';
import { packageEntryUri } from '../packageFileSystem';
import { BirdsEyeView } from './panel';
import type { RunSource } from './runData';

/** Registers the bird's-eye view and its commands; returns the view (for the extension's API). */
export function registerBirdsEye(context: vscode.ExtensionContext, client: LanguageClient, log: (message: string) => void): BirdsEyeView {
  const view = new BirdsEyeView(context.extensionUri, client, log);
  context.subscriptions.push(
    view,
    vscode.commands.registerCommand('modular2simple.showBirdsEye', async (clicked: unknown) => {
      let [source] = commandTargets(clicked, undefined);
      if (!source) {
        void vscode.window.showErrorMessage("Show Bird's-Eye View: open an OpenSCENARIO file (.xosc) or a .mosc first.");
        return;
      }
      // A package stands for its main.xosc, read through the mosc: file system.
      if (source.scheme === 'file' && source.path.toLowerCase().endsWith('.mosc')) source = packageEntryUri(source, 'main.xosc');
      await view.show(source);
    }),
    // For the run command (args: csvPath, { logPath?, logText?, scenario? }) and for a person (picks a CSV).
    vscode.commands.registerCommand('modular2simple.birdsEye.showRun', async (csvPath?: unknown, options?: unknown) => {
      let path = typeof csvPath === 'string' ? csvPath : csvPath instanceof vscode.Uri ? csvPath.fsPath : undefined;
      if (!path) {
        const picked = await vscode.window.showOpenDialog({ canSelectMany: false, filters: { 'esmini CSV log': ['csv'] }, title: 'Load an esmini run (--csv_logger output)' });
        path = picked?.[0]?.fsPath;
        if (!path) return;
      }
      const given = (options && typeof options === 'object' ? options : {}) as { logPath?: unknown; logText?: unknown; scenario?: unknown };
      const run: RunSource = { csvPath: path };
      if (typeof given.logPath === 'string') run.logPath = given.logPath;
      if (typeof given.logText === 'string') run.logText = given.logText;
      const scenario = typeof given.scenario === 'string' ? vscode.Uri.parse(given.scenario) : given.scenario instanceof vscode.Uri ? given.scenario : undefined;
      await view.showRun(run, scenario);
    }),
  );
  return view;
}
