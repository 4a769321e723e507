import * as path from 'node:path';
import { WorkspaceEdit } from 'vscode-languageserver/node';
import {
  LibraryCollisionsParams,
  LibraryCollisionsResult,
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
import { entityOffers, exampleSpeedDifference, newEntityChanges, TrafficRules } from '../core/libraryEntities';
import { parseScenario } from '../core/model';
import { Evaluator } from '../core/semantics/evaluator';
import { semanticModelOf } from '../core/semantics/model';
import { locateRoadFile } from '../core/semantics/roadFiles';
import { roadSignalsOf } from '../core/semantics/roadNetwork';
import { diskRef, nodeFileSystem, SourceRef } from '../core/sources';
import {
  entityKinds,
  freeEntities,
  guessPlayer,
  insertModuleGroup,
  isEntityKey,
  mainShape,
  moduleRoles,
  scriptedActors,
} from '../core/libraryInsert';
import { Flattener } from '../core/flatten';
import { removeRunFolder, runScenario } from '../esmini/run';
import { LineIndex } from '../core/text';
import { listTemplates, templateOutputs } from '../libraries';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { invalidParams, refOf } from './commands';
import { stringList } from './esminiRun';

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
  const readText = (file: string) =>
    workspace.store.host
      .readFile(file)
      .then((bytes) => (bytes ? decodeScenario(bytes) : ''))
      // Read when listed a moment ago; unread now, the kinds are not known and the user is asked.
      .catch(() => '');
  const moduleText = await readText(module.file);
  // The example main supplies new entities; unread, none is offered.
  const exampleText = module.example ? await readText(module.example) : '';
  const kinds = { roles: moduleRolesOf, module: entityKinds(moduleText), main: entityKinds(text), busy: shape.actors };
  const offers = new Map(entityOffers(module, exampleText, shape.entities).map((offer) => [offer.role, offer.name]));
  // Free to play a role the module drives: no actor of a group of the main; any other role (the ego a key names): any.
  const free = { actor: freeEntities(shape.entities, moduleRolesOf, shape.actors), other: freeEntities(shape.entities, moduleRolesOf, []) };
  const roles = moduleRolesOf.map((role) => {
    const guess = guessPlayer(role, shape.entities, kinds);
    // Offered where the main has no entity of the role's name or kind to guess: the question is asked then.
    const newEntity = guess ? undefined : offers.get(role.name);
    return {
      ...role,
      ...(guess ? { guess } : {}),
      ...(newEntity ? { newEntity, ...((role.actor ? free.actor : free.other).length === 0 ? { newEntityOnly: true } : {}) } : {}),
    };
  });
  const result: LibraryInsertResult = { acts: shape.acts.map((act) => act.path), entities: shape.entities, roles };
  const players = params.players ?? {};
  if (roles.some((role) => typeof players[role.name] !== 'string')) return result;
  const create = params.create ?? [];
  if (!Array.isArray(create) || create.some((role) => typeof role !== 'string' || !moduleRolesOf.some((known) => known.name === role)))
    throw invalidParams(`create: the names of roles of ${module.name} (${moduleRolesOf.map((role) => role.name).join(', ')})`);
  // A car that enters the lane moves the slower cars ahead of the ego behind it, each its example's difference slower.
  const slower = new Map<string, number>();
  if (module.queue === 'enters')
    for (const candidate of listing.modules)
      if (candidate.queue === 'slower' && candidate.example) {
        const difference = exampleSpeedDifference(candidate, await readText(candidate.example));
        if (difference !== undefined) slower.set(candidate.name, difference);
      }
  let inserted;
  let entities;
  try {
    const mainFile = filePathOf(params.uri);
    // A new entity is placed, and a key meaning a side written, as a driver of the main's road expects: its rule against the example's.
    const rules: TrafficRules = module.example
      ? {
          main: await leftHandRoadsOf(workspace, ref, text),
          example: await leftHandRoadsOf(workspace, diskRef(module.example), exampleText),
        }
      : {};
    entities = newEntityChanges(
      text,
      module,
      exampleText,
      Object.fromEntries(create.map((role) => [role, players[role]])),
      players,
      mainFile && module.example ? { main: mainFile, example: module.example } : undefined,
      rules,
      new Set(listing.modules.filter((candidate) => candidate.queue === 'enters').map((candidate) => candidate.name)),
      slower,
    );
    const at = position ? lines.offsetAt(position) : undefined;
    inserted = insertModuleGroup(text, module, { act: params.act, at, players, values: entities.values });
  } catch (error) {
    throw invalidParams(`${module.name} cannot go into ${params.uri}: ${(error as Error).message}`);
  }
  const at = lines.positionAt(inserted.offset);
  const changes = [
    ...entities.changes.map((change) => ({
      range: { start: lines.positionAt(change.start), end: lines.positionAt(change.end) },
      newText: change.text,
    })),
    { range: { start: at, end: at }, newText: inserted.text },
  ];
  const edit: WorkspaceEdit = { changes: { [params.uri]: changes } };
  // The group's first line once the entities' lines are in, which come before it.
  const added = entities.changes
    .filter((change) => change.start <= inserted.offset)
    .reduce((sum, change) => sum + lineCount(change.text) - lineCount(text.slice(change.start, change.end)), 0);
  const line = at.line + (inserted.text.startsWith('\n') ? 1 : 0) + added;
  return { ...result, edit, groupName: inserted.groupName, line, ...(entities.added.length > 0 ? { added: entities.added } : {}) };
}

/**
 * After an insert: the main as the editor has it, run headless in esmini to its end (a few tenths of a second for a
 * composition of a few modules), and the collisions between its scripted actors (scriptedActors), for a notice that
 * never holds the edit back. The run's folder is removed at once.
 */
export async function libraryCollisions(workspace: Workspace, params: LibraryCollisionsParams): Promise<LibraryCollisionsResult> {
  const ref = await refOf(workspace, params?.uri);
  const text = await workspace.store.readText(ref);
  const scripted = scriptedActors(text);
  const run = await runScenario(new Flattener(workspace.store), ref, {
    esminiPath: typeof params.esminiPath === 'string' && params.esminiPath ? params.esminiPath : undefined,
    roadPath: stringList(params.roadPath),
    base: workspace.folders[0],
  });
  try {
    if (run.outcome !== 'ok' && run.outcome !== 'errors') return { ran: false, message: run.message, collisions: [] };
    const collisions = (run.collisions ?? [])
      .filter((collision) => collision.entities.every((entity) => scripted.has(entity)))
      .map(({ entities, time }) => ({ entities, time: time ?? 0 }));
    return { ran: true, message: run.message, collisions };
  } finally {
    removeRunFolder(run);
  }
}

/**
 * The ids of the roads of left-hand traffic in a scenario's road file, found as a run finds it; undefined where it names
 * none, or it is not found or cannot be read (its placement then is that of right-hand traffic, OpenDRIVE's default; the
 * diagnostics say why the road file is not read). Read through the road memo the road rules use, not again per insert.
 */
async function leftHandRoadsOf(workspace: Workspace, ref: SourceRef, text: string): Promise<ReadonlySet<string> | undefined> {
  const document = parseScenario(text).document;
  const road = await locateRoadFile(workspace.store, ref, document, new Evaluator(semanticModelOf(document)), [], nodeFileSystem);
  return (await roadSignalsOf(workspace.store, road))?.leftHandRoads;
}

function lineCount(text: string): number {
  return text.split('\n').length - 1;
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
