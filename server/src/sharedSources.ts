import { Flattener, FlatSource, SchemaOptions } from './core/flatten';
import { SchemaCheckMemory } from './core/schema/problems';
import { refId, ScenarioStore, SourceRef } from './core/sources';
import { CarlaRelease, Simulator } from './core/profiles/simulators';
import { SERVER_MEMOS } from './database';
import { SourceDependencies } from './sourceDependencies';

/** Heap bytes a read source takes per character of its text, about (its parse tree, models and evaluated values). */
const SOURCE_BYTES_PER_CHARACTER = 30;

/** The read sources kept across generations beyond those open documents read, about this many heap bytes in all. */
export const SHARED_SOURCE_BYTES: number = SERVER_MEMOS.sharedSources.bound.bytes;

/**
 * The sources shared across generations, least recently used first out once the approximate size of
 * the others passes a bound (a source is sized when it is read). Those `kept` names (open documents and
 * the files they read) stay and do not count while kept: a large open main file must not push out the
 * files it imports, which every edit of it reads again; once its document closes they count again and
 * may go. A source let go is read again on demand.
 */
export class SharedSources {
  private readonly entries = new Map<string, { source: Promise<FlatSource>; size: number; settled?: FlatSource }>();
  /** Bytes of every source read, kept or not. */
  private total = 0;

  constructor(
    private readonly maxBytes: number,
    private readonly kept: () => ReadonlySet<string>,
  ) {}

  /** Approximate heap bytes of the sources not kept (as it was when each was read). */
  get size(): number {
    return this.total - this.keptBytes(this.kept());
  }

  get(id: string): Promise<FlatSource> | undefined {
    const entry = this.entries.get(id);
    if (!entry) return undefined;
    this.entries.delete(id);
    this.entries.set(id, entry);
    return entry.source;
  }

  /** The source of `id` once read (used as `get` is), or undefined while it is being read or not kept. */
  settled(id: string): FlatSource | undefined {
    return this.get(id) && this.entries.get(id)?.settled;
  }

  set(id: string, source: Promise<FlatSource>): void {
    this.delete(id);
    const entry: { source: Promise<FlatSource>; size: number; settled?: FlatSource } = { source, size: 0 };
    this.entries.set(id, entry);
    source.then(
      (flat) => {
        if (this.entries.get(id) !== entry) return;
        entry.settled = flat;
        entry.size = SOURCE_BYTES_PER_CHARACTER * ((flat.original?.document.text.length ?? 0) + (flat.text?.length ?? 0));
        this.total += entry.size;
        this.trim();
      },
      // The flattener forgets a source that failed; nothing is counted for it.
      () => undefined,
    );
  }

  delete(id: string): void {
    const entry = this.entries.get(id);
    if (!entry) return;
    this.entries.delete(id);
    this.total -= entry.size;
  }

  clear(): void {
    this.entries.clear();
    this.total = 0;
  }

  keys(): string[] {
    return [...this.entries.keys()];
  }

  /** Lets the least recently used sources not kept go until the rest is within the bound (also when a document closed). */
  trim(): void {
    const kept = this.kept();
    let counted = this.total - this.keptBytes(kept);
    for (const [id, entry] of this.entries) {
      if (counted <= this.maxBytes) break;
      if (entry.size > 0 && !kept.has(id)) {
        counted -= entry.size;
        this.delete(id);
      }
    }
  }

  private keptBytes(kept: ReadonlySet<string>): number {
    let bytes = 0;
    for (const id of kept) bytes += this.entries.get(id)?.size ?? 0;
    return bytes;
  }
}

/**
 * A Flattener that shares what it read with the Flatteners of later generations, so that an edit
 * in one file analyses that file again and reuses every unchanged file it depends on.
 */
export class ReusingFlattener extends Flattener {
  constructor(
    store: ScenarioStore,
    private readonly shared: SharedSources,
    private readonly dependencies: SourceDependencies,
    simulator: Simulator,
    schema: SchemaOptions,
    schemaChecks: SchemaCheckMemory,
    /** Told of each file read on behalf of another (the first of `stack`), before the read finishes. */
    private readonly noteRead: (reader: string, id: string) => void,
    carlaRelease: CarlaRelease,
  ) {
    super(store, simulator, schema, schemaChecks, carlaRelease);
  }

  /** The source `source` would give now, read before (the same bookkeeping as `source`); undefined when it would read. */
  override knownSource(ref: SourceRef, stack: SourceRef[]): FlatSource | undefined {
    const id = refId(ref);
    if (stack.length > 0) this.noteRead(refId(stack[0]), id);
    return this.shared.settled(id);
  }

  override source(ref: SourceRef, stack: SourceRef[]): Promise<FlatSource> {
    const id = refId(ref);
    if (stack.length > 0) this.noteRead(refId(stack[0]), id);
    const known = this.shared.get(id);
    if (known) return known;
    // Only the shared sources hold it (not this generation's own cache too), so their bound holds within a generation.
    const created = this.build(ref, [...stack, ref]);
    this.shared.set(id, created);
    this.dependencies.readStarted(id);
    created.then(
      (source) => {
        if (this.shared.get(id) === created)
          this.dependencies.set(
            id,
            source.dependencies.map((dependency) => refId(dependency)),
          );
      },
      () => {
        this.shared.delete(id);
        this.dependencies.readFailed(id);
      },
    );
    return created;
  }
}
