import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { CommandReporter } from './commands';
import type { ServerCommandClient } from './languageClient';
import { fileNameProblem, freeScenarioName, scenarioFileName, writeNewFiles } from './naming';

/** What a caller (a test, a keybinding) may pass instead of being asked. */
export interface NewScenarioOptions {
  /** The road network's path. */
  roadNetwork?: string;
  /** The new file's name, in the folder. */
  fileName?: string;
}

const TITLE = 'New Modular Scenario';
const BROWSE = 'Browse…';
/** Road files listed from each roadPath folder, and how deep it is searched: a picker, not an index. */
const MAX_LISTED = 200;
const ROAD_PATH_DEPTH = 3;

/** The options object among a command's arguments: the one that sets one of `keys` to a string (not a Uri, not a list). */
export function optionsAmong<Options extends object>(args: unknown[], keys: (keyof Options & string)[]): Partial<Options> {
  const isOptions = (value: unknown): value is Partial<Options> =>
    typeof value === 'object' &&
    value !== null &&
    !(value instanceof vscode.Uri) &&
    !Array.isArray(value) &&
    keys.some((key) => typeof (value as Record<string, unknown>)[key] === 'string');
  return args.find(isOptions) ?? {};
}

function isDirectory(filePath: string): boolean {
  try {
    return fs.statSync(filePath).isDirectory();
  } catch {
    return false;
  }
}

/** The folder the command was run on: the explorer's folder (or a file's folder), else the workspace's first. */
export async function targetFolder(clicked: unknown, title = TITLE): Promise<string | undefined> {
  if (clicked instanceof vscode.Uri && clicked.scheme === 'file')
    return isDirectory(clicked.fsPath) ? clicked.fsPath : path.dirname(clicked.fsPath);
  const folders = vscode.workspace.workspaceFolders?.filter((folder) => folder.uri.scheme === 'file') ?? [];
  if (folders.length === 1) return folders[0].uri.fsPath;
  const chosen = await vscode.window.showOpenDialog({
    canSelectFolders: true,
    canSelectFiles: false,
    openLabel: 'Create the scenario here',
    title: `${title}: the folder`,
    defaultUri: folders[0]?.uri,
  });
  return chosen?.[0]?.fsPath;
}

/** `.xodr` files below a folder, a few levels deep, at most `MAX_LISTED`. */
function roadFilesBelow(folder: string, depth = ROAD_PATH_DEPTH, found: string[] = []): string[] {
  let entries: fs.Dirent[];
  try {
    entries = fs.readdirSync(folder, { withFileTypes: true });
  } catch {
    return found;
  }
  for (const entry of entries) {
    if (found.length >= MAX_LISTED) break;
    const full = path.join(folder, entry.name);
    if (entry.isFile() && entry.name.toLowerCase().endsWith('.xodr')) found.push(full);
    else if (entry.isDirectory() && depth > 1 && !entry.name.startsWith('.')) roadFilesBelow(full, depth - 1, found);
  }
  return found;
}

/** A road network offered; `copied`: a road of the built-in Scenario Library, copied beside the new main when picked. */
interface RoadCandidate {
  file: string;
  where: string;
  copied?: boolean;
}

/** The built-in Scenario Library's roads (its modules' examples drive on them): none when the server lists no built-in library. */
async function libraryRoads(server: ServerCommandClient): Promise<string[]> {
  const listing = await server.libraryModules();
  const builtIn = listing.libraries.find((library) => library.label === 'built-in');
  return builtIn ? roadFilesBelow(path.join(builtIn.folder, 'roads'), 1).sort() : [];
}

/**
 * The road networks to offer: those in the workspace, then those in the `modular2simple.esmini.roadPath` folders,
 * then the Scenario Library's (so that a new user in an empty folder has a road to start on).
 */
async function roadCandidates(folder: string, fromLibrary: string[]): Promise<RoadCandidate[]> {
  const inWorkspace = (await vscode.workspace.findFiles('**/*.xodr', '**/node_modules/**', MAX_LISTED))
    .filter((uri) => uri.scheme === 'file')
    .map((uri) => uri.fsPath);
  const scope = vscode.Uri.file(folder);
  const base = (vscode.workspace.getWorkspaceFolder(scope) ?? vscode.workspace.workspaceFolders?.[0])?.uri.fsPath ?? folder;
  const roadPath = vscode.workspace.getConfiguration('modular2simple.esmini', scope).get<string[]>('roadPath') ?? [];
  const seen = new Set<string>();
  const candidates: RoadCandidate[] = [];
  const add = (file: string, where: string, copied?: boolean) => {
    if (seen.has(file)) return;
    seen.add(file);
    candidates.push({ file, where, ...(copied ? { copied } : {}) });
  };
  for (const file of inWorkspace.sort()) add(file, path.relative(folder, file).split(path.sep).join('/'));
  for (const entry of roadPath) {
    const directory = path.resolve(base, entry);
    for (const file of roadFilesBelow(directory).sort()) add(file, `roadPath ${entry}`);
  }
  for (const file of fromLibrary) add(file, 'Scenario Library road, copied beside the new main', true);
  return candidates;
}

