import * as path from 'node:path';
import { WorkspaceEdit } from 'vscode-languageserver/node';
import {
  LibraryInsertParams,
  LibraryInsertResult,
  LibraryListingResult,
  LibraryModuleSummary,
  NewFromTemplateParams,
  NewFromTemplateResult,
  TemplateSummary,
} from '../../../common/src/libraryProtocol';
import { decodeScenario } from '../core/encoding';
import { findModule, LibraryModule, listLibraries } from '../core/library';
import { entityKinds, guessPlayer, insertModuleGroup, isEntityKey, mainShape, moduleRoles } from '../core/libraryInsert';
import { LineIndex } from '../core/text';
import { listTemplates, templateOutputs } from '../libraries';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { invalidParams, refOf } from './commands';

function summary(module: LibraryModule): LibraryModuleSummary {
  return {
    name: module.name,
    file: module.file,
    library: module.library.folder,
    libraryLabel: module.library.label,
    title: module.title,
    group: module.group,
    summary: module.summary,
    maneuverGroup: module.maneuverGroup,
    actor: module.actor,
    parameters: module.parameters.map((parameter) => ({
      key: parameter.key,
      name: parameter.name,
      ...(parameter.unit ? { unit: parameter.unit } : {}),
      ...(parameter.range ? { range: parameter.range } : {}),
      about: parameter.about,
      ...(parameter.defaultValue !== undefined ? { defaultValue: parameter.defaultValue } : {}),
      entity: isEntityKey(parameter.key),
    })),
    ...(module.example ? { example: module.example } : {}),
    ...(module.picture ? { picture: module.picture } : {}),
    hides: module.hides,
  };
}

/** The modules of the workspace's libraries (the user's folders, then the built-in one), and what could not be read. */
export async function libraryModules(workspace: Workspace): Promise<LibraryListingResult> {
  const libraries = workspace.store.libraries;
  const listing = await listLibraries(workspace.store.host, libraries);
  return {
    libraries: libraries.map((library) => ({ folder: library.folder, label: library.label })),
    modules: listing.modules.map(summary),
    problems: listing.problems,
  };
}

/**
 * *Insert into main*: the questions (the main's Acts and entities, the module's roles with a guess each) and,
 * once each role has a player, the edit that writes the group into the Act.
 */
export async function libraryInsert(workspace: Workspace, params: LibraryInsertParams): Promise<LibraryInsertResult> {
  if (typeof params?.module !== 'string' || params.module === '') throw invalidParams('module: a library module name is required');
  const position = params.position;
  if (position !== undefined && !(Number.isInteger(position?.line) && Number.isInteger(position?.character) && position.line >= 0))
    throw invalidParams('position: { line, character }, zero-based integers, where the group goes');
  const ref = await refOf(workspace, params.uri);
  const text = await workspace.store.readText(ref).catch((error: Error) => {
    throw invalidParams(`the main could not be read: ${error.message}`);
  });
  const listing = await listLibraries(workspace.store.host, workspace.store.libraries);
  const { module, suggestion } = findModule(listing, params.module);
  if (!module) throw invalidParams(`no library module '${params.module}'${suggestion ? `: did you mean '${suggestion}'?` : ''}`);
  const lines = new LineIndex(text);
  const shape = mainShape(text, position ? lines.offsetAt(position) : undefined);
  // Asked before any question: a drop or the light bulb's position that cannot take a group is said at once.
  if (position && !shape.insertsAt)
    throw invalidParams(
      `${module.name} cannot go into ${params.uri} at line ${position.line + 1}: that is not on an Act or on a ManeuverGroup of an Act; put it on one (not inside its Actors, a Maneuver or a trigger)`,
    );
  const moduleRolesOf = moduleRoles(module);
  const moduleText = await workspace.store.host
    .readFile(module.file)
    .then((bytes) => (bytes ? decodeScenario(bytes) : ''))
    // Read when listed a moment ago; unread now, the kinds are not known and the user is asked.
    .catch(() => '');
  const kinds = { roles: moduleRolesOf, module: entityKinds(moduleText), main: entityKinds(text) };
  const roles = moduleRolesOf.map((role) => {
    const guess = guessPlayer(role, shape.entities, kinds);
    return { ...role, ...(guess ? { guess } : {}) };
  });
  const result: LibraryInsertResult = { acts: shape.acts.map((act) => act.path), entities: shape.entities, roles };
  const players = params.players ?? {};
  if (roles.some((role) => typeof players[role.name] !== 'string')) return result;
  let inserted;
  try {
    const at = position ? lines.offsetAt(position) : undefined;
    inserted = insertModuleGroup(text, module, { act: params.act, at, players });
  } catch (error) {
    throw invalidParams(`${module.name} cannot go into ${params.uri}: ${(error as Error).message}`);
  }
  const at = lines.positionAt(inserted.offset);
  const edit: WorkspaceEdit = { changes: { [params.uri]: [{ range: { start: at, end: at }, newText: inserted.text }] } };
  const line = at.line + (inserted.text.startsWith('\n') ? 1 : 0);
  return { ...result, edit, groupName: inserted.groupName, line };
}

/** The built-in library's templates, for *New Scenario from Template…*. */
export async function templates(): Promise<TemplateSummary[]> {
  return listTemplates().templates.map((template) => ({
    name: template.name,
    title: template.title,
    summary: template.summary,
    ...(template.distribution ? { distribution: template.distribution } : {}),
  }));
}

/** The files of a new scenario from a template, none written: the client writes them, never over a file. */
export async function newFromTemplate(params: NewFromTemplateParams): Promise<NewFromTemplateResult> {
  const { templates: known } = listTemplates();
  const template = known.find((candidate) => candidate.name === params?.template);
  if (!template) throw invalidParams(`no template '${String(params?.template)}'`);
  const scenario = typeof params.scenario === 'string' ? (filePathOf(params.scenario) ?? params.scenario) : '';
  if (!path.isAbsolute(scenario) || !scenario.toLowerCase().endsWith('.xosc'))
    throw invalidParams(`scenario: ${String(params.scenario)} is no absolute path or file: URI ending in .xosc`);
  try {
    return { files: templateOutputs(template, scenario).map((output) => ({ path: output.target, text: output.data })) };
  } catch (error) {
    throw invalidParams((error as Error).message);
  }
}
