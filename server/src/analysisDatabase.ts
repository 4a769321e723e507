import { AnalysisResult, Flattener, FlatSource } from './core/flatten';
import { Problem } from './core/problems';
import { SchemaCheckMemory } from './core/schema/problems';
import { refId, ScenarioStore, SourceRef } from './core/sources';
import { SERVER_MEMOS } from './database';
import { OpenDocuments } from './documents';
import { ServerSettings } from './settings';
import { ReusingFlattener, SHARED_SOURCE_BYTES, SharedSources } from './sharedSources';
import { SourceDependencies } from './sourceDependencies';

/** An analysis of one generation: whole while pending or for an open document, else its problems only. */
interface CachedAnalysis {
  generation: number;
  result: Promise<AnalysisResult> | undefined;
  problems: Problem[];
  lookedUp: string[];
}

/** What the database derives its state from: the workspace's inputs, read when asked (a new store on settings or folders). */
export interface DatabaseInputs {
  store: () => ScenarioStore;
  settings: () => ServerSettings;
  documents: OpenDocuments;
}

/**
 * The owner of the server's derived analysis state (the memos `sharedSources`, `analyses`, `flattener` and
 * `lastSchemaChecks` of `database.ts`): the generation, the sources read and flattened across generations
 * with their dependencies, the files open documents read, the last schema check of each file, the analyses
 * of the current generation and its Flattener. The `Workspace` owns the inputs (store, open documents,
 * settings, folders) and tells the database what changed (`changed`); everything here is derived from them.
 */
export class AnalysisDatabase {
  private generation = 0;
  private flattenerGeneration = -1;
  private currentFlattener: Flattener | undefined;
  /** Sources read so far, kept across generations until a file they depend on changes. */
  private readonly sharedSources: SharedSources;
  /** What each shared source depends on, and the reverse: the sources a change makes stale. */
  private readonly sourceDependencies = new SourceDependencies();
  /**
   * The files each open document's source read, as last known (kept in memory while it is open): the
   * dependencies of its last read (`from`), and the files a read still running has asked for since (`grew` once it
   * asked for one not among them).
   */
  private readonly openDocumentReads = new Map<string, { ids: Set<string>; from: string[] | undefined; grew: boolean }>();
  /** The last schema check of each file, shared by every generation's flattener. */
  private readonly schemaChecks = new SchemaCheckMemory();
  /** Analyses of the current generation; one of a file not open keeps only its problems, its source staying in the shared sources. */
  private readonly analysisResults = new Map<string, CachedAnalysis>();

  /** `sharedSourceBytes`: the bound of the read sources kept beyond those open documents read. */
  constructor(
    private readonly inputs: DatabaseInputs,
    sharedSourceBytes = SHARED_SOURCE_BYTES,
  ) {
    this.sharedSources = new SharedSources(sharedSourceBytes, () => this.keptSources());
  }

  /** Grows with every change that can alter an analysis: equal versions give equal diagnostics. */
  get version(): number {
    return this.generation;
  }

  /**
   * Marks analyses stale: those depending on the given files (ids, or disk paths of files and
   * folders), or every one when no file is named (settings, or a file appearing or vanishing,
   * which can change how any name resolves).
   */
  changed(changedIds?: string[]): void {
    this.generation++;
    // Remembers what open documents read before their dependencies are forgotten below.
    this.rememberOpenReads();
    if (!changedIds) {
      this.analysisResults.clear();
      this.sharedSources.clear();
      this.sourceDependencies.clear();
      return;
    }
    const folders = changedIds.map((changed) => changed + '/');
    const touches = (id: string) => changedIds.includes(id) || folders.some((folder) => id.startsWith(folder));
    // At most the bound's entries (an open document's and a few more); older generations' are stale anyway.
    for (const id of [...this.analysisResults.keys()]) if (touches(id)) this.analysisResults.delete(id);
    // From the reverse index: a keystroke does not walk every shared source (400 for a main with 400 references).
    for (const id of this.sourceDependencies.staleAfter(changedIds)) {
      this.sharedSources.delete(id);
      this.sourceDependencies.delete(id);
    }
  }

