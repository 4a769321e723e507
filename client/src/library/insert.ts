import * as path from 'node:path';
import * as vscode from 'vscode';
import type { LibraryModuleSummary } from '../../../common/src/libraryProtocol';
import type { CommandReporter } from '../commands';
import { LANGUAGE_ID, type ServerCommandClient } from '../languageClient';

const TITLE = 'Insert into Main';

/** What a caller (a test, the code action) may pass instead of being asked. */
export interface InsertOptions {
  /** The main, a URI or its string; else the active scenario editor (or the last one). */
  main?: vscode.Uri | string;
  /** `Story/Act`; asked when the main has several. */
  act?: string;
  /** *Insert library module here…*: the position in the main (its Act and the group the new one follows); no Act is asked. */
  position?: { line: number; character: number };
  /** The main's entity for each role of the module; a role without one is asked (unless the main has an entity of its name). */
  players?: Record<string, string>;
}

export function isInsertOptions(value: unknown): value is InsertOptions {
  if (typeof value !== 'object' || value === null || value instanceof vscode.Uri || Array.isArray(value)) return false;
  const candidate = value as Record<string, unknown>;
  return (
    candidate.main !== undefined ||
    typeof candidate.act === 'string' ||
    typeof candidate.players === 'object' ||
    typeof candidate.position === 'object'
  );
}

/** The scenario editor last active: clicking in the library view or its detail page leaves the main it is for. */
export class MainTracker implements vscode.Disposable {
  private last: vscode.Uri | undefined;
  private readonly subscription: vscode.Disposable;

  constructor() {
    this.remember(vscode.window.activeTextEditor);
    this.subscription = vscode.window.onDidChangeActiveTextEditor((editor) => this.remember(editor));
  }

  private remember(editor: vscode.TextEditor | undefined): void {
    if (editor?.document.languageId === LANGUAGE_ID) this.last = editor.document.uri;
  }

  get main(): vscode.Uri | undefined {
    const active = vscode.window.activeTextEditor?.document;
    if (active?.languageId === LANGUAGE_ID) return active.uri;
    return this.last && vscode.workspace.textDocuments.some((document) => document.uri.toString() === this.last?.toString())
      ? this.last
      : undefined;
  }

  dispose(): void {
    this.subscription.dispose();
  }
}

/** The edit that writes a module's group into a main, not yet applied, and what to say once it is. */
export interface PreparedInsert {
  main: vscode.Uri;
  document: vscode.TextDocument;
  edit: vscode.WorkspaceEdit;
  groupName: string;
  /** The new group's first line. */
  line: number;
  /** Who plays each role: `role = entity, ...`. */
  cast: string;
}

/**
 * The edit that writes the module's group into an Act of the main: a ManeuverGroup with the ScenarioReference, every
 * key at its default and the module's entities played by the main's (asked in a quick pick where the main has no
 * entity of the role's name). Undefined when the user cancels a question or the main cannot take it (said in a
 * message); a failure of the server's is thrown.
 */
export async function prepareInsert(
  server: ServerCommandClient,
  tracker: MainTracker,
  module: LibraryModuleSummary,
  options: InsertOptions,
  title = TITLE,
): Promise<PreparedInsert | undefined> {
  const main = typeof options.main === 'string' ? vscode.Uri.parse(options.main) : (options.main ?? tracker.main);
  if (!main) {
    void vscode.window.showErrorMessage(`${title}: open the main scenario the module goes into first (New Modular Scenario… writes one).`);
    return undefined;
  }
  const document = await vscode.workspace.openTextDocument(main);
  const position = options.position;
  const questions = await server.libraryInsert({ uri: main.toString(), module: module.name, ...(position ? { position } : {}) });
  if (questions.acts.length === 0) {
    void vscode.window.showErrorMessage(`${title}: ${path.posix.basename(main.path)} has no Story with an Act to put the group in.`);
    return undefined;
  }
  let act = options.act;
  if (!act && !position && questions.acts.length > 1) {
    act = await vscode.window.showQuickPick(questions.acts, {
      title: `${title}: ${module.title}`,
      placeHolder: 'The Act the group goes into',
    });
    if (!act) return undefined;
  }
  const players: Record<string, string> = { ...options.players };
  for (const role of questions.roles) {
    if (players[role.name]) continue;
    if (role.guess) {
      players[role.name] = role.guess;
      continue;
    }
    if (questions.entities.length === 0) {
      void vscode.window.showErrorMessage(`${title}: ${path.posix.basename(main.path)} declares no entity to play '${role.name}'.`);
      return undefined;
    }
    const taken = new Set(Object.values(players));
    const items = [...questions.entities]
      .sort((a, b) => Number(taken.has(a)) - Number(taken.has(b)))
      .map((entity) => ({ label: entity, description: taken.has(entity) ? 'plays another role already' : undefined }));
    const picked = await vscode.window.showQuickPick(items, {
      title: `${title}: ${module.title}`,
      placeHolder: `Which entity plays '${role.name}' (${role.about})?`,
    });
    if (!picked) return undefined;
    players[role.name] = picked.label;
  }
  const answer = await server.libraryInsert({
    uri: main.toString(),
    module: module.name,
    act,
    players,
    ...(position ? { position } : {}),
  });
  if (!answer.edit || !answer.groupName) throw new Error('the language server gave no edit');
  return {
    main,
    document,
    edit: await server.workspaceEdit(answer.edit),
    groupName: answer.groupName,
    line: answer.line ?? 0,
    cast: questions.roles.map((role) => `${role.name} = ${players[role.name]}`).join(', '),
  };
}

/** Logs and shows in the status bar what an insert wrote. */
export function reportInserted(reporter: CommandReporter, title: string, module: LibraryModuleSummary, inserted: PreparedInsert): void {
  reporter.log(`${title}: library:${module.name} as ${inserted.groupName} in ${inserted.main.toString()} (${inserted.cast})`);
  void vscode.window.setStatusBarMessage(`Inserted library:${module.name} as ${inserted.groupName} (${inserted.cast})`, 8000);
}

/** Writes the module's group into an Act of the main (prepareInsert) and shows it. Returns the new group's name. */
export async function insertIntoMain(
  server: ServerCommandClient,
  reporter: CommandReporter,
  tracker: MainTracker,
  module: LibraryModuleSummary,
  options: InsertOptions = {},
): Promise<string | undefined> {
  try {
    const inserted = await prepareInsert(server, tracker, module, options);
    if (!inserted) return undefined;
    const applied = await vscode.workspace.applyEdit(inserted.edit);
    if (!applied) throw new Error(`the editor refused the edit of ${inserted.main.toString()}`);
    const editor = await vscode.window.showTextDocument(inserted.document, { viewColumn: vscode.ViewColumn.One, preserveFocus: false });
    editor.revealRange(new vscode.Range(inserted.line, 0, inserted.line, 0), vscode.TextEditorRevealType.InCenter);
    editor.selection = new vscode.Selection(inserted.line, 0, inserted.line, 0);
    reportInserted(reporter, TITLE, module, inserted);
    return inserted.groupName;
  } catch (error) {
    // Not awaited: the message waits for the user, the command's caller should not.
    void reporter.failure(TITLE, error);
    return undefined;
  }
}
