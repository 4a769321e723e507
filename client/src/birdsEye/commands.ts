import * as vscode from 'vscode';
import type { ServerCommandClient } from '../languageClient';
import { commandTargets } from '../commands';
import { packageEntryUri } from '../packageFileSystem';
import { BirdsEyeView } from './panel';
import type { TraceRecord } from '../../../common/src/trace';
import type { RunCollision } from '../../../common/src/collisions';
import type { RunSource } from './runData';

/** Registers the bird's-eye view and its commands; returns the view (for the extension's API). */
export function registerBirdsEye(
  context: vscode.ExtensionContext,
  server: ServerCommandClient,
  log: (message: string) => void,
): BirdsEyeView {
  const view = new BirdsEyeView(context.extensionUri, server, log);
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
    // For the run command (args: csvPath, { logPath?, logText?, trace?, scenario?, compare?, roadFile? }) and for a person (picks a CSV);
    // `compare: true` or 'overlay' draws it over the run shown (dashed), 'side' beside it.
    vscode.commands.registerCommand('modular2simple.birdsEye.showRun', async (csvPath?: unknown, options?: unknown) => {
      let path = typeof csvPath === 'string' ? csvPath : csvPath instanceof vscode.Uri ? csvPath.fsPath : undefined;
      if (!path) {
        const picked = await vscode.window.showOpenDialog({
          canSelectMany: false,
          filters: { 'esmini CSV log': ['csv'] },
          title: 'Load an esmini run (--csv_logger output)',
        });
        path = picked?.[0]?.fsPath;
        if (!path) return;
      }
      const given = (options && typeof options === 'object' ? options : {}) as {
        logPath?: unknown;
        logText?: unknown;
        trace?: unknown;
        scenario?: unknown;
        compare?: unknown;
        roadFile?: unknown;
        label?: unknown;
        until?: unknown;
        collisions?: unknown;
      };
      const run: RunSource = { csvPath: path };
      if (typeof given.roadFile === 'string') run.roadFile = given.roadFile;
      if (typeof given.label === 'string') run.label = given.label;
      if (typeof given.until === 'number' && Number.isFinite(given.until)) run.until = given.until;
      if (typeof given.logPath === 'string') run.logPath = given.logPath;
      if (typeof given.logText === 'string') run.logText = given.logText;
      if (Array.isArray(given.collisions)) run.collisions = given.collisions as RunCollision[];
      // Run in esmini's trace (common/src/trace.ts records), already placed on the flattened elements.
      if (Array.isArray(given.trace)) run.trace = given.trace as TraceRecord[];
      const scenario =
        typeof given.scenario === 'string'
          ? vscode.Uri.parse(given.scenario)
          : given.scenario instanceof vscode.Uri
            ? given.scenario
            : undefined;
      await view.showRun(
        run,
        scenario,
        given.compare === true || given.compare === 'overlay' ? 'overlay' : given.compare === 'side' ? 'side' : undefined,
      );
    }),
    // Saves the picture shown (args: 'png' | 'svg', target path or URI, { width, height }; without a target, asks where; without a size, the panel's).
    vscode.commands.registerCommand('modular2simple.birdsEye.save', async (format?: unknown, target?: unknown, resolution?: unknown) => {
      const kind = format === 'svg' ? 'svg' : 'png';
      const uri = typeof target === 'string' ? vscode.Uri.file(target) : target instanceof vscode.Uri ? target : undefined;
      if (!view.isOpen) {
        void vscode.window.showErrorMessage("Save the bird's-eye view: open it first (Show Bird's-Eye View).");
        return undefined;
      }
      const given = (resolution && typeof resolution === 'object' ? resolution : {}) as { width?: unknown; height?: unknown };
      const size =
        typeof given.width === 'number' &&
        typeof given.height === 'number' &&
        given.width >= 16 &&
        given.height >= 16 &&
        given.width <= 16384 &&
        given.height <= 16384
          ? { width: Math.round(given.width), height: Math.round(given.height) }
          : undefined;
      return view.saveTo(kind, uri, size);
    }),
  );
  return view;
}
