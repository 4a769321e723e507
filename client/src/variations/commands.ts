import * as vscode from 'vscode';
import { VariationsView } from './panel';

/** Registers the Variations view and its command; returns the view (for the extension's API). */
export function registerVariations(context: vscode.ExtensionContext, log: (message: string) => void): VariationsView {
  const view = new VariationsView(context.extensionUri, log);
  context.subscriptions.push(
    view,
    // Args: a results folder or its results.csv (a path or a URI, as the explorer's context menu gives); without one, asks.
    vscode.commands.registerCommand('modular2simple.showVariations', async (target?: unknown) => {
      let folder =
        typeof target === 'string' ? target : target instanceof vscode.Uri && target.scheme === 'file' ? target.fsPath : undefined;
      if (!folder) {
        const active = vscode.window.activeTextEditor?.document.uri;
        if (active?.scheme === 'file' && /(^|\/)results\.csv$/i.test(active.path)) folder = active.fsPath;
      }
      if (!folder) {
        const picked = await vscode.window.showOpenDialog({
          canSelectFiles: true,
          canSelectFolders: true,
          canSelectMany: false,
          filters: { 'Batch results': ['csv'] },
          title: 'Show Variations: a batch results folder or its results.csv',
        });
        folder = picked?.[0]?.fsPath;
        if (!folder) return;
      }
      await view.show(folder);
    }),
  );
  return view;
}
