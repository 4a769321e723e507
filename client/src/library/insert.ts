import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { LibraryModuleSummary } from '../../../common/src/libraryProtocol';
import type { CommandReporter } from '../commands';
import { LANGUAGE_ID, type ServerCommandClient } from '../languageClient';
import { freeScenarioName } from '../naming';
import { targetFolder } from '../newScenario';
import { newFromTemplateCommand } from './templates';
import { collisionNotice } from './collisionNotice';

const TITLE = 'Insert into Main';
/** The template a new main is written from when none is open: its entities are named after the modules' roles. */
const BENCH_TEMPLATE = 'composition-bench';
/** Scenario files read to offer as mains: a picker, not an index. */
const MAX_LISTED = 200;

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
    // Open in a tab, as the user sees it: a closed editor's document may linger in textDocuments for minutes.
    const last = this.last?.toString();
    const open = vscode.window.tabGroups.all.some((group) =>
      group.tabs.some((tab) => tab.input instanceof vscode.TabInputText && tab.input.uri.toString() === last),
    );
    return open ? this.last : undefined;
  }

  dispose(): void {
    this.subscription.dispose();
  }
}

/** How a workspace scenario serves as a main: 2 when it already references scenarios, 1 with an Act only, 0 not at all. */
function mainRank(file: string): number {
  try {
    const text = fs.readFileSync(file, 'utf8');
    if (!/<Story[\s>]/.test(text) || !/<Act[\s>]/.test(text)) return 0;
    return /<ScenarioReference[\s>]/.test(text) ? 2 : 1;
  } catch {
    return 0;
  }
}

/**
 * No main open: asks which one in a quick pick, a new main from the composition bench first (written under a free name
 * it shows, not asked: its entities play the modules' roles), then the workspace's scenarios with an Act, those that
 * already reference scenarios first.
 */
async function chooseMain(
  server: ServerCommandClient,
  reporter: CommandReporter,
  module: LibraryModuleSummary,
): Promise<vscode.Uri | undefined> {
  const folders = vscode.workspace.workspaceFolders?.filter((folder) => folder.uri.scheme === 'file') ?? [];
  const newIn = folders.length === 1 ? folders[0] : undefined;
  const bench = (await server.templates()).find((template) => template.name === BENCH_TEMPLATE);
  const mains = (await vscode.workspace.findFiles('**/*.xosc', '**/node_modules/**', MAX_LISTED))
    .filter((uri) => uri.scheme === 'file')
    .map((uri) => ({ uri, rank: mainRank(uri.fsPath), label: vscode.workspace.asRelativePath(uri) }))
    .filter((main) => main.rank > 0)
    .sort((a, b) => b.rank - a.rank || a.label.localeCompare(b.label));
  const newName = freeScenarioName(newIn?.uri.fsPath ?? '', (file) => newIn !== undefined && fs.existsSync(file), BENCH_TEMPLATE);
  const items: (vscode.QuickPickItem & { main?: vscode.Uri })[] = [
    { label: `$(new-file) New main ${newName}`, description: newIn ? `in ${newIn.name}` : undefined, detail: bench?.summary },
    ...mains.map((main) => ({
      label: `$(file) ${main.label}`,
      description: main.rank === 2 ? 'references scenarios' : undefined,
      main: main.uri,
    })),
  ];
  const picked = await vscode.window.showQuickPick(items, {
    title: `${TITLE}: ${module.title}`,
    placeHolder: 'No main is open: the main the module goes into',
  });
  if (!picked) return undefined;
  if (picked.main) return picked.main;
  const folder = newIn?.uri.fsPath ?? (await targetFolder(undefined, TITLE));
  if (!folder) return undefined;
  return newFromTemplateCommand(server, reporter, vscode.Uri.file(folder), {
    template: BENCH_TEMPLATE,
    fileName: freeScenarioName(folder, fs.existsSync, BENCH_TEMPLATE),
  });
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
  /** The new entities the edit adds, as the user reads them. */
  added: string[];
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
    void vscode.window.showErrorMessage(`${title}: open the main scenario the module goes into first.`);
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
  const create: string[] = [];
  for (const role of questions.roles) {
    if (players[role.name]) continue;
    if (role.guess) {
      players[role.name] = role.guess;
      continue;
    }
    // No entity of the main is free to play it: the new one, as the example main has it, is the only answer.
    if (role.newEntity && role.newEntityOnly) {
      players[role.name] = role.newEntity;
      create.push(role.name);
      continue;
    }
    if (questions.entities.length === 0 && !role.newEntity) {
      void vscode.window.showErrorMessage(`${title}: ${path.posix.basename(main.path)} declares no entity to play '${role.name}'.`);
      return undefined;
    }
    const taken = new Set(Object.values(players));
    const fresh = role.newEntity
      ? [
          {
            label: `$(add) New entity '${role.newEntity}'`,
            description: `as the ${module.name} example main declares and places it`,
            entity: role.newEntity,
            create: true,
          },
        ]
      : [];
    const existing = [...questions.entities]
      .sort((a, b) => Number(taken.has(a)) - Number(taken.has(b)))
      .map((entity) => ({ label: entity, description: taken.has(entity) ? 'plays another role already' : undefined, entity }));
    // An actor (the module drives it) is most often new; another role (the ego a key names) most often the main's.
    const items: (vscode.QuickPickItem & { entity: string; create?: boolean })[] = role.actor
      ? [...fresh, ...existing]
      : [...existing, ...fresh];
    const picked = await vscode.window.showQuickPick(items, {
      title: `${title}: ${module.title}`,
      placeHolder: `Which entity plays '${role.name}' (${role.about})?`,
    });
    if (!picked) return undefined;
    players[role.name] = picked.entity;
    if (picked.create) create.push(role.name);
  }
  const answer = await server.libraryInsert({
    uri: main.toString(),
    module: module.name,
    act,
    players,
    ...(create.length > 0 ? { create } : {}),
    ...(position ? { position } : {}),
  });
  if (!answer.edit || !answer.groupName) throw new Error('the language server gave no edit');
  return {
    main,
    document,
    edit: await server.workspaceEdit(answer.edit),
    groupName: answer.groupName,
    line: answer.line ?? 0,
    cast: questions.roles.map((role) => `${role.name} = ${players[role.name]}${create.includes(role.name) ? ' (new)' : ''}`).join(', '),
    added: answer.added ?? [],
  };
}

