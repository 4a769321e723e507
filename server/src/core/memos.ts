/**
 * The core's memos, each declared once: what it is keyed by, what it holds, how much it keeps and what
 * makes it stale (the query table of rust-analyzer's `RootDatabase`, by hand). A module asks for its
 * memo by name (`coreMemo`) instead of making a `WeakMap` of its own; the server's database
 * (`server/src/database.ts`) composes this table with its own, and ARCHITECTURE.md's table of caches is
 * rendered from both. This module imports nothing, so every folder of the core may use it.
 */

/** How much a memo keeps. */
export interface MemoBound {
  /** At most this many entries (files, unless said otherwise). */
  entries?: number;
  /** At most about this many bytes. */
  bytes?: number;
  /** Entries older than this are read again. */
  freshMs?: number;
  /** The bound in words, as ARCHITECTURE.md says it. */
  text: string;
}

/** One memo: a piece of derived state, who owns it and when it goes. */
export interface MemoDeclaration {
  /** Where it lives: the module, and the owner when it is not the module. */
  where: string;
  /** What it is keyed by: the value it is derived from. */
  key: string;
  /** What it holds. */
  holds: string;
  bound: MemoBound;
  /** What makes an entry stale, or why nothing does. */
  invalidated: string;
}

/** A memo attached to its key: it goes when the key is collected, nothing else keeps it. */
const WITH_KEY: MemoBound = { text: 'one entry per key, collected with it' };

