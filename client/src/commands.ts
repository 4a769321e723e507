import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { ProblemSummary, WriteResult } from '../../server/src/protocol';
import type { ServerCommandClient } from './languageClient';
import { packageEntryUri } from './packageFileSystem';

/** Options a caller (a test, a keybinding) may pass instead of being asked. */
export interface WriteCommandOptions {
  output?: string;
  /** Replace an existing output without asking. */
  overwrite?: boolean;
}

function isUri(value: unknown): value is vscode.Uri {
  return value instanceof vscode.Uri;
}

function isWriteOptions(value: unknown): value is WriteCommandOptions {
  // The editor title passes its own context object too; only ours names an output or overwrite.
  if (typeof value !== 'object' || value === null || isUri(value) || Array.isArray(value)) return false;
  const candidate = value as Record<string, unknown>;
  return typeof candidate.output === 'string' || typeof candidate.overwrite === 'boolean';
}

/**
 * What a command applies to: the explorer selection (clicked item, all selected items), the
 * editor title's file, or else the active editor's file.
 */
export function commandTargets(clicked: unknown, selected: unknown): vscode.Uri[] {
  if (Array.isArray(selected) && selected.length > 0 && selected.every(isUri)) return selected;
  if (isUri(clicked)) return [clicked];
  if (typeof clicked === 'string') return [vscode.Uri.parse(clicked)];
  const active = vscode.window.activeTextEditor?.document.uri;
  return active ? [active] : [];
}

export function commandOptions(...args: unknown[]): WriteCommandOptions {
  return args.find(isWriteOptions) ?? {};
}

function isDirectory(filePath: string): boolean {
  try {
    return fs.statSync(filePath).isDirectory();
  } catch {
    return false;
  }
}

/** The folder that stands for a package: the folder itself, or the folder of a `main.xosc`. */
function packageFolder(target: string): string | undefined {
  if (isDirectory(target)) return target;
  if (path.basename(target).toLowerCase() === 'main.xosc') return path.dirname(target);
  return undefined;
}

/** Beside the folder `NAME/` as `NAME.EXT`, or inside it when the folder is a workspace root. */
function besideFolder(folder: string, extension: string): string {
  const isRoot = (vscode.workspace.workspaceFolders ?? []).some((root) => root.uri.scheme === 'file' && path.resolve(root.uri.fsPath) === path.resolve(folder));
  const name = `${path.basename(folder)}${extension}`;
  return isRoot ? path.join(folder, name) : path.join(path.dirname(folder), name);
}

/** What flattening starts from: a package's `main.xosc` (inside a `.mosc`, or in a folder), or the file itself. */
export function mainFileOf(target: vscode.Uri): vscode.Uri {
  if (target.scheme === 'file' && isDirectory(target.fsPath)) return vscode.Uri.file(path.join(target.fsPath, 'main.xosc'));
  if (target.path.toLowerCase().endsWith('.mosc')) return packageEntryUri(target, 'main.xosc');
  return target;
}

export function defaultPackOutput(inputs: string[]): string {
  const main = inputs.find((input) => path.basename(input).toLowerCase() === 'main.xosc');
  const folder = inputs.length === 1 ? packageFolder(inputs[0]) : undefined;
  return besideFolder(folder ?? path.dirname(main ?? inputs[0]), '.mosc');
}

export function defaultFlattenOutput(input: string): string {
  if (input.toLowerCase().endsWith('.mosc')) return input.slice(0, -'.mosc'.length) + '.xosc';
  const folder = packageFolder(input);
  if (folder) return besideFolder(folder, '.xosc');
  return input.replace(/\.xosc$/i, '') + '.flattened.xosc';
}

/** Reports what went wrong and what to do; the details go to the output channel. */
export class CommandReporter {
  constructor(private readonly output: vscode.OutputChannel) {}

  log(message: string): void {
    this.output.appendLine(`[${new Date().toISOString()}] ${message}`);
  }

  async problems(action: string, problems: ProblemSummary[]): Promise<void> {
    this.log(`${action} failed:`);
    for (const problem of problems) {
      this.log(`  ${problem.severity} ${problem.uri}:${problem.line + 1}:${problem.character + 1} ${problem.message}${problem.hint ? ` (${problem.hint})` : ''}`);
    }
    const first = problems.find((problem) => problem.severity === 'error') ?? problems[0];
    const advice = first ? `${first.message}${first.hint ? `; ${first.hint}` : ''}` : 'the language server gave no reason';
    const choice = await vscode.window.showErrorMessage(`${action} failed: ${advice}`, ...(first ? ['Go to Problem'] : []), 'Show Details');
    if (choice === 'Show Details') this.output.show(true);
    if (choice === 'Go to Problem' && first) {
      const position = new vscode.Position(first.line, first.character);
      await vscode.window.showTextDocument(vscode.Uri.parse(first.uri), { selection: new vscode.Range(position, position) });
    }
  }

