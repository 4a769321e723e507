import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { PACKAGE_SCHEME, type FlattenOptions, type ProblemSummary, type WriteResult } from '../../common/src/protocol';
import { problemPlace, writeAnywayQuestion, writtenAnywayNote } from './anyway';
import { LANGUAGE_ID, type ServerCommandClient } from './languageClient';
import { FLATTENED_SUFFIX, flattenedName } from './naming';
import { withNotificationProgress } from './notificationProgress';
import type { PlacedDiagnostics } from './placedDiagnostics';
import { exportSummary, problemLine } from './placed';
import { packageEntryUri } from './packageFileSystem';

/** Options a caller (a test, a keybinding) may pass instead of being asked. */
export interface WriteCommandOptions {
  output?: string;
  /** Replace an existing output without asking. */
  overwrite?: boolean;
  /** Pack: store the roads and catalogs inside the package (asked when no output is named). */
  selfContained?: boolean;
}

function isUri(value: unknown): value is vscode.Uri {
  return value instanceof vscode.Uri;
}

function isWriteOptions(value: unknown): value is WriteCommandOptions {
  // The editor title passes its own context object too; only ours names an output or overwrite.
  if (typeof value !== 'object' || value === null || isUri(value) || Array.isArray(value)) return false;
  const candidate = value as Record<string, unknown>;
  return typeof candidate.output === 'string' || typeof candidate.overwrite === 'boolean' || typeof candidate.selfContained === 'boolean';
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
  const isRoot = (vscode.workspace.workspaceFolders ?? []).some(
    (root) => root.uri.scheme === 'file' && path.resolve(root.uri.fsPath) === path.resolve(folder),
  );
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

/** Where Flatten proposes to write: `<package>.flattened.xosc` (see naming.ts) beside the package, or inside it when it is a workspace root. */
export function defaultFlattenOutput(input: string): string {
  const folder = packageFolder(input);
  if (folder) return besideFolder(folder, FLATTENED_SUFFIX);
  return path.join(path.dirname(input), flattenedName(vscode.Uri.file(input)));
}

/** Reports what went wrong and what to do; the details go to the output channel. */
export class CommandReporter {
  constructor(private readonly output: vscode.OutputChannel) {}

  log(message: string): void {
    this.output.appendLine(`[${new Date().toISOString()}] ${message}`);
  }

  show(): void {
    this.output.show(true);
  }

  async problems(action: string, problems: ProblemSummary[]): Promise<void> {
    this.log(`${action} failed:`);
    for (const problem of problems) {
      this.log(
        `  ${problem.severity} ${problem.uri}:${problem.line + 1}:${problem.character + 1} ${problem.message}${problem.hint ? ` (${problem.hint})` : ''}`,
      );
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

  /** `problems` without waiting for the user: the command goes on while the message stays; a failure to show it is logged. */
  problemsWithoutWaiting(action: string, problems: ProblemSummary[]): void {
    this.problems(action, problems).catch((error: unknown) =>
      this.log(`${action}: its message could not be shown: ${(error as Error).stack ?? String(error)}`),
    );
  }

  async failure(action: string, error: unknown): Promise<void> {
    this.log(`${action} failed: ${(error as Error).stack ?? String(error)}`);
    const choice = await vscode.window.showErrorMessage(
      `${action} failed: ${(error as Error).message}. See the Modular2Simple output for details.`,
      'Show Details',
    );
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

/**
 * Where to write: the output a caller named (asking before replacing a file), or the place the
 * user picks in a save dialog that proposes the conventional name (the dialog asks about replacing).
 */
async function chooseOutput(
  action: string,
  proposed: string,
  options: WriteCommandOptions,
  filters: Record<string, string[]>,
): Promise<string | undefined> {
  if (options.output) return (await confirmOverwrite(options.output, options)) ? options.output : undefined;
  const picked = await vscode.window.showSaveDialog({
    defaultUri: vscode.Uri.file(proposed),
    filters,
    saveLabel: action.split(' ')[0],
    title: action,
  });
  if (!picked) return undefined;
  return picked.scheme === 'file' ? picked.fsPath : picked.path;
}

type WriteOutcome = { result: WriteResult } | { error: unknown };

async function withWriteProgress(
  action: string,
  output: string,
  write: (token: vscode.CancellationToken) => Promise<WriteResult>,
): Promise<WriteOutcome> {
  try {
    return {
      result: await withNotificationProgress(`${action}: ${path.basename(output)}`, (_progress, token) => write(token)),
    };
  } catch (error) {
    return { error };
  }
}

function reportWritten(reporter: CommandReporter, action: string, result: WriteResult & { written: string }, note = ''): string {
  reporter.log(`${action}: wrote ${result.written}${note}`);
  for (const problem of result.problems) reporter.log(`  ${problem.severity} ${problem.uri}:${problem.line + 1} ${problem.message}`);
  void vscode.window.showInformationMessage(`${action}: wrote ${path.basename(result.written)}${note}`, 'Open').then((choice) => {
    if (choice === 'Open') void vscode.commands.executeCommand('vscode.open', vscode.Uri.file(result.written));
  });
  return result.written;
}

async function runWrite(
  reporter: CommandReporter,
  action: string,
  output: string,
  write: (token: vscode.CancellationToken) => Promise<WriteResult>,
  note = '',
): Promise<string | undefined> {
  const outcome = await withWriteProgress(action, output, write);
  if ('error' in outcome) {
    await reporter.failure(action, outcome.error);
    return undefined;
  }
  const { result } = outcome;
  if (result.written === null) {
    await reporter.problems(action, result.problems);
    return undefined;
  }
  return reportWritten(reporter, action, { ...result, written: result.written }, note);
}

/** Scenario files with unsaved changes, on disk or inside packages: Pack saves them first, so the package holds what the editor shows. */
function unsavedScenarios(): vscode.TextDocument[] {
  return vscode.workspace.textDocuments.filter(
    (document) =>
      document.isDirty && document.languageId === LANGUAGE_ID && (document.uri.scheme === 'file' || document.uri.scheme === PACKAGE_SCHEME),
  );
}

/** Saves the unsaved scenario files; answers their names, or undefined when one could not be saved. */
async function saveScenarios(reporter: CommandReporter, action: string): Promise<string[] | undefined> {
  const saved: string[] = [];
  for (const document of unsavedScenarios()) {
    const name = path.posix.basename(document.uri.path);
    if (!(await document.save())) {
      reporter.log(`${action}: could not save ${document.uri.toString()}`);
      void vscode.window.showErrorMessage(
        `${action}: ${name} has unsaved changes and could not be saved, so nothing was packed. Save it, then pack again.`,
      );
      return undefined;
    }
    saved.push(name);
  }
  return saved;
}

/** Whether a package carries the road networks and catalogs its scenarios name; undefined when the user cancels. */
async function chooseSelfContained(): Promise<boolean | undefined> {
  const outside = {
    label: 'Reference roads and catalogs where they are',
    detail: 'the package names them relative to its folder; it runs only beside them',
    selfContained: false,
  };
  const inside = {
    label: 'Store roads and catalogs inside the package',
    detail: 'self-contained: the package runs wherever it is copied',
    selfContained: true,
  };
  const picked = await vscode.window.showQuickPick([outside, inside], {
    title: 'Pack into .mosc',
    placeHolder: 'Files the scenarios name outside the package',
    ignoreFocusOut: true,
  });
  return picked?.selfContained;
}

export async function packCommand(
  server: ServerCommandClient,
  reporter: CommandReporter,
  clicked: unknown,
  selected: unknown,
  ...rest: unknown[]
): Promise<string | undefined> {
  const targets = commandTargets(clicked, selected).filter((uri) => uri.scheme === 'file');
  if (targets.length === 0) {
    void vscode.window.showErrorMessage(
      'Pack into .mosc: select a main.xosc, an unpacked package folder or the files to pack (one of them named main.xosc).',
    );
    return undefined;
  }
  const options = commandOptions(clicked, selected, ...rest);
  const selfContained = options.selfContained ?? (options.output !== undefined ? false : await chooseSelfContained());
  if (selfContained === undefined) return undefined;
  const output = await chooseOutput('Pack into .mosc', defaultPackOutput(targets.map((uri) => uri.fsPath)), options, {
    'OpenSCENARIO package': ['mosc'],
  });
  if (!output) return undefined;
  // A package holds what the editor shows: unsaved scenario files are saved first, and the message says which.
  const saved = await saveScenarios(reporter, 'Pack into .mosc');
  if (!saved) return undefined;
  const note = saved.length > 0 ? ` (saved ${saved.join(', ')} first)` : '';
  return runWrite(
    reporter,
    'Pack into .mosc',
    output,
    async (token) => {
      const result = await server.pack(targets, output, token, selfContained);
      // Said when written, not only later in Problems: a package that reaches outside itself runs only beside those files
      // (pack's one file-path warning, core/pack.ts).
      const outside =
        result.written === null ? [] : result.problems.filter((problem) => problem.severity === 'warning' && problem.code === 'file-path');
      if (outside.length > 0) {
        void vscode.window.showWarningMessage(
          `Pack into .mosc: ${problemPlace(outside[0])}${outside.length > 1 ? `; and ${outside.length - 1} more` : ''}. Pack again storing roads and catalogs inside the package to carry them.`,
        );
      }
      return result;
    },
    note,
  );
}

/** Sends a write; where the server asks first (an output outside the workspace), asks the user and sends it again if agreed. */
async function writeConfirmingOutside(
  output: string,
  what: string,
  send: (outsideWorkspace: boolean) => Promise<WriteResult>,
): Promise<WriteResult> {
  const result = await send(false);
  if (result.needsConfirmation !== 'outsideWorkspace') return result;
  const write = 'Write';
  const answer = await vscode.window.showWarningMessage(
    `${output} lies outside the workspace. Write ${what} there?`,
    { modal: true },
    write,
  );
  return answer === write ? send(true) : result;
}

export async function flattenCommand(
  server: ServerCommandClient,
  reporter: CommandReporter,
  clicked: unknown,
  selected: unknown,
  ...rest: unknown[]
): Promise<string | undefined> {
  const [target] = commandTargets(clicked, selected);
  if (!target || target.scheme !== 'file') {
    void vscode.window.showErrorMessage('Flatten to .xosc: select a .mosc package, a main.xosc or an unpacked package folder on disk.');
    return undefined;
  }
  const options = commandOptions(clicked, selected, ...rest);
  const action = 'Flatten to .xosc';
  const output = await chooseOutput(action, defaultFlattenOutput(target.fsPath), options, { OpenSCENARIO: ['xosc'] });
  if (!output) return undefined;
  const main = mainFileOf(target);
  // The server writes outside the workspace only when the user agrees.
  const flattenTo = (options: FlattenOptions, token: vscode.CancellationToken): Promise<WriteResult> =>
    writeConfirmingOutside(output, 'the flattened scenario', (outside) => server.flattenToFile(main, output, options, token, outside));
  const outcome = await withWriteProgress(action, output, (token) => flattenTo({}, token));
  if ('error' in outcome) {
    await reporter.failure(action, outcome.error);
    return undefined;
  }
  if (outcome.result.written !== null) return reportWritten(reporter, action, { ...outcome.result, written: outcome.result.written });
  // Refused for its errors: when a forced flatten produces an output, offer what --force does, naming the errors.
  const problems = outcome.result.problems;
  const forced = await server.flattenToText(main, { force: true }).catch(() => undefined);
  if (!forced || forced.text === null) {
    await reporter.problems(action, problems);
    return undefined;
  }
  reporter.log(`${action} refused; writing anyway would keep these errors:`);
  for (const problem of problems.filter((candidate) => candidate.severity === 'error'))
    reporter.log(`  ${problem.uri}:${problem.line + 1}:${problem.character + 1} ${problem.message}`);
  const writeAnyway = 'Write Anyway';
  const choice = await vscode.window.showWarningMessage(writeAnywayQuestion(action, problems), writeAnyway, 'Go to Problem');
  if (choice === 'Go to Problem') {
    const first = problems.find((problem) => problem.severity === 'error');
    if (first)
      await vscode.window.showTextDocument(vscode.Uri.parse(first.uri), {
        selection: new vscode.Range(first.line, first.character, first.line, first.character),
      });
    return undefined;
  }
  if (choice !== writeAnyway) return undefined;
  return runWrite(reporter, action, output, (token) => flattenTo({ force: true }, token), writtenAnywayNote(problems));
}

/** The output proposed for an export for CARLA: `<name>.carla.xosc` beside the scenario (or its package). */
function defaultCarlaOutput(input: string): string {
  const flattened = defaultFlattenOutput(input);
  return flattened.replace(/(\.flattened)?\.xosc$/i, '.carla.xosc');
}

/**
 * *Export for CARLA…*: asks for the output, has the server write OpenSCENARIO 1.0 for ScenarioRunner
 * (modular2simple/exportForCarla); the loss report lands as diagnostics on the source lines (replacing the previous
 * export's) and in the output channel; a refusal names its reasons and writes nothing.
 */
export async function exportForCarlaCommand(
  server: ServerCommandClient,
  reporter: CommandReporter,
  losses: PlacedDiagnostics,
  clicked: unknown,
  selected: unknown,
  ...rest: unknown[]
): Promise<string | undefined> {
  const [target] = commandTargets(clicked, selected);
  if (!target || (target.scheme !== 'file' && target.scheme !== PACKAGE_SCHEME)) {
    void vscode.window.showErrorMessage(
      'Export for CARLA: open or select a .xosc, a main.xosc, a .mosc or an unpacked package folder first.',
    );
    return undefined;
  }
  const action = 'Export for CARLA';
  const options = commandOptions(clicked, selected, ...rest);
  const input = target.scheme === 'file' ? target.fsPath : (target.path.split(/\.mosc\//i)[0] ?? target.path) + '.mosc';
  const output = await chooseOutput(action, defaultCarlaOutput(input), options, { OpenSCENARIO: ['xosc'] });
  if (!output) return undefined;
  losses.clear();
  const exportTo = (token: vscode.CancellationToken): Promise<WriteResult> =>
    writeConfirmingOutside(output, 'the export', (outside) => server.exportForCarla(target, output, token, outside));
  const outcome = await withWriteProgress(action, output, exportTo);
  if ('error' in outcome) {
    await reporter.failure(action, outcome.error);
    return undefined;
  }
  const { result } = outcome;
  if (result.needsConfirmation) return undefined;
  losses.replace(result.problems);
  reporter.log(`${action} of ${target.toString(true)}: ${exportSummary(result.written, result.problems)}`);
  for (const problem of result.problems) reporter.log(`  ${problemLine(problem)}`);
  if (result.written !== null) {
    const written = result.written;
    void vscode.window
      .showInformationMessage(`${action}: ${exportSummary(written, result.problems)}`, 'Open', 'Show Report')
      .then((choice) => {
        if (choice === 'Open') void vscode.commands.executeCommand('vscode.open', vscode.Uri.file(written));
        if (choice === 'Show Report') reporter.show();
      });
    return written;
  }
  // The command answers now, while its message (with Go to Problem) stays until the user dismisses it.
  reporter.problemsWithoutWaiting(action, result.problems);
  return undefined;
}