  /** A document closed: what it kept (the files it read) counts against the bound again. */
  documentClosed(): void {
    this.sharedSources.trim();
  }

  /** Open documents and every file their sources read: what each edit of an open file reads again. */
  private keptSources(): Set<string> {
    this.rememberOpenReads();
    const kept = new Set<string>();
    for (const [id, reads] of this.openDocumentReads) {
      kept.add(id);
      for (const dependency of reads.ids) kept.add(dependency);
    }
    return kept;
  }

  /** Brings `openDocumentReads` up to date: an entry per open document, the files its last read depended on. */
  private rememberOpenReads(): void {
    const open = new Set<string>();
    for (const document of this.inputs.documents.values()) {
      const id = refId(document.ref);
      open.add(id);
      // An edit forgets the file's dependencies until it is read again: what it read last time stays meanwhile.
      const known = this.sourceDependencies.get(id);
      const reads = this.openDocumentReads.get(id);
      // Made again only when the dependencies or the files noted since differ: a keystroke mostly leaves both as they were.
      if (!reads || (known && (reads.from !== known || reads.grew)))
        this.openDocumentReads.set(id, { ids: new Set(known), from: known, grew: false });
    }
    for (const id of [...this.openDocumentReads.keys()]) if (!open.has(id)) this.openDocumentReads.delete(id);
  }

  /**
   * A file read for an open document's analysis is kept from the moment it is read: counted against
   * the bound until that analysis ends, the files read first were let go while it read the others,
   * and the next edit read them all again (144 of 400 for a main file with 400 references).
   */
  private noteRead(reader: string, id: string): void {
    if (!this.inputs.documents.get(reader) || this.sourceDependencies.has(reader)) return;
    const reads = this.openDocumentReads.get(reader);
    if (!reads) this.openDocumentReads.set(reader, { ids: new Set([id]), from: undefined, grew: true });
    else if (!reads.ids.has(id)) {
      reads.ids.add(id);
      reads.grew = true;
    }
  }

  flattener(): Flattener {
    if (!this.currentFlattener || this.flattenerGeneration !== this.generation) {
      const settings = this.inputs.settings();
      this.currentFlattener = new ReusingFlattener(
        this.inputs.store(),
        this.sharedSources,
        this.sourceDependencies,
        settings.simulator,
        { version: settings.schemaVersion },
        this.schemaChecks,
        (reader, id) => this.noteRead(reader, id),
        settings.carlaRelease,
      );
      this.flattenerGeneration = this.generation;
    }
    return this.currentFlattener;
  }

  /** The file read and flattened as the current generation sees it. */
  source(ref: SourceRef): Promise<FlatSource> {
    return this.flattener().source(ref, []);
  }

  /** The file analysed as a main file (with the checks only a main file gets), cached per generation. */
  analyze(ref: SourceRef): Promise<AnalysisResult> {
    const id = refId(ref);
    const cached = this.analysisResults.get(id);
    if (cached && cached.generation === this.generation) {
      if (cached.result) return cached.result;
      const { problems, lookedUp } = cached;
      // The source as the shared sources still hold it, or read again: the same text gives the same source.
      return this.source(ref).then((source) => ({ problems, source, lookedUp }));
    }
    const result = this.flattener().analyze(ref);
    const fresh: CachedAnalysis = { generation: this.generation, result, problems: [], lookedUp: [] };
    this.analysisResults.set(id, fresh);
    // A file not open must not keep its parse tree past the bound of the shared sources.
    if (!this.inputs.documents.get(id))
      result.then(
        (analysis) => {
          if (this.analysisResults.get(id) !== fresh || this.inputs.documents.get(id)) return;
          fresh.problems = analysis.problems;
          fresh.lookedUp = analysis.lookedUp;
          fresh.result = undefined;
        },
        () => undefined,
      );
    if (this.analysisResults.size > SERVER_MEMOS.analyses.bound.entries)
      for (const [key, entry] of this.analysisResults) if (entry.generation !== this.generation) this.analysisResults.delete(key);
    return result;
  }
}
