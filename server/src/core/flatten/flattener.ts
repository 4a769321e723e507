import * as path from 'node:path';
import { declareUtf8 } from '../encoding';
import { buildModel, readModel, ScenarioModel } from '../model';
import { Problem, uniqueProblems } from '../problems';
import { Simulator } from '../profiles/simulators';
import { SchemaCheckMemory, schemaProblems } from '../schema/problems';
import { SCHEMA_PROBLEM_CODES } from '../schema/validate';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../semantics';
import { refId, ScenarioStore, SourceError, SourceRef } from '../sources';
import { isWellFormed, parseXml } from '../xml';
import { checkDeclarations, checkOutput, entityProblems } from './checks';
import { stripParameterAttributes } from './edits';
import { link } from './link';
import { outputSchemaProblems, overrideValueProblems } from './outputSchema';
import { problemAt } from './report';
import { render } from './render';
import { AnalysisResult, FlatSource, FlattenOptions, FlattenResult, OVERRIDE_PROBLEM_CODES, SchemaOptions } from './types';

/** The catalogs a file reaches (its own references first, then those of the files it imports from). */
function catalogIndexOf(source: FlatSource): Map<string, { kind: string; directory: string }> {
  const index = new Map<string, { kind: string; directory: string }>();
  const catalogs = source.semantics?.catalogs;
  for (const resolution of catalogs?.references ?? []) {
    const file = resolution.catalogs[0];
    const name = resolution.catalogName;
    if (!file || !name || file.ref.entries.length > 0 || index.has(name)) continue;
    const directory = path.dirname(file.ref.disk);
    const location = catalogs?.locations.find((candidate) => candidate.directories.some((known) => !known.packageRef && known.directory === directory));
    if (location) index.set(name, { kind: location.location.kind, directory });
  }
  for (const link of source.links) {
    for (const [name, place] of link.source?.catalogIndex ?? []) if (!index.has(name)) index.set(name, place);
  }
  return index;
}

/** Whether an error stops flattening (overrides and schema problems do not: `--force` writes the output despite them). */
function blocksRendering(problem: Problem): boolean {
  return problem.severity === 'error' && !OVERRIDE_PROBLEM_CODES.has(problem.code) && !SCHEMA_PROBLEM_CODES.has(problem.code);
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
  ) {
    this.catalogs = new CatalogLoader(store);
  }

  /** Every problem of `main` and of what it uses, without writing its flattened text (for an editor). */
  async analyze(main: SourceRef): Promise<AnalysisResult> {
    const source = await this.source(main, []);
    const schemaVersion = this.schema.version;
    const overrides = schemaVersion === 'off' ? [] : overrideValueProblems(source, { version: schemaVersion });
    return { problems: uniqueProblems([...source.allProblems, ...entityProblems(source), ...overrides]), source };
  }

  /** Flattens the scenario `main` (a `main.xosc` on disk or inside a package) into plain OpenSCENARIO. */
  async flatten(main: SourceRef, options: FlattenOptions = {}): Promise<FlattenResult> {
    const outputDirectory = path.dirname(path.resolve(options.outputPath ?? main.disk));
    const analysis = await this.analyze(main);
    const source = await this.renderedFor(analysis.source, outputDirectory);
    // The output is checked strictly against the schema too; its problems are reported where the source wrote them.
    const schemaVersion = this.schema.version;
    const schemaOutput =
      schemaVersion !== 'off' && source.model && source.model !== source.original ? outputSchemaProblems(source, this.schemaChecks, { version: schemaVersion }) : [];
    // Rendering the main file itself may find it too large.
    const problems = uniqueProblems([
      ...analysis.problems,
      ...source.problems,
      ...(source.carried?.problems ?? []),
      ...(await checkOutput(this, source, outputDirectory)),
      ...schemaOutput,
    ]);
    const blocking = problems.filter(
      (problem) => problem.severity === 'error' && !(options.force && (OVERRIDE_PROBLEM_CODES.has(problem.code) || SCHEMA_PROBLEM_CODES.has(problem.code))),
    );
    const text = source.text !== undefined && blocking.length === 0 ? declareUtf8(stripParameterAttributes(source.model ?? buildModel(parseXml(source.text)))) : undefined;
    // Removing whole attributes keeps a well-formed text well-formed, so the rendered model is the check.
    if (text !== undefined && source.model && !isWellFormed(source.model.document)) {
      throw new Error('internal error: the flattened output is not well-formed XML');
    }
    return { text, problems, source };
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

  /**
   * Renders the flattened text and model of a source on first use: only the sources whose groups
   * are imported, and the outputs, need them, so an editor analysing one file never renders it.
   * Carried catalog locations are written relative to `outputDirectory` (the source's own folder by default).
   */
  rendered(source: FlatSource, outputDirectory: string = path.dirname(source.ref.disk)): FlatSource {
    if (source.renderable && source.original) {
      source.renderable = false;
      render(this.store, source, source.original, outputDirectory);
    }
    return source;
  }

  /**
   * The source rendered for an output in `outputDirectory`: the cached rendering when its text does not
   * depend on the folder or was made for this one, else a new reading of the file rendered for it.
   */
  private async renderedFor(source: FlatSource, outputDirectory: string): Promise<FlatSource> {
    const rendered = this.rendered(source, outputDirectory);
    if (rendered.locationsRelativeTo === undefined || rendered.locationsRelativeTo === outputDirectory) return rendered;
    return this.rendered(await this.build(source.ref, [source.ref]), outputDirectory);
  }

  private async build(ref: SourceRef, stack: SourceRef[]): Promise<FlatSource> {
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
      locationsRelativeTo: undefined,
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
        code: sourceError && /ZIP|package|unpacks|entry/.test(sourceError.message) ? 'bad-package' : 'io',
        message: (error as Error).message,
        hint: sourceError?.hint,
      });
      result.allProblems = [...result.problems];
      return result;
    }
    const document = this.store.parse(ref, text);
    for (const problem of document.problems) {
      result.problems.push(problemAt({ source: ref, document, start: problem.start, end: problem.end, severity: problem.severity, code: 'xml', message: problem.message }));
    }
    const schemaVersion = this.schema.version;
    if (schemaVersion !== 'off') result.problems.push(...schemaProblems(ref, document, this.schemaChecks, { version: schemaVersion }));
    const model = readModel(document);
    result.original = model;
    checkDeclarations(result, model);
    if (document.root) {
      const semantics = await analyzeDocument(ref, document, this.catalogs, model.references.length > 0);
      semantics.simulator = this.simulator;
      result.semantics = semantics;
      result.problems.push(...semanticProblems(semantics));
      for (const file of semantics.catalogs.files) if (!result.dependencies.some((known) => refId(known) === refId(file))) result.dependencies.push(file);
    }
    const wellFormed = isWellFormed(document);
    await this.linkAll(result, model, stack);
    result.catalogIndex = catalogIndexOf(result);

    if (!wellFormed) return result;
    if (model.references.length === 0) {
      result.text = text;
      result.model = model;
      return result;
    }
    result.renderable = !result.allProblems.some(blocksRendering);
    return result;
  }

  /** Follows every reference of a file read, gathering the problems and dependencies of the files they read. */
  private async linkAll(result: FlatSource, model: ScenarioModel, stack: SourceRef[]): Promise<void> {
    const childProblems: Problem[] = [];
    const dependencyIds = new Set([refId(result.ref)]);
    for (const reference of model.references) {
      const linked = await link(this, reference, result.ref, model, stack, result);
      result.links.push(linked);
      if (linked.source) {
        childProblems.push(...linked.source.allProblems);
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
  }
}
