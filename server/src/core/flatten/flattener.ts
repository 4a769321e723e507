import * as path from 'node:path';
import { declareUtf8 } from '../encoding';
import { buildModel, readModel, ScenarioModel } from '../model';
import { Problem, uniqueProblems } from '../problems';
import { xmlWording } from '../diagnostics/xml';
import { CarlaRelease, DEFAULT_CARLA_RELEASE, Simulator } from '../profiles/simulators';
import { parameterValueProblems } from '../semantics/parameterValues';
import { schemaProblems } from '../diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../schema/problems';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../semantics';
import { refId, ScenarioStore, SourceError, SourceRef } from '../sources';
import { isWellFormed, parseXml, ValueEdit, valueEditOf } from '../xml';
import { LinkCarry, linkProblems, ReferenceCheckResults, rememberLinks } from './carriedLinks';
import { checkDeclarations, checkOutput } from './checks';
import { applyEdits, parameterAttributeSpans } from './edits';
import { duplicateOuterGroupProblems, link } from './link';
import { outputSchemaProblems } from './outputSchema';
import { referenceChecks } from './referenceChecks';
import { problemAt } from './report';
import { importedControllerFileProblems, pathBaseOf, rebaseFlattened } from './rebase';
import { render } from './render';
import {
  AnalysisResult,
  FlatSource,
  FlattenOptions,
  FlattenResult,
  LinkedReference,
  PackagedFile,
  SchemaOptions,
  concernsImporter,
} from './types';

/** The catalogs a file reaches (its own references first, then those of the files it imports from). */
function catalogIndexOf(source: FlatSource): Map<string, { kind: string; directory: string }> {
  const index = new Map<string, { kind: string; directory: string }>();
  const catalogs = source.semantics?.catalogs;
  for (const resolution of catalogs?.references ?? []) {
    const file = resolution.catalogs[0];
    const name = resolution.catalogName;
    if (!file || !name || file.ref.entries.length > 0 || index.has(name)) continue;
    const directory = path.dirname(file.ref.disk);
    const location = catalogs?.locations.find((candidate) =>
      candidate.directories.some((known) => !known.packageRef && known.directory === directory),
    );
    if (location) index.set(name, { kind: location.location.kind, directory });
  }
  for (const link of source.links) {
    for (const [name, place] of link.source?.catalogIndex ?? []) if (!index.has(name)) index.set(name, place);
  }
  return index;
}

/**
 * Flattens modular scenarios (SPEC 4 and 5). One instance caches every file it read and flattened,
 * so a simple scenario used by many references is read and reported once.
 */
export class Flattener {
  private readonly cache = new Map<string, Promise<FlatSource>>();
  /** Catalog files read for this flattener's files (a new flattener reads them again). */
  readonly catalogs: CatalogLoader;

  constructor(
    readonly store: ScenarioStore,
    /** The simulator whose known gaps each file read is checked for (core/profiles); `asam`: none. */
    readonly simulator: Simulator = 'asam',
    /** Off unless asked for: the CLI and the language server pass their setting (`auto` by default). */
    readonly schema: SchemaOptions = { version: 'off' },
    /** The last schema check of each file, for a quick check again after an edit inside one value (a workspace passes its own to each generation). */
    readonly schemaChecks: SchemaCheckMemory = new SchemaCheckMemory(),
    /** With `simulator` = `carla`: the ScenarioRunner release whose facts apply. */
    readonly carlaRelease: CarlaRelease = DEFAULT_CARLA_RELEASE,
  ) {
    this.catalogs = new CatalogLoader(store);
  }

  /** Every problem of `main` and of what it uses, without writing its flattened text (for an editor). */
  async analyze(main: SourceRef): Promise<AnalysisResult> {
    const source = await this.source(main, []);
    const { entity, override } = referenceChecks(source, this.schema.version);
    const controllerFiles = await importedControllerFileProblems(source, this.store);
    return {
      problems: uniqueProblems([...source.allProblems, ...entity, ...override, ...controllerFiles.problems]),
      source,
      lookedUp: controllerFiles.lookedUp,
    };
  }

