/**
 * The Scenario Library view's requests (`modular2simple/libraryModules`, `modular2simple/libraryInsert`), typed
 * for both sides (both bundles import this file).
 */
import { RequestType, WorkspaceEdit } from 'vscode-languageserver-protocol';
import type { RunCollision } from './collisions';

export interface LibraryParameterSummary {
  key: string;
  name: string;
  unit?: string;
  range?: string;
  about: string;
  defaultValue?: string;
  /** Whether the key's value names an entity (the main's entity that plays a role of the module). */
  entity: boolean;
}

export interface LibraryModuleSummary {
  /** What `library:NAME` names. */
  name: string;
  /** The module's file, a path. */
  file: string;
  /** The library folder it comes from, and whether it is the built-in one or the user's. */
  library: string;
  libraryLabel: string;
  title: string;
  group: string;
  summary: string;
  maneuverGroup: string;
  actor: { name: string; about: string };
  parameters: LibraryParameterSummary[];
  example?: string;
  picture?: string;
  /** Files of later libraries' modules of the same name, which this one hides. */
  hides: string[];
}

/** A library folder or file that could not be used; the rest of the library is listed. */
export interface LibraryProblemSummary {
  file: string;
  /** One-based, when known. */
  line?: number;
  message: string;
}

export interface LibraryListingResult {
  /** The folders searched, in order (the user's first, the built-in last). */
  libraries: { folder: string; label: string }[];
  modules: LibraryModuleSummary[];
  problems: LibraryProblemSummary[];
}

export const LibraryModulesRequest = new RequestType<Record<string, never>, LibraryListingResult, void>('modular2simple/libraryModules');

export interface LibraryInsertParams {
  /** The main the group goes into, a `file:` or `mosc:` URI (its unsaved text is used). */
  uri: string;
  /** The module's name (`cut-in`). */
  module: string;
  /** `Story/Act`; the first Act when left out. */
  act?: string;
  /**
   * *Insert library module here…*: the cursor the code action was asked at (zero-based, as LSP's); the group goes
   * after the ManeuverGroup there (or before the cursor) in that Act, and `act` is not read.
   */
  position?: { line: number; character: number };
  /** For each role of the module (an entity it names), the main's entity that plays it; asked about when left out. */
  players?: Record<string, string>;
  /**
   * The roles whose player (`players[role]`, a name the main does not declare) is a new entity, added to the main as
   * the module's example main declares and places it (the role's `newEntity` offer), in the same edit.
   */
  create?: string[];
}

export interface LibraryRoleSummary {
  name: string;
  about: string;
  actor: boolean;
  keys: string[];
  /** The main's entity of the same name, when there is one. */
  guess?: string;
  /** The name of a new entity for the role, free in the main, when the module's example main declares and places one to copy. */
  newEntity?: string;
  /** No entity of the main is free to play it (each plays another role or acts in a group): the new entity is the answer. */
  newEntityOnly?: boolean;
}

export interface LibraryInsertResult {
  /** The main's Acts (`Story/Act`) and entities, for the questions. */
  acts: string[];
  entities: string[];
  roles: LibraryRoleSummary[];
  /** Present when every question was answered: the edit that inserts the group, and its name. */
  edit?: WorkspaceEdit;
  groupName?: string;
  /** Where the group starts once inserted, zero-based. */
  line?: number;
  /** The new entities the edit adds, as the user reads them: `adversary (Vehicle, 35 m ahead of Ego, lane -2, 7 m/s)`. */
  added?: string[];
}

export const LibraryInsertRequest = new RequestType<LibraryInsertParams, LibraryInsertResult, void>('modular2simple/libraryInsert');

/** After an insert: the main as the editor has it run headless in esmini, and the collisions between its scripted actors. */
export interface LibraryCollisionsParams {
  uri: string;
  /** Setting modular2simple.esmini.path: the program or its folder; PATH when empty. */
  esminiPath?: string;
  /** Setting modular2simple.esmini.roadPath: extra folders for road files and catalogs. */
  roadPath?: string[];
}

export interface LibraryCollisionsResult {
  /** Whether esmini ran the main (else `message` says why: no esmini, not flattened, ...). */
  ran: boolean;
  message: string;
  /** Where two actors of the main's groups began to touch, but for an entity a library group names as its ego (its driver under test). */
  collisions: RunCollision[];
}

export const LibraryCollisionsRequest = new RequestType<LibraryCollisionsParams, LibraryCollisionsResult, void>(
  'modular2simple/libraryCollisions',
);

/** The client's command that inserts a library module (the Scenario Library's *Insert into Main*, the code action's). */
export const INSERT_LIBRARY_MODULE_COMMAND = 'modular2simple.library.insert';

/** What *Insert library module here…* passes to the command (after the module, which it leaves to be picked). */
export interface InsertHereArguments {
  /** The main's URI. */
  main: string;
  position: { line: number; character: number };
}

export interface TemplateSummary {
  name: string;
  title: string;
  summary: string;
  /** The distribution file that comes with it, when it has one. */
  distribution?: string;
}

export const TemplatesRequest = new RequestType<Record<string, never>, TemplateSummary[], void>('modular2simple/templates');

export interface NewFromTemplateParams {
  template: string;
  /** The new scenario: a `file:` URI or an absolute path, ending in .xosc. */
  scenario: string;
}

/** The files to write (none exists yet): the scenario first, then its road and distribution where they come along. */
export interface NewFromTemplateResult {
  files: { path: string; text: string }[];
}

export const NewFromTemplateRequest = new RequestType<NewFromTemplateParams, NewFromTemplateResult, void>('modular2simple/newFromTemplate');