  async failure(action: string, error: unknown): Promise<void> {
    this.log(`${action} failed: ${(error as Error).stack ?? String(error)}`);
    const choice = await vscode.window.showErrorMessage(`${action} failed: ${(error as Error).message}. See the Modular2Simple output for details.`, 'Show Details');
    if (choice === 'Show Details') this.output.show(true);
  }
}

async function confirmOverwrite(output: string, options: WriteCommandOptions): Promise<boolean> {
  if (options.overwrite || !fs.existsSync(output)) return true;
  // A quick pick rather than a modal dialog: keyboard-first, and Cancel is what Enter picks.
  const replace = `Replace ${path.basename(output)}`;
  const answer = await vscode.window.showQuickPick(['Cancel', replace], {
    title: `${path.basename(output)} already exists`,
    placeHolder: `${output} already exists. Replace it?`,
    ignoreFocusOut: true,
  });
  return answer === replace;
}

async function runWrite(
  reporter: CommandReporter,
  action: string,
  output: string,
  write: (token: vscode.CancellationToken) => Promise<WriteResult>,
): Promise<string | undefined> {
  try {
    const result = await vscode.window.withProgress(
      { location: vscode.ProgressLocation.Notification, title: `${action}: ${path.basename(output)}`, cancellable: true },
      (_progress, token) => write(token),
    );
    if (result.written === null) {
      await reporter.problems(action, result.problems);
      return undefined;
    }
    reporter.log(`${action}: wrote ${result.written}`);
    for (const problem of result.problems) reporter.log(`  ${problem.severity} ${problem.uri}:${problem.line + 1} ${problem.message}`);
    void vscode.window.showInformationMessage(`${action}: wrote ${path.basename(result.written)}`, 'Open').then((choice) => {
      if (choice === 'Open' && result.written) void vscode.commands.executeCommand('vscode.open', vscode.Uri.file(result.written));
    });
    return result.written;
  } catch (error) {
    await reporter.failure(action, error);
    return undefined;
  }
}

export async function packCommand(server: ServerCommandClient, reporter: CommandReporter, clicked: unknown, selected: unknown, ...rest: unknown[]): Promise<string | undefined> {
  const targets = commandTargets(clicked, selected).filter((uri) => uri.scheme === 'file');
  if (targets.length === 0) {
    void vscode.window.showErrorMessage('Pack into .mosc: select a main.xosc, an unpacked package folder or the files to pack (one of them named main.xosc).');
    return undefined;
  }
  const options = commandOptions(clicked, selected, ...rest);
  const output = options.output ?? defaultPackOutput(targets.map((uri) => uri.fsPath));
  if (!(await confirmOverwrite(output, options))) return undefined;
  return runWrite(reporter, 'Pack into .mosc', output, (token) => server.pack(targets, output, token));
}

export async function flattenCommand(server: ServerCommandClient, reporter: CommandReporter, clicked: unknown, selected: unknown, ...rest: unknown[]): Promise<string | undefined> {
  const [target] = commandTargets(clicked, selected);
  if (!target || target.scheme !== 'file') {
    void vscode.window.showErrorMessage('Flatten to .xosc: select a .mosc package, a main.xosc or an unpacked package folder on disk.');
    return undefined;
  }
  const options = commandOptions(clicked, selected, ...rest);
  const output = options.output ?? defaultFlattenOutput(target.fsPath);
  if (!(await confirmOverwrite(output, options))) return undefined;
  return runWrite(reporter, 'Flatten to .xosc', output, async (token) => {
    const result = await server.flattenToFile(mainFileOf(target), output, token);
    if (result.needsConfirmation !== 'outsideWorkspace') return result;
    // The server writes outside the workspace only when the user agrees.
    const write = 'Write';
    const answer = await vscode.window.showWarningMessage(`${output} lies outside the workspace. Write the flattened scenario there?`, { modal: true }, write);
    return answer === write ? server.flattenToFile(mainFileOf(target), output, token, true) : result;
  });
}