/** Every piece of derived state the core keeps, by name. */
export const CORE_MEMOS = {
  packages: {
    where: '`ScenarioStore.packages` (`SizedCache`)',
    key: 'a `.mosc` on disk or inside another package',
    holds: 'unpacked `.mosc` contents, least recently used out',
    bound: { text: "the store's `packageCacheBytes`: 64 MiB in the server" },
    invalidated: '`ScenarioStore.invalidate` on a watched-file event; a new store on settings or workspace folder changes',
  },
  resolutions: {
    where: '`ScenarioStore.resolve` (`core/sources/store.ts`)',
    key: 'the file writing a `scenarioFileName`, then the name',
    holds: 'the file or package the name was found as (names not found, or not readable, are looked up again)',
    bound: { entries: 4096, text: '4,096 names, then started again' },
    invalidated: "when the store's kinds of files are forgotten (`KindCache.clear`: a watched-file event, `ScenarioStore.invalidate`)",
  },
  overlays: {
    where: '`ScenarioStore.overlays`',
    key: 'an open file',
    holds: 'unsaved text of open documents (an input, not derived: the one state the others are derived from besides the disk)',
    bound: { text: 'one per open document' },
    invalidated: 'replaced on every change; removed on close',
  },
  previousParses: {
    where: '`ScenarioStore.editedParses`',
    key: 'an open file',
    holds: 'the last parse of each open document, for incremental re-parse',
    bound: { text: 'one per open document' },
    invalidated: 'replaced by each parse; removed on close',
  },
  schemaModel: {
    where: '`core/schema/model.ts`, `core/schema/index.ts`',
    key: 'a schema version, then a type',
    holds:
      "the compiled schemas (`dist/openscenario-schemas.json`, whose first line gives each version's byte range: a process decodes and parses only the versions it checks), per version the children, attributes and a content automaton per type, built on first use",
    bound: { text: 'the versions checked' },
    invalidated: 'never: built from bundled data',
  },
  lastSchemaChecks: {
    where: '`SchemaCheckMemory` (`core/schema/problems.ts`), one per `AnalysisDatabase` and one per CLI run',
    key: 'a file',
    holds:
      "each file's last schema findings by offset, its text and chosen version (no parse tree), so an edit inside one attribute value re-checks only that attribute",
    bound: { entries: 64, bytes: 32 * 1024 * 1024, text: '64 files and about 32 MiB (text, 100 bytes a finding)' },
    invalidated: 'replaced by the next check of the file; the least recently checked file goes first (checked in full when next asked)',
  },
  refIds: {
    where: '`core/sources/ref.ts` (`refId`)',
    key: 'a `SourceRef`',
    holds: 'the ref as a string id',
    bound: WITH_KEY,
    invalidated: 'never: a ref never changes',
  },
  problemRefKeys: {
    where: '`core/problems.ts`',
    key: 'a `SourceRef`',
    holds: "the key a problem's file sorts and groups by",
    bound: WITH_KEY,
    invalidated: 'never: a ref never changes',
  },
  overridableAttributes: {
    where: '`core/keys.ts`',
    key: 'a group element',
    holds: 'the attributes a group lists',
    bound: WITH_KEY,
    invalidated:
      "never: an element's offsets, attributes and subtree never change (a value re-parse shares only subtrees not holding the edit whose offsets stay, those before it and, when the edit keeps the text's length, those after it, re-pointing just their roots' `parent`; the rest are new elements)",
  },
  keyReaches: {
    where: '`planOverrides` (`core/keys.ts`)',
    key: "a group's overridable attributes (`overridableAttributes`), then a key",
    holds:
      'the attributes the key reaches, its suggestion when it reaches none, and how specific it is, for every reference writing that key',
    bound: { entries: 512, text: 'one entry per group; 512 keys each, then started again' },
    invalidated: "never: a group's attributes and their elements never change (a new parse is a new group element, a new key)",
  },
  overrideValueChecks: {
    where: '`overrideValueProblems` (`core/flatten/outputSchema.ts`)',
    key: "a group's overridable attribute, then the schema version read and the value a ParameterReference gives it",
    holds: "the schema's findings on that value in that attribute, placed at each ParameterReference giving it",
    bound: { entries: 64, text: 'one entry per attribute; 64 values each, then started again' },
    invalidated: 'never: an attribute, its element and the schemas never change (a new parse of the group is a new key)',
  },
  lastScenarioModels: {
    where: '`core/model.ts`',
    key: 'a parse',
    holds:
      'the modular model read from it, given again when the parse is read again (a change leaving the text as it was, a generation that changed another file) and from which the model of the next parse after a value edit is carried',
    bound: WITH_KEY,
    invalidated: 'never: a new parse is a new key',
  },
  linksOfParse: {
    where: '`Flattener.linkAll` (`core/flatten/carriedLinks.ts`)',
    key: 'a parse of a file with references',
    holds:
      "the links its references were given (resolution, source read, groups, override plans) and the problems each reported, with the store and the files being read: after an edit inside one value, a reference outside the edited group whose file resolves to the same source read takes its link (a parse's own parameters planned again) and its problems (moved on the edited line) instead of being linked again; so does every reference of the same parse read again. With them, the analysis's checks of each reference (`referenceChecks`: undeclared imported entities, override values against their attribute), taken by a carried reference when the entities declared and the schema version read are as they were and it read no parameter of the main file",
    bound: WITH_KEY,
    invalidated:
      'never: a new parse is a new key; a link is taken only while its resolution and source read are those `resolve` and `source` would give now',
  },
  previousParseOfValueEdit: {
    where: '`valueEditOf` (`core/xml/reparse.ts`)',
    key: 'the new parse of an in-value edit',
    holds: 'the parse it came from, and how its elements map to the new ones',
    bound: { text: 'at most one previous tree per edited file' },
    invalidated: "once the new parse's semantic model is built (`forgetValueEdit`), or when the next edit re-parses it",
  },
  textSearches: {
    where: '`parseTextMatches` (`core/xml/textSearch.ts`)',
    key: 'a parse, then a search of its whole text (`TextSearch`)',
    holds:
      "whether the text holds a match (the scan for a distribution file's `<ParameterValueDistribution`, on each diagnostics pass of an open file); the parse after an edit inside one value takes the previous parse's answers when neither text has a match within the search's span of the edit (`carryTextSearches`, from the re-parse), instead of scanning the new text",
    bound: WITH_KEY,
    invalidated: 'never: a new parse is a new key (a parse not made by a value edit, or with a match near the edit, is scanned when asked)',
  },
  semanticModels: {
    where: '`semanticModelOf` (`core/semantics/model.ts`)',
    key: 'a parse',
    holds:
      "scopes, declarations, uses of `$name` and `${...}`, names; after an edit inside one value that is not a name, type or reference, carried over from the previous parse's model (`semantics/incremental.ts`: elements mapped through the re-parse's table of the copies it made, entries about shared subtrees taken as they are, later offsets moved, a site's parsed form moved only when read, the edited value read again)",
    bound: WITH_KEY,
    invalidated:
      'never: a new parse is a new key; each `FlatSource` holds its `DocumentSemantics` (model, evaluator, catalogs) and goes with it',
  },
  modelCarries: {
    where: '`core/semantics/incremental.ts`',
    key: 'a semantic model carried over an in-value edit',
    holds: 'what its checks take from the previous model (the changed declarations, the offset shift)',
    bound: WITH_KEY,
    invalidated: 'taken once (`takeModelCarry`)',
  },
  expressionErrors: {
    where: '`checks/carriedResults.ts`',
    key: 'a semantic model, per reading',
    holds:
      'the errors of each site and declaration the last `expressionErrors` found, before they are placed; a model carried over an in-value edit takes those of values naming no changed declaration (transitively), offsets moved',
    bound: WITH_KEY,
    invalidated: 'never: a new model is a new key; the carry from the previous model is taken once (`takeModelCarry`)',
  },
  elementIndex: {
    where: '`elementsNamed` (`core/semantics/elementIndex.ts`)',
    key: 'a semantic model',
    holds: "the document's elements by name, for the network checks",
    bound: WITH_KEY,
    invalidated:
      "never: a new model is a new key; a model carried over an in-value edit takes the previous model's lists, each element its counterpart (`ValueEdit.counterparts`: only the elements holding the edit, and those after it when it moved them, looked up by halves; a list holding none of them as it is)",
  },
  namedSiblings: {
    where: '`namedSiblings` (`core/semantics/elementIndex.ts`)',
    key: 'a semantic model',
    holds: "each element's children that have a `name` attribute, where two or more do, for the check of names unique on each level",
    bound: WITH_KEY,
    invalidated:
      "never: a new model is a new key; a model carried over an in-value edit takes the previous model's lists, each element its counterpart",
  },
  catalogFiles: {
    where: '`core/semantics/catalogs.ts`, per store',
    key: 'a `ScenarioStore` (a workspace, a CLI run), then file and text',
    holds:
      "each catalog file's model and entries, so a loader of the next generation (or the next file of a folder check) does not model it again",
    bound: { entries: 200, text: '200 files' },
    invalidated: 'a changed text is modelled again; the oldest goes first',
  },
  roadSignals: {
    where: '`core/semantics/roadNetwork.ts`, per store',
    key: 'a `ScenarioStore`, then the road file',
    holds:
      'the signal ids and roads of left-hand traffic of the road file a scenario names, for the road rules and Insert into Main: a read reused for 2 s, and the summary by path and content hash',
    bound: { entries: 8, freshMs: 2000, text: '8 files by content hash; reads of the last 2 s' },
    invalidated: 'a read older than 2 s is read again; a changed text is parsed again',
  },
  carlaCatalogSchemaErrors: {
    where: '`core/semantics/carlaFiles.ts`',
    key: 'a modelled catalog file (`CatalogFile`)',
    holds: "the first 3 of its errors against the OpenSCENARIO 1.0 schema, for the CARLA profile's report",
    bound: WITH_KEY,
    invalidated: 'never: a changed text is modelled again, a new key (see `catalogFiles`)',
  },
  standardEvaluators: {
    where: '`core/flatten/checks.ts`',
    key: "an imported file's semantic model",
    holds: 'the evaluator of its values without overrides, one per model rather than one per reference and edit',
    bound: WITH_KEY,
    invalidated: 'never: a new model is a new key',
  },
  entityReferences: {
    where: '`core/flatten/checks.ts`',
    key: 'a group element',
    holds: 'the entity references below it',
    bound: WITH_KEY,
    invalidated: 'never: an element never changes',
  },
  firstPrivateActions: {
    where: '`privateActionActors` (`core/semantics/networkChecks.ts`)',
    key: 'a ManeuverGroup element',
    holds: 'the first PrivateAction below it (none: null), so the check of actors does not walk every group on each edit',
    bound: WITH_KEY,
    invalidated: 'never: an element never changes',
  },
  listsWithinRanges: {
    where: '`valueRanges` (`core/semantics/networkChecks.ts`)',
    key: 'a list of the elements of one name (`elementIndex`)',
    holds:
      'the ranges of the schema version read when every value they constrain in the list is written without `$` and lies within them, so the check skips the list while a value edit elsewhere keeps it',
    bound: WITH_KEY,
    invalidated: 'never: a list is carried as it is only while every element in it is; an edit of one makes a new list',
  },
  distinctLiteralNames: {
    where: '`duplicateNames` (`core/semantics/checks/names.ts`)',
    key: "a list of an element's children with names (`namedSiblings`)",
    holds:
      'that their names are written without `$` and all differ, so no name repeats there whatever the parameters: the check skips the list',
    bound: WITH_KEY,
    invalidated: 'never: a list is carried as it is only while every element in it is; an edit of one makes a new list',
  },
  declaredEntityReferences: {
    where: '`undeclaredEntities` (`core/semantics/checks.ts`)',
    key: "a semantic model's list of entity references",
    holds:
      'the names they use when every one is written without `$` and declared, so the check skips the list while those names stay declared (a value edit leaving the references alone keeps the list: `carriedEntries`)',
    bound: WITH_KEY,
    invalidated: 'never: a list is carried as it is only while every reference in it is; an edit of one makes a new list',
  },
  reachesOutside: {
    where: '`core/flatten/carry.ts`',
    key: 'an element a carried declaration targets',
    holds: 'whether its values name declarations outside the group',
    bound: WITH_KEY,
    invalidated: 'never: an element never changes',
  },
  parameterUses: {
    where: '`core/flatten/carry.ts`',
    key: 'a semantic model',
    holds: 'its parameter uses by element, for the carry of declarations (SPEC 11)',
    bound: WITH_KEY,
    invalidated: 'never: a new model is a new key',
  },
  controllerFileUses: {
    where: '`importedControllerFileProblems` (`core/flatten/rebase.ts`)',
    key: "an imported group (in its file's flattened model)",
    holds:
      "the CatalogReferences inside it to a Controller entry whose File is a relative path, each where it was written, with the path's value, so an analysis of the importing main looks up only whether that path names a file from the main's folder (the store's kinds, `fileBytes`) on each edit",
    bound: WITH_KEY,
    invalidated: 'never: a changed imported file (or one it imports) is read again, a new model and a new key',
  },
  namedElements: {
    where: '`core/modularize/simpleScenario.ts`',
    key: 'a parse',
    holds: 'its elements by kind and `name`, however many behaviours look into it',
    bound: WITH_KEY,
    invalidated: 'never: a new parse is a new key',
  },
  elementTypes: {
    where: '`typeOfElement` (`core/schema/query.ts`)',
    key: 'a schema index, then an element',
    holds: "the element's complex type, found from the root's content model (override checks ask on every edit)",
    bound: WITH_KEY,
    invalidated: 'never: a parse and a schema never change',
  },
  contentTransitions: {
    where: '`core/schema/automaton.ts`, per content automaton',
    key: 'a set of automaton states, then a child name',
    holds: 'the states after that child, and the particle it matched',
    bound: WITH_KEY,
    invalidated: 'never: built from bundled schemas',
  },
  exportNodeIndexes: {
    where: '`indexOf` (`core/export/tree.ts`), per tree the CARLA export rewrites',
    key: "a tree's root node",
    holds: 'its nodes in document order and by name, for the rules that ask for the nodes of a name dozens of times',
    bound: WITH_KEY,
    invalidated:
      'kept up to date by the structural changes of `core/export/tree.ts` (`reindex`, `unindex`); dropped when a root is adopted or many nodes changed (`adopted`, `liveIndex`)',
  },
} as const satisfies Record<string, MemoDeclaration>;

export type CoreMemoName = keyof typeof CORE_MEMOS;

/**
 * The store of one of the core's memos, keyed by the object it is derived from. Each name is asked for
 * by one module (`test/server/database.test.ts` checks it).
 */
export function coreMemo<K extends object, V>(name: CoreMemoName): WeakMap<K, V> {
  void name;
  return new WeakMap<K, V>();
}