/** Logs and shows in the status bar what an insert wrote. */
export function reportInserted(reporter: CommandReporter, title: string, module: LibraryModuleSummary, inserted: PreparedInsert): void {
  const added = inserted.added.length > 0 ? `; added ${inserted.added.join(', ')}` : '';
  reporter.log(`${title}: library:${module.name} as ${inserted.groupName} in ${inserted.main.toString()} (${inserted.cast})${added}`);
  void vscode.window.setStatusBarMessage(`Inserted library:${module.name} as ${inserted.groupName} (${inserted.cast})${added}`, 8000);
}

/** A run of the main after an insert: the module inserted, the main, whether esmini ran, and the notice shown (none where nothing touches). */
export interface AfterInsertRun {
  module: string;
  main: string;
  ran: boolean;
  notice?: string;
}

/** The after-insert runs kept for the view's API (the tests read them): the latest this many. */
const KEPT_RUNS = 20;

/** Runs the main as the editor has it in esmini and shows a notice where scripted actors touch; a run that cannot happen is logged. */
async function noticeCollisions(
  server: ServerCommandClient,
  reporter: CommandReporter,
  module: LibraryModuleSummary,
  main: vscode.Uri,
  runs: AfterInsertRun[],
): Promise<void> {
  try {
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini', main);
    const result = await server.libraryCollisions({
      uri: main.toString(),
      esminiPath: settings.get<string>('path') || undefined,
      roadPath: settings.get<string[]>('roadPath') ?? [],
    });
    const notice = collisionNotice(module.name, result);
    runs.push({ module: module.name, main: main.toString(), ran: result.ran, ...(notice ? { notice } : {}) });
    runs.splice(0, Math.max(0, runs.length - KEPT_RUNS));
    reporter.log(`${TITLE}: esmini's run after the insert: ${notice ?? (result.ran ? 'no scripted actors touch' : result.message)}`);
    if (notice) void vscode.window.showWarningMessage(notice);
  } catch (error) {
    reporter.log(`${TITLE}: esmini's run after the insert failed: ${(error as Error).stack ?? String(error)}`);
  }
}

/** Writes the module's group into an Act of the main (prepareInsert) and shows it. Returns the new group's name. */
export async function insertIntoMain(
  server: ServerCommandClient,
  reporter: CommandReporter,
  tracker: MainTracker,
  module: LibraryModuleSummary,
  options: InsertOptions = {},
  runs: AfterInsertRun[] = [],
): Promise<string | undefined> {
  try {
    if (options.main === undefined && !tracker.main) {
      const main = await chooseMain(server, reporter, module);
      if (!main) return undefined;
      options = { ...options, main };
    }
    const inserted = await prepareInsert(server, tracker, module, options);
    if (!inserted) return undefined;
    // An edit like VS Code's own: the main is left modified, Ctrl+Z undoes it, and saving is the user's (or files.autoSave's).
    const applied = await vscode.workspace.applyEdit(inserted.edit);
    if (!applied) throw new Error(`the editor refused the edit of ${inserted.main.toString()}`);
    const editor = await vscode.window.showTextDocument(inserted.document, { viewColumn: vscode.ViewColumn.One, preserveFocus: false });
    editor.revealRange(new vscode.Range(inserted.line, 0, inserted.line, 0), vscode.TextEditorRevealType.InCenter);
    editor.selection = new vscode.Selection(inserted.line, 0, inserted.line, 0);
    reportInserted(reporter, TITLE, module, inserted);
    // Not awaited: the notice comes when the run has, and never holds the edit back.
    void noticeCollisions(server, reporter, module, inserted.main, runs);
    return inserted.groupName;
  } catch (error) {
    // Not awaited: the message waits for the user, the command's caller should not.
    void reporter.failure(TITLE, error);
    return undefined;
  }
}