  /** Flattens the scenario `main` (a `main.xosc` on disk or inside a package) into plain OpenSCENARIO. */
  async flatten(main: SourceRef, options: FlattenOptions = {}): Promise<FlattenResult> {
    // Standard output names files absolutely (SPEC 11.6); a file names them from its own folder.
    const outputPath = options.standardOutput
      ? undefined
      : path.resolve(options.outputPath ?? path.join(pathBaseOf(main), 'flattened.xosc'));
    const analysis = await this.analyze(main);
    const source = this.rendered(analysis.source);
    // The output is checked strictly against the schema too; its problems are reported where the source wrote them.
    const schemaVersion = this.schema.version;
    const schemaOutput =
      schemaVersion !== 'off' && source.model && source.model !== source.original
        ? outputSchemaProblems(source, this.schemaChecks, { version: schemaVersion })
        : [];
    // Rendering the main file itself may find it too large.
    const found = [
      ...analysis.problems,
      ...source.problems,
      ...(source.carried?.problems ?? []),
      ...(await checkOutput(this, source, pathBaseOf(main))),
      ...schemaOutput,
    ];
    // Forced, every error is listed and whatever could be rendered is written (SPEC 12); else any error refuses.
    const blocking = options.force ? [] : found.filter((problem) => problem.severity === 'error');
    let text: string | undefined;
    let files: PackagedFile[] = [];
    if (source.text !== undefined && blocking.length === 0) {
      const model = source.model ?? buildModel(parseXml(source.text));
      const rebase = await rebaseFlattened(source, model, outputPath, this.store, options);
      found.push(...rebase.problems);
      files = rebase.files;
      // Removing whole attributes and replacing path values keeps a well-formed text well-formed, so the rendered model is the check.
      const stripped = parameterAttributeSpans(model).map((span) => ({ ...span, text: '' }));
      text = declareUtf8(applyEdits(model.document.text, [...stripped, ...rebase.edits]));
    }
    if (text !== undefined && source.model && !isWellFormed(source.model.document)) {
      throw new Error('internal error: the flattened output is not well-formed XML');
    }
    return { text, problems: uniqueProblems(found), source, files };
  }

  /** Reads (and, when it holds references, flattens) one file; cached per file. */
  source(ref: SourceRef, stack: SourceRef[]): Promise<FlatSource> {
    const id = refId(ref);
    let pending = this.cache.get(id);
    if (!pending) {
      pending = this.build(ref, [...stack, ref]);
      this.cache.set(id, pending);
    }
    return pending;
  }

  /** What `source` would give without reading: this flattener reads each file once and carries no links across edits. */
  knownSource(ref: SourceRef, stack: SourceRef[]): FlatSource | undefined {
    void ref;
    void stack;
    return undefined;
  }

  /**
   * Renders the flattened text and model of a source on first use: only the sources whose groups
   * are imported, and the outputs, need them, so an editor analysing one file never renders it.
   * Carried catalog locations are written relative to the source's own folder; flatten rebases them with every other path.
   */
  rendered(source: FlatSource): FlatSource {
    if (source.renderable && source.original) {
      source.renderable = false;
      render(this.store, source, source.original, pathBaseOf(source.ref));
    }
    return source;
  }