async function askRoadNetwork(folder: string, fromLibrary: string[]): Promise<RoadCandidate | undefined> {
  const candidates = await roadCandidates(folder, fromLibrary);
  const items: (vscode.QuickPickItem & { candidate?: RoadCandidate })[] = [
    ...candidates.map((candidate) => ({ label: path.basename(candidate.file), description: candidate.where, candidate })),
    { label: BROWSE, description: 'an OpenDRIVE file anywhere' },
  ];
  const picked = await vscode.window.showQuickPick(items, {
    title: `${TITLE}: the road network`,
    placeHolder:
      candidates.length > 0
        ? 'The OpenDRIVE road network the scenario drives on'
        : 'No .xodr file in the workspace or in modular2simple.esmini.roadPath: browse for one',
    matchOnDescription: true,
  });
  if (!picked) return undefined;
  if (picked.candidate) return picked.candidate;
  const browsed = await vscode.window.showOpenDialog({
    canSelectFiles: true,
    canSelectMany: false,
    filters: { OpenDRIVE: ['xodr'] },
    title: `${TITLE}: the road network`,
    defaultUri: vscode.Uri.file(folder),
  });
  return browsed?.[0] ? { file: browsed[0].fsPath, where: '' } : undefined;
}

/**
 * A library road copied into the folder, as a template's road is: the file beside the main, not written when a file of
 * that name with the same content is there already (undefined returned for `written`); a different file of that name is
 * an error naming it.
 */
async function copiedRoad(road: string, folder: string): Promise<{ file: string; written?: string }> {
  const target = path.join(folder, path.basename(road));
  const data = await fs.promises.readFile(road, 'utf8');
  if (!fs.existsSync(target)) return { file: target, written: (await writeNewFiles([{ path: target, text: data }]))[0] };
  if ((await fs.promises.readFile(target, 'utf8')) !== data)
    throw new Error(`${target} exists and is not the Scenario Library's road: move it away, or create the scenario in another folder`);
  return { file: target };
}

/** What the file name question says and proposes. */
export interface FileNameQuestion {
  title: string;
  prompt: string;
  proposed: string;
  /** The part of the proposal selected, to be typed over (all of it when left out). */
  selection?: [number, number];
}

/**
 * The new file's path in the folder: the name given, or else the one the user types (checked as typed); undefined when
 * the question is dismissed or the name will not do (said in an error message).
 */
export async function newFilePath(folder: string, given: string | undefined, question: FileNameQuestion): Promise<string | undefined> {
  const fileName =
    given ??
    (
      await vscode.window.showInputBox({
        title: `${question.title}: the file name`,
        prompt: question.prompt,
        value: question.proposed,
        valueSelection: question.selection,
        validateInput: (value) => fileNameProblem(folder, value),
      })
    )?.trim();
  if (!fileName) return undefined;
  const problem = fileNameProblem(folder, fileName);
  if (problem) {
    void vscode.window.showErrorMessage(`${question.title}: ${problem}.`);
    return undefined;
  }
  return path.join(folder, scenarioFileName(fileName));
}

/**
 * *New Modular Scenario…*: asks for a road network and a file name, has the server write the main
 * (an ego on the road, a Story/Act ready to import groups), writes it without overwriting anything and opens it.
 */
export async function newScenarioCommand(
  server: ServerCommandClient,
  reporter: CommandReporter,
  clicked: unknown,
  ...rest: unknown[]
): Promise<vscode.Uri | undefined> {
  const options = optionsAmong<NewScenarioOptions>([clicked, ...rest], ['roadNetwork', 'fileName']);
  try {
    const folder = await targetFolder(clicked);
    if (!folder) return undefined;
    const road = options.roadNetwork ? { file: options.roadNetwork, where: '' } : await askRoadNetwork(folder, await libraryRoads(server));
    if (!road) return undefined;
    const target = await newFilePath(folder, options.fileName, {
      title: TITLE,
      prompt: `The new main scenario, in ${folder}`,
      proposed: freeScenarioName(folder),
      selection: [0, 'main'.length],
    });
    if (!target) return undefined;
    const copied = road.copied ? await copiedRoad(road.file, folder) : undefined;
    try {
      const roadNetwork = copied?.file ?? path.resolve(folder, road.file);
      const result = await server.newScenario(vscode.Uri.file(target), vscode.Uri.file(roadNetwork));
      await writeNewFiles([{ path: target, text: result.text }]);
      reporter.log(
        `${TITLE}: wrote ${target} (ego on road ${result.ego.roadId}, lane ${result.ego.laneId}, s ${result.ego.s} of ${result.roadFile}${copied?.written ? `, copied from ${road.file}` : ''})`,
      );
    } catch (error) {
      // The road copied for this main goes with it.
      if (copied?.written) await fs.promises.rm(copied.written, { force: true });
      throw error;
    }
    const uri = vscode.Uri.file(target);
    await vscode.window.showTextDocument(uri, { preview: false });
    return uri;
  } catch (error) {
    await reporter.failure(TITLE, error);
    return undefined;
  }
}
