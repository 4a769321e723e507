import { CORE_MEMOS, MemoDeclaration } from './core/memos';

/**
 * The server's analysis database: every piece of derived state the language server keeps, declared
 * once with its key, its bound and what invalidates it (rust-analyzer's `RootDatabase`, the TypeScript
 * language service's `Program`). It composes the core's table (`core/memos.ts`); ARCHITECTURE.md's
 * table of caches is `cachesTable()` of it, which `test/server/database.test.ts` keeps so. A change
 * to the generation (`AnalysisDatabase.changed`, `analysisDatabase.ts`, the owner of the analysis state) is what
 * makes the per-generation entries stale.
 */
export const SERVER_MEMOS = {
  fileBytes: {
    where: '`CachingFileSystem` (`workspace.ts`)',
    key: 'a path',
    holds:
      'bytes of each file an analysis read (read again on demand once let go; the scan of the index reads without keeping, `readOnce`), file/folder kinds',
    bound: { bytes: 64 * 1024 * 1024, text: '64 MiB of bytes in all, least recently used out' },
    invalidated: 'a watched-file event for the path (bytes below it, all kinds); a save; settings',
  },
  sharedSources: {
    where: '`AnalysisDatabase.sharedSources` (`analysisDatabase.ts`; `SharedSources`, `sharedSources.ts`)',
    key: 'a file id',
    holds:
      'each file read and flattened (`FlatSource`), across generations; the only holder of the parse trees of files not open (a source let go is read again, to the same answer). Open documents and the files they read are kept beyond the bound, uncounted (a file counts as read by an open document from the moment its first analysis asks for it, `AnalysisDatabase.noteRead`, so a main importing more than the bound does not push out the files it read first); once the document closes, what it kept counts again and the least recently used go past the bound',
    bound: { bytes: 64 * 1024 * 1024, text: 'about 64 MiB of heap (30 bytes per character of text), least recently used out' },
    invalidated:
      '`AnalysisDatabase.changed(ids)`: the file and everything depending on it; all on settings or a file appearing or vanishing',
  },
  sourceDependencies: {
    where: '`AnalysisDatabase.sourceDependencies` (`analysisDatabase.ts`; `SourceDependencies`, `sourceDependencies.ts`)',
    key: 'a file id',
    holds:
      'the files each source read depends on (itself, and the files its references and catalogs read, transitively), and the reverse index: the sources depending on each file, and how many files lie below each folder or package path, so `AnalysisDatabase.changed` finds the sources a change makes stale without walking every shared source; the sources still being read (any change makes them stale). A source made stale keeps its links, left out of every answer, until it is read again: when that read finds the same files (a keystroke in a value of the main file), they are taken as they were',
    bound: {
      text: 'one entry per file read: its dependencies as ids, each in the reverse index (kept, with its links, when the shared sources let its source go or a change makes it stale, until it is read again)',
    },
    invalidated:
      'made stale with its shared source in `AnalysisDatabase.changed` (the file or a dependency changed): out of every answer, its links kept until the source is read again, which replaces it; all on settings or a file appearing or vanishing',
  },
  analyses: {
    where: '`AnalysisDatabase.analysisResults` (`analysisDatabase.ts`)',
    key: 'a file id, per generation',
    holds:
      'a file analysed as a main file: whole for an open document, only the problems for another file (its source is asked of the shared sources again)',
    bound: { entries: 200, text: '200 entries (those of older generations go first)' },
    invalidated: 'a new generation for the file or its dependencies',
  },
  flattener: {
    where: '`AnalysisDatabase.flattener()`',
    key: 'the generation',
    holds:
      "one `Flattener`; the server's (`ReusingFlattener`, `sharedSources.ts`) keeps no per-file cache of its own, the shared sources are its cache (the CLI's `Flattener` caches every file of its run)",
    bound: { entries: 1, text: 'one' },
    invalidated: 'replaced when the generation grows',
  },
  workspaceIndex: {
    where: '`Workspace.index` (`WorkspaceIndex`, `workspaceIndex.ts`)',
    key: 'a scenario file on disk',
    holds:
      "by a text scan: group names, whether it has references, and the catalog entries its `CatalogReference`s name (the reverse index a diagnostic pass asks for the scenarios referencing an entry, `Workspace.catalogReferrers`, instead of reading every file), and the `scenarioFileName`s its references write (the reverse index a pull of a file's diagnostics asks for the main files that may reach it, `Workspace.referringFiles(target)`, instead of analysing every main file); the list of files from one walk of the folders, kept while the client reports files appearing and vanishing",
    bound: { text: 'one entry per scenario file of the folders (no parse tree, files over `maxIndexedFileBytes` not scanned)' },
    invalidated:
      'an entry: the file changes on disk or in the editor, read again on next use; the list: a file appearing or vanishing (walked again on next use), folders changing',
  },
  diagnosticDependencies: {
    where: '`DiagnosticsScheduler.dependencies`',
    key: 'an open file',
    holds: 'the files its last analysis read',
    bound: { text: 'one per open document' },
    invalidated: 'replaced after each analysis; removed on close',
  },
  workspaceReport: {
    where: '`handlers/workspaceDiagnostic.ts`',
    key: 'the generation',
    holds: 'the last workspace-wide problems',
    bound: { entries: 1, text: 'one' },
    invalidated: 'when `Workspace.version` (the generation) changed',
  },
  clientUris: {
    where: '`UriResolver.known`',
    key: 'an open URI',
    holds: 'the URI spelling a client used for a file',
    bound: { text: 'one per open document' },
    invalidated: 'forgotten on close',
  },
  inlayHints: {
    where: '`features/inlayHints.ts`',
    key: 'an analysis (`DocumentSemantics`)',
    holds: 'the hints of its expressions, for every range asked',
    bound: { text: 'one entry per key, collected with it' },
    invalidated: 'never: a new analysis is a new key',
  },
  semanticTokens: {
    where: '`features/semanticTokens.ts`',
    key: 'an analysis (`DocumentSemantics`)',
    holds: 'its tokens, listed once',
    bound: { text: 'one entry per key, collected with it' },
    invalidated: 'never: a new analysis is a new key',
  },
  encodedSemanticTokens: {
    where: '`features/semanticTokens.ts`',
    key: 'an analysis (`DocumentSemantics`)',
    holds: 'its tokens as the protocol encodes them, for a full request',
    bound: { text: 'one entry per key, collected with it' },
    invalidated: 'never: a new analysis is a new key',
  },
  distributionAnalyses: {
    where: '`features/distributions.ts`, per `Workspace`',
    key: 'a distribution file, per generation',
    holds: 'the distribution read with its scenario (its parameters as esmini sees them)',
    bound: { entries: 50, text: '50 files (those of older generations go first)' },
    invalidated: 'a new generation (`Workspace.version`)',
  },
  distributionCounts: {
    where: '`features/distributions.ts`',
    key: "a distribution's variations",
    holds: 'how many concrete scenarios it gives, those its constraints refuse discarded',
    bound: { text: 'one entry per key, collected with it' },
    invalidated: 'never: new variations are a new key',
  },
  roadNetworks: {
    where: '`ServerContext.roads` (`RoadNetworkCache` in `features/scene.ts`)',
    key: 'a road file path',
    holds: 'a parsed OpenDRIVE file and its lane-border polylines, with the text it came from',
    bound: { entries: 4, text: '4 files per server' },
    invalidated: "when the file's text differs (road files are read fresh on every scene request)",
  },
  esminiRuns: {
    where: '`ServerContext.esminiRuns` (`EsminiRuns.previous` in `features/esminiRun.ts`)',
    key: 'a scenario file',
    holds: 'the private folder of its last run (flattened scenario, CSV, log)',
    bound: { text: 'one folder per file run' },
    invalidated: "deleted when the same file runs again, and all of the server's at exit",
  },
} as const satisfies Record<string, MemoDeclaration>;