  protected async build(ref: SourceRef, stack: SourceRef[]): Promise<FlatSource> {
    const result: FlatSource = {
      ref,
      original: undefined,
      links: [],
      text: undefined,
      model: undefined,
      insertions: [],
      problems: [],
      allProblems: [],
      dependencies: [ref],
      renderable: false,
      semantics: undefined,
      catalogIndex: new Map(),
      carried: undefined,
      additions: [],
    };
    let text: string;
    try {
      text = await this.store.readText(ref);
    } catch (error) {
      const sourceError = error instanceof SourceError ? error : undefined;
      const line = sourceError?.line ?? 0;
      result.problems.push({
        source: ref,
        range: { start: { line, character: 0 }, end: { line, character: 0 } },
        severity: 'error',
        code: sourceError?.code ?? 'io',
        message: (error as Error).message,
        hint: sourceError?.hint,
      });
      result.allProblems = [...result.problems];
      return result;
    }
    const document = this.store.parse(ref, text);
    for (const problem of document.problems) {
      result.problems.push(
        problemAt({
          source: ref,
          document,
          start: problem.start,
          end: problem.end,
          ...xmlWording(problem.severity, problem.message),
        }),
      );
    }
    const schemaVersion = this.schema.version;
    if (schemaVersion !== 'off') result.problems.push(...schemaProblems(ref, document, this.schemaChecks, { version: schemaVersion }));
    // Taken before the semantic model lets the previous parse go: the links of references the edit left alone carry over.
    const valueEdit = valueEditOf(document);
    const model = readModel(document);
    result.original = model;
    checkDeclarations(result, model);
    if (document.root) {
      const semantics = await analyzeDocument(ref, document, this.catalogs, model.references.length > 0, this.simulator, this.carlaRelease);
      result.semantics = semantics;
      result.problems.push(...semanticProblems(semantics));
      // The schema's attribute types, for the values parameters give them.
      if (schemaVersion !== 'off') result.problems.push(...parameterValueProblems(semantics, schemaVersion));
      for (const file of semantics.catalogs.files)
        if (!result.dependencies.some((known) => refId(known) === refId(file))) result.dependencies.push(file);
    }
    const wellFormed = isWellFormed(document);
    await this.linkAll(result, model, stack, valueEdit);
    result.catalogIndex = catalogIndexOf(result);

    if (!wellFormed) return result;
    if (model.references.length === 0) {
      result.text = text;
      result.model = model;
      return result;
    }
    // Rendered whatever its errors: whether they stop the output is the caller's choice (`force`), made in flatten.
    result.renderable = true;
    return result;
  }

  /** Follows every reference of a file read, gathering the problems and dependencies of the files they read. */
  private async linkAll(result: FlatSource, model: ScenarioModel, stack: SourceRef[], valueEdit: ValueEdit | undefined): Promise<void> {
    const childProblems: Problem[] = [];
    const dependencyIds = new Set([refId(result.ref)]);
    result.problems.push(...duplicateOuterGroupProblems(model, result.ref));
    const carry = LinkCarry.of(model.document, valueEdit, model.references.length, this, result.ref, stack);
    const problemsOfLinks: Problem[][] = [];
    const carriedChecks: (ReferenceCheckResults | undefined)[] = [];
    // By index: an entries() iterator makes a pair for each reference on each edit.
    for (let index = 0; index < model.references.length; index++) {
      const reference = model.references[index];
      const carried = carry?.carry(index, reference);
      const firstProblem = result.problems.length;
      let linked: LinkedReference;
      carriedChecks.push(carried ? carry?.checksOf(index) : undefined);
      if (carried) {
        linked = carried.link;
        result.problems.push(...carried.problems);
      } else {
        linked = await link(this, reference, result.ref, model, stack, result);
      }
      problemsOfLinks.push(linkProblems(result.problems, firstProblem, result.problems.length));
      result.links.push(linked);
      if (linked.source) {
        const groupNames = reference.groupReferences.map((groupReference) => groupReference.name);
        for (const problem of linked.source.allProblems)
          if (concernsImporter(problem, linked.source, groupNames)) childProblems.push(problem);
        for (const dependency of linked.source.dependencies) {
          const id = refId(dependency);
          if (!dependencyIds.has(id)) {
            dependencyIds.add(id);
            result.dependencies.push(dependency);
          }
        }
      }
    }
    result.allProblems = uniqueProblems([...result.problems, ...childProblems]);
    if (model.references.length > 0) {
      const checksContext = carry?.checksContext;
      rememberLinks(model.document, {
        store: this.store,
        stack: stack.map(refId),
        links: result.links,
        problems: problemsOfLinks,
        checks: checksContext === undefined ? undefined : { context: checksContext, results: carriedChecks },
      });
    }
  }
}