export type ServerMemoName = keyof typeof SERVER_MEMOS;

/** Every memo of the language server: its own, then the core's. */
export const ANALYSIS_DATABASE: Readonly<Record<ServerMemoName | keyof typeof CORE_MEMOS, MemoDeclaration>> = {
  ...SERVER_MEMOS,
  ...CORE_MEMOS,
};

/**
 * The store of one of the server's memos, keyed by the object it is derived from. Each name is asked
 * for by one module (`test/server/database.test.ts` checks it).
 */
export function serverMemo<K extends object, V>(name: ServerMemoName): WeakMap<K, V> {
  void name;
  return new WeakMap<K, V>();
}

/** The database as ARCHITECTURE.md's table of caches: one row per memo. */
export function cachesTable(): string {
  const cell = (text: string) => text.replace(/\|/g, '\\|');
  const rows = Object.entries(ANALYSIS_DATABASE).map(
    ([name, memo]) =>
      `| \`${name}\` | ${cell(memo.where)} | ${cell(memo.key)} | ${cell(memo.holds)} | ${cell(memo.bound.text)} | ${cell(memo.invalidated)} |`,
  );
  return ['| memo | where | key | holds | bound | invalidated |', '| --- | --- | --- | --- | --- | --- |', ...rows].join('\n');
}
