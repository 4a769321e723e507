import { OverridableAttribute, overridableAttributes, OverridePlan, planOverrides } from './keys';
import {
  buildModel,
  findGroup,
  ManeuverGroupInfo,
  ManeuverGroupReferenceInfo,
  PARAMETER_ATTRIBUTES,
  listedName,
  ScenarioModel,
  ScenarioReferenceInfo,
} from './model';
import { Problem, ProblemCode, RelatedProblemLocation, Severity, uniqueProblems, ZERO_RANGE } from './problems';
import { displayRef, refId, Resolution, ScenarioStore, SourceError, SourceRef } from './sources';
import * as path from 'node:path';
import { CarryEdit, carryEdits, CarryPlan, planCarry } from './carry';
import { declareUtf8 } from './encoding';
import { analyzeDocument, CatalogLoader, DocumentSemantics, Evaluator, Finding, OUTPUT_CHECKS, problemOfFinding, runChecks, semanticModelOf, semanticProblems } from './semantics';
import { Simulator } from './profiles/simulators';
import { closestMatch, detectEol, indentationAt } from './text';
import { attribute, descendants, elementStartingAt, escapeAttributeValue, isWellFormed, parseXml, selfAndDescendants, XmlAttribute, XmlDocument, XmlElement } from './xml';
import { outputSchemaProblems, overrideValueProblems, schemaProblems } from './schema/problems';
import { SCHEMA_PROBLEM_CODES } from './schema/validate';
import { SchemaVersionSetting } from './schema/version';

const entityRefCache = new WeakMap<XmlElement, XmlElement[]>();

/** The elements of a group that carry an entityRef; computed once per parsed group. */
function entityRefElements(group: XmlElement): XmlElement[] {
  let found = entityRefCache.get(group);
  if (!found) {
    found = selfAndDescendants(group).filter((element) => element.name === 'EntityRef' || attribute(element, 'entityRef') !== undefined);
    entityRefCache.set(group, found);
  }
  return found;
}

/**
 * Where an element of a flattened text was written: the file and element it was copied from,
 * followed through every nested package. Elements outside imported groups map to the file itself.
 */
export function originOf(source: FlatSource, element: XmlElement): { source: FlatSource; element: XmlElement } {
  if (!source.model || !source.original || source.model === source.original) return { source, element };
  const insertion = source.insertions.find((candidate) => element.start >= candidate.start && element.end <= candidate.end);
  const addition = insertion ? undefined : source.additions.find((candidate) => element.start >= candidate.start && element.end <= candidate.end);
  const part = addition?.parts.find((candidate) => element.start === candidate.start && element.end === candidate.end);
  if (part) return originOf(part.source, part.element);
  if (!insertion) {
    // Outside imported groups the flattened text is the original text, shifted by each replaced region.
    const regions = new Map<number, { outStart: number; outEnd: number; inStart: number; inEnd: number }>();
    for (const candidate of source.additions) {
      regions.set(-1 - candidate.replacedStart, { outStart: candidate.start, outEnd: candidate.end, inStart: candidate.replacedStart, inEnd: candidate.replacedEnd });
    }
    for (const candidate of source.insertions) {
      const region = regions.get(candidate.replacedStart);
      if (region) region.outEnd = Math.max(region.outEnd, candidate.end);
      else regions.set(candidate.replacedStart, { outStart: candidate.start, outEnd: candidate.end, inStart: candidate.replacedStart, inEnd: candidate.replacedEnd });
    }
    let shift = 0;
    for (const region of regions.values()) {
      if (region.outEnd <= element.start) shift += region.inEnd - region.inStart - (region.outEnd - region.outStart);
    }
    const original = elementStartingAt(source.original.document.root, element.start + shift);
    return { source, element: original && original.name === element.name ? original : element };
  }
  const copied = copiedFrom(source, insertion, element);
  return copied ? originOf(copied.source, copied.element) : { source, element };
}

/** The element of the imported group (in the referenced file's flattened model) that `element` of an insertion copies. */
export function copiedFrom(source: FlatSource, insertion: Insertion, element: XmlElement): { source: FlatSource; element: XmlElement } | undefined {
  const copyRoot = source.model?.groups.find((group) => group.element.start === insertion.start)?.element;
  const sourceOfCopy = insertion.link.source;
  const targetGroup = insertion.group.target;
  if (!copyRoot || !sourceOfCopy || !targetGroup) return undefined;
  const index = selfAndDescendants(copyRoot).indexOf(element);
  const counterpart = selfAndDescendants(targetGroup.element)[index];
  return counterpart ? { source: sourceOfCopy, element: counterpart } : undefined;
}

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

/** Catalog problems, which the output check reports only for what flattening carried. */
const CATALOG_CODES: ReadonlySet<ProblemCode> = new Set<ProblemCode>(['catalog-directory', 'unknown-catalog', 'unknown-catalog-entry', 'unknown-assigned-parameter']);

/** A chain of files for a message: all of a short one, the ends of a long one. */
export function describeChain(chain: SourceRef[]): string {
  const names = chain.map((entry) => displayRef(entry));
  return (names.length <= 12 ? names : [...names.slice(0, 5), `... (${names.length - 10} more)`, ...names.slice(-5)]).join(' -> ');
}

/** Problems that the original tool ignored silently: `--force` writes the output despite them. */
export const OVERRIDE_PROBLEM_CODES: ReadonlySet<ProblemCode> = new Set<ProblemCode>([
  'unknown-key',
  'no-default',
  'unknown-parameter-attribute',
]);

export interface LinkedGroupReference {
  info: ManeuverGroupReferenceInfo;
  /** The group in the source (the flattened package for a `.mosc`) that the name selects. */
  target: ManeuverGroupInfo | undefined;
  overridable: OverridableAttribute[];
  plan: OverridePlan | undefined;
}

export interface LinkedReference {
  info: ScenarioReferenceInfo;
  resolution: Resolution;
  /** The referenced file, flattened when it is a package or itself holds references. */
  source: FlatSource | undefined;
  groups: LinkedGroupReference[];
  /** The files from this reference back to itself, when it closes a cycle. */
  cycle: SourceRef[] | undefined;
}

/** A group that flattening put into the output, and where it came from. */
export interface Insertion {
  reference: ManeuverGroupReferenceInfo;
  outerGroup: ManeuverGroupInfo;
  link: LinkedReference;
  group: LinkedGroupReference;
  /** Offsets of the copy in the flattened text. */
  start: number;
  end: number;
  /** Offsets of the outer group it replaced (with its siblings) in the original text. */
  replacedStart: number;
  replacedEnd: number;
}

/** One file read and, when it holds references, flattened (with `parameterAttributes` kept). */
export interface FlatSource {
  ref: SourceRef;
  /** The file as read; undefined when it could not be read. */
  original: ScenarioModel | undefined;
  links: LinkedReference[];
  /** The flattened text; undefined when an error here or below prevents flattening. */
  text: string | undefined;
  model: ScenarioModel | undefined;
  insertions: Insertion[];
  /** Problems found in this file itself. */
  problems: Problem[];
  /** Problems of this file and of every file it depends on. */
  allProblems: Problem[];
  /** Every file this one depends on, itself included. */
  dependencies: SourceRef[];
  /** True while the flattened text can be, but has not yet been, rendered (see Flattener.rendered). */
  renderable: boolean;
  /** The OpenSCENARIO semantics of the file as read (parameters, expressions, catalogs, names). */
  semantics: DocumentSemantics | undefined;
  /**
   * Where each catalog this file or the files it imports from reach lives: catalog name to the
   * catalog kind and the directory on disk (the first found wins), for carrying locations.
   */
  catalogIndex: Map<string, { kind: string; directory: string }>;
  /** What rendering carried from the sources into the root (SPEC 11), once rendered. */
  carried: CarryPlan | undefined;
  /** Text the carrying added to the main file's text, with the declarations it copied (offsets of the flattened text). */
  additions: Addition[];
}

/** A region of the flattened text that carrying added or replaced outside the imported groups. */
export interface Addition {
  start: number;
  end: number;
  replacedStart: number;
  replacedEnd: number;
  parts: { start: number; end: number; source: FlatSource; element: XmlElement }[];
}

/** How files are checked against the OpenSCENARIO schemas: by their FileHeader, pinned, or not at all. */
export interface SchemaOptions {
  version: SchemaVersionSetting | 'off';
}

export interface FlattenOptions {
  /** Write the output even when overrides could not be applied (the original's behaviour). */
  force?: boolean;
  /** Where the output will be written (carried catalog directories are made relative to its folder); beside the main file by default. */
  outputPath?: string;
}

export interface AnalysisResult {
  problems: Problem[];
  source: FlatSource;
}

export interface FlattenResult {
  /** The flattened scenario; undefined when errors prevent it. */
  text: string | undefined;
  problems: Problem[];
  source: FlatSource;
}

/** The location of a name inside the `parameterAttributes` of an element, in the file it was written in. */
export function declarationLocation(origin: { source: FlatSource; element: XmlElement }, name: string, message: string): RelatedProblemLocation {
  const model = origin.source.original ?? origin.source.model;
  const listed = listedName(origin.element, name);
  const start = listed?.start ?? origin.element.start;
  const end = listed?.end ?? origin.element.nameEnd;
  return { source: origin.source.ref, range: model ? model.document.lines.range(start, end) : ZERO_RANGE, message };
}

function problemAt(
  ref: SourceRef,
  document: XmlDocument,
  start: number,
  end: number,
  severity: Severity,
  code: ProblemCode,
  message: string,
  hint?: string,
): Problem {
  return { source: ref, range: document.lines.range(start, end), severity, code, message, hint };
}

function valueRange(attributeNode: XmlAttribute | undefined, element: XmlElement): [number, number] {
  return attributeNode ? [attributeNode.valueStart, attributeNode.valueEnd] : [element.start, element.nameEnd];
}

/** Moves a copied block from one indentation depth to another, line by line. */
export function reindent(block: string, fromIndent: string, toIndent: string, eol: string): string {
  const lines = block.split(/\r\n|\r|\n/);
  return lines
    .map((line, index) => {
      if (index === 0) return line;
      if (line.trim() === '') return '';
      if (line.startsWith(fromIndent)) return toIndent + line.slice(fromIndent.length);
      return toIndent + line.trimStart();
    })
    .join(eol);
}

interface TextEdit {
  start: number;
  end: number;
  text: string;
}

function applyEdits(text: string, edits: TextEdit[], from = 0, to = text.length): string {
  const sorted = [...edits].sort((a, b) => a.start - b.start);
  let out = '';
  let position = from;
  for (const edit of sorted) {
    out += text.slice(position, edit.start) + edit.text;
    position = edit.end;
  }
  return out + text.slice(position, to);
}

/** The spans that stripping removes: every `parameterAttributes` attribute, with the white space before it. */
export function parameterAttributeSpans(model: ScenarioModel): { start: number; end: number }[] {
  const text = model.document.text;
  return model.declarations.map(({ attribute: declaration }) => {
    let start = declaration.nameStart;
    while (start > 0 && /\s/.test(text[start - 1])) start--;
    return { start, end: declaration.valueEnd + 1 };
  });
}

/** Removes every `parameterAttributes` attribute, with the white space before it. */
export function stripParameterAttributes(model: ScenarioModel): string {
  return applyEdits(model.document.text, parameterAttributeSpans(model).map((span) => ({ ...span, text: '' })));
}

const ENTITY_REFERENCE = /<!--[\s\S]*?-->|<!\[CDATA\[[\s\S]*?\]\]>|&([A-Za-z_:][\w.:-]*);/g;
const PREDEFINED = new Set(['lt', 'gt', 'amp', 'quot', 'apos']);

/**
 * The DOCTYPE of a simple scenario stays behind when a group is copied, so references to its
 * internal entities are replaced by their escaped values in the copy (attribute values and text).
 */
function expandEntitiesInCopy(text: string, group: XmlElement, entities: ReadonlyMap<string, string>, edits: Map<number, TextEdit>): void {
  for (const element of selfAndDescendants(group)) {
    for (const attributeNode of element.attributes) {
      if (edits.has(attributeNode.valueStart) || !/&(?!(?:lt|gt|amp|quot|apos);|#)/.test(text.slice(attributeNode.valueStart, attributeNode.valueEnd))) continue;
      edits.set(attributeNode.valueStart, { start: attributeNode.valueStart, end: attributeNode.valueEnd, text: escapeAttributeValue(attributeNode.value, attributeNode.quote) });
    }
    if (element.selfClosing) continue;
    // Text runs: between the start tag, the children and the end tag.
    const endTagStart = element.closed ? text.lastIndexOf('</', element.end) : element.end;
    let from = element.startTagEnd;
    for (const child of [...element.children, undefined]) {
      const to = child ? child.start : Math.max(from, endTagStart);
      ENTITY_REFERENCE.lastIndex = 0;
      const run = text.slice(from, to);
      for (let match = ENTITY_REFERENCE.exec(run); match; match = ENTITY_REFERENCE.exec(run)) {
        const name = match[1];
        if (name === undefined || PREDEFINED.has(name)) continue;
        const value = entities.get(name);
        if (value === undefined) continue;
        const start = from + match.index;
        edits.set(start, { start, end: start + match[0].length, text: value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;') });
      }
      if (child) from = child.end;
    }
  }
}

/**
 * Flattens modular scenarios (SPEC 4 and 5). One instance caches every file it read and flattened,
 * so a simple scenario used by many references is read and reported once.
 */
export class Flattener {
  private readonly cache = new Map<string, Promise<FlatSource>>();
  /** Catalog files read for this flattener's files (a new flattener reads them again). */
  readonly catalogs: CatalogLoader;
  /** The folder the output is written to, against which carried catalog directories are made relative. */
  private outputDirectory: string | undefined;

  constructor(
    readonly store: ScenarioStore,
    /** The simulator whose known gaps each file read is checked for (core/profiles); `asam`: none. */
    readonly simulator: Simulator = 'asam',
    /** Off unless asked for: the CLI and the language server pass their setting (`auto` by default). */
    readonly schema: SchemaOptions = { version: 'off' },
  ) {
    this.catalogs = new CatalogLoader(store);
  }

  /** Every problem of `main` and of what it uses, without writing its flattened text (for an editor). */
  async analyze(main: SourceRef): Promise<AnalysisResult> {
    const source = await this.source(main, []);
    const schemaVersion = this.schema.version;
    const overrides = schemaVersion === 'off' ? [] : overrideValueProblems(source, { version: schemaVersion });
    return { problems: uniqueProblems([...source.allProblems, ...this.entityProblems(source), ...overrides]), source };
  }

  /** Flattens the scenario `main` (a `main.xosc` on disk or inside a package) into plain OpenSCENARIO. */
  async flatten(main: SourceRef, options: FlattenOptions = {}): Promise<FlattenResult> {
    this.outputDirectory = path.dirname(path.resolve(options.outputPath ?? main.disk));
    const analysis = await this.analyze(main);
    const source = this.rendered(analysis.source);
    // The output is checked strictly against the schema too; its problems are reported where the source wrote them.
    const schemaVersion = this.schema.version;
    const schemaOutput = schemaVersion !== 'off' && source.model && source.model !== source.original ? outputSchemaProblems(source, { version: schemaVersion }) : [];
    // Rendering the main file itself may find it too large.
    const problems = uniqueProblems([...analysis.problems, ...source.problems, ...(source.carried?.problems ?? []), ...(await this.checkOutput(source)), ...schemaOutput]);
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
      result.problems.push(problemAt(ref, document, problem.start, problem.end, problem.severity, 'xml', problem.message));
    }
    const schemaVersion = this.schema.version;
    if (schemaVersion !== 'off') result.problems.push(...schemaProblems(ref, document, { version: schemaVersion }));
    const model = buildModel(document);
    result.original = model;
    this.checkDeclarations(result, model);
    if (document.root) {
      const semantics = await analyzeDocument(ref, document, this.catalogs, model.references.length > 0);
      semantics.simulator = this.simulator;
      result.semantics = semantics;
      result.problems.push(...semanticProblems(semantics));
      for (const file of semantics.catalogs.files) if (!result.dependencies.some((known) => refId(known) === refId(file))) result.dependencies.push(file);
    }
    const wellFormed = isWellFormed(document);

    const childProblems: Problem[] = [];
    const dependencyIds = new Set([refId(ref)]);
    for (const reference of model.references) {
      const link = await this.link(reference, ref, model, stack, result);
      result.links.push(link);
      if (link.source) {
        childProblems.push(...link.source.allProblems);
        for (const dependency of link.source.dependencies) {
          const id = refId(dependency);
          if (!dependencyIds.has(id)) {
            dependencyIds.add(id);
            result.dependencies.push(dependency);
          }
        }
      }
    }
    result.allProblems = uniqueProblems([...result.problems, ...childProblems]);
    result.catalogIndex = catalogIndexOf(result);

    if (!wellFormed) return result;
    if (model.references.length === 0) {
      result.text = text;
      result.model = model;
      return result;
    }
    const blocked = result.allProblems.some((problem) => problem.severity === 'error' && !OVERRIDE_PROBLEM_CODES.has(problem.code) && !SCHEMA_PROBLEM_CODES.has(problem.code));
    result.renderable = !blocked;
    return result;
  }

  /**
   * Renders the flattened text and model of a source on first use: only the sources whose groups
   * are imported, and the outputs, need them, so an editor analysing one file never renders it.
   */
  rendered(source: FlatSource): FlatSource {
    if (source.renderable && source.original) {
      source.renderable = false;
      this.render(source, source.original.document.text, source.original);
    }
    return source;
  }

  private checkDeclarations(result: FlatSource, model: ScenarioModel): void {
    for (const declaration of model.declarations) {
      for (const name of declaration.names) {
        if (name.target) continue;
        const attributes = declaration.element.attributes.map((a) => a.name).filter((n) => n !== PARAMETER_ATTRIBUTES);
        const suggestion = closestMatch(name.name.split('.').pop() ?? name.name, attributes);
        const problem = problemAt(
          result.ref,
          model.document,
          name.start,
          name.end,
          'warning',
          'unknown-parameter-attribute',
          `'${name.name}' names no attribute of <${declaration.element.name}>, so no default value exists and no key can override it` +
            (attributes.length ? ` (its attributes: ${attributes.join(', ')})` : ''),
          suggestion ? `write '${suggestion}'` : `add ${name.name}="..." to <${declaration.element.name}> as its default`,
        );
        if (suggestion) problem.data = { suggestion };
        result.problems.push(problem);
      }
    }
  }

  /**
   * Warns on each later group of a name that a reference uses, where it is written: a duplicate
   * name nothing refers to (common in plain scenarios) harms nobody and is not reported.
   */
  private duplicateGroupProblems(source: FlatSource, named: ManeuverGroupInfo[]): Problem[] {
    const written = (group: ManeuverGroupInfo) => {
      const origin = originOf(source, group.element);
      const model = origin.source.original ?? origin.source.model;
      const [start, end] = valueRange(attribute(origin.element, 'name'), origin.element);
      return model ? { ref: origin.source.ref, document: model.document, start, end } : undefined;
    };
    const first = written(named[0]);
    const problems: Problem[] = [];
    for (const group of named.slice(1)) {
      const place = written(group);
      if (!place || !first) continue;
      const problem = problemAt(
        place.ref,
        place.document,
        place.start,
        place.end,
        'warning',
        'duplicate-group',
        `another ManeuverGroup is already named '${group.name}'; a reference to that name takes the first one`,
        'give each ManeuverGroup a unique name',
      );
      problem.related = [{ source: first.ref, range: first.document.lines.range(first.start, first.end), message: 'the first group of that name' }];
      problems.push(problem);
    }
    return problems;
  }

  private async link(
    reference: ScenarioReferenceInfo,
    from: SourceRef,
    model: ScenarioModel,
    stack: SourceRef[],
    result: FlatSource,
  ): Promise<LinkedReference> {
    const document = model.document;
    const report = (start: number, end: number, severity: Severity, code: ProblemCode, message: string, hint?: string) => {
      const problem = problemAt(from, document, start, end, severity, code, message, hint);
      result.problems.push(problem);
      return problem;
    };
    const [fileStart, fileEnd] = valueRange(reference.fileAttribute, reference.element);
    const link: LinkedReference = {
      info: reference,
      resolution: { kind: 'invalid', message: '' },
      source: undefined,
      groups: [],
      cycle: undefined,
    };
    if (!reference.outerGroup) {
      report(reference.element.start, reference.element.nameEnd, 'error', 'reference-outside-group', 'a ScenarioReference must stand directly inside a ManeuverGroup');
    } else if (!reference.outerGroup.actor) {
      const group = reference.outerGroup;
      const [start, end] = valueRange(group.nameAttribute, group.element);
      report(start, end, 'error', 'no-entity-ref', `ManeuverGroup '${group.name}' has no <Actors><EntityRef entityRef="..."/></Actors>, so the imported groups have no actor`, 'add an Actors element with the EntityRef of the entity that performs the imported groups');
    } else if (!attribute(reference.outerGroup.actor, 'entityRef')) {
      const actor = reference.outerGroup.actor;
      report(actor.start, actor.nameEnd, 'error', 'no-entity-ref', 'this EntityRef has no entityRef attribute', 'write entityRef="NAME" with the name of a ScenarioObject');
    }
    if (!reference.fileAttribute) {
      report(reference.element.start, reference.element.nameEnd, 'error', 'missing-attribute', 'ScenarioReference has no scenarioFileName attribute', 'add scenarioFileName="NAME.xosc" or "NAME.mosc"');
      return link;
    }
    for (const groupReference of reference.groupReferences) {
      if (!groupReference.nameAttribute) report(groupReference.element.start, groupReference.element.nameEnd, 'error', 'missing-attribute', 'ManeuverGroupReference has no maneuverGroupName attribute');
      for (const parameter of groupReference.parameters) {
        if (!parameter.keyAttribute || !parameter.valueAttribute) {
          report(parameter.element.start, parameter.element.nameEnd, 'error', 'missing-attribute', `ParameterReference needs both key and value attributes`, 'write <ParameterReference key="Element.attribute" value="..."/>');
        }
      }
    }
    const resolution = await this.store.resolve(reference.fileName, from);
    link.resolution = resolution;
    if (resolution.kind === 'invalid') {
      report(fileStart, fileEnd, 'error', 'invalid-reference', resolution.message);
      return link;
    }
    if (resolution.kind === 'unreadable') {
      report(fileStart, fileEnd, 'error', 'bad-package', `cannot look up '${reference.fileName}': ${resolution.message}`, resolution.hint);
      return link;
    }
    if (resolution.kind === 'missing') {
      report(fileStart, fileEnd, 'error', 'missing-file', `cannot find '${reference.fileName}'; searched ${resolution.searched.join(', ')}`, resolution.hint);
      return link;
    }
    if (resolution.kind === 'package' && resolution.fallbackFrom) {
      const packageName = `${resolution.fallbackFrom.slice(0, -'.xosc'.length)}.mosc`;
      const problem = report(
        fileStart,
        fileEnd,
        'warning',
        'xosc-fallback',
        `'${resolution.fallbackFrom}' does not exist; the flattened package '${packageName}' is used in its place`,
        `write scenarioFileName="${packageName}"`,
      );
      problem.data = { replacement: packageName };
    }
    const target = resolution.kind === 'package' ? resolution.main : resolution.ref;
    const targetId = refId(target);
    const cycleStart = stack.findIndex((entry) => refId(entry) === targetId);
    if (cycleStart >= 0) {
      const cycle = [...stack.slice(cycleStart), target];
      link.cycle = cycle;
      report(fileStart, fileEnd, 'error', 'cycle', `reference cycle: ${cycle.map((entry) => displayRef(entry)).join(' -> ')}`, 'remove one reference of the cycle');
      return link;
    }
    if (stack.length >= this.store.limits.maxDepth) {
      report(
        fileStart,
        fileEnd,
        'error',
        'too-deep',
        `references nest deeper than ${this.store.limits.maxDepth} files: ${describeChain([...stack, target])}`,
        'flatten the inner packages first, or raise the bound with --max-depth',
      );
      return link;
    }
    const source = this.rendered(await this.source(target, stack));
    link.source = source;
    // Schema problems do not stop flattening: they are reported in their own file and checked again in the output.
    const sourceErrors = source.allProblems.filter((problem) => problem.severity === 'error' && !OVERRIDE_PROBLEM_CODES.has(problem.code) && !SCHEMA_PROBLEM_CODES.has(problem.code));
    if (sourceErrors.length > 0) {
      const problem = report(
        fileStart,
        fileEnd,
        'error',
        'source-errors',
        `'${reference.fileName}' has ${sourceErrors.length} error${sourceErrors.length === 1 ? '' : 's'}: ${sourceErrors[0].message}`,
      );
      problem.related = sourceErrors.slice(0, 20).map((item) => ({ source: item.source, range: item.range, message: item.message }));
    }
    const sourceModel = source.model;
    for (const groupReference of reference.groupReferences) {
      const linked: LinkedGroupReference = { info: groupReference, target: undefined, overridable: [], plan: undefined };
      link.groups.push(linked);
      if (!sourceModel || !groupReference.nameAttribute) continue;
      const [nameStart, nameEnd] = valueRange(groupReference.nameAttribute, groupReference.element);
      const targetGroup = findGroup(sourceModel, groupReference.name);
      if (!targetGroup) {
        const names = [...new Set(sourceModel.groups.map((group) => group.name))];
        const suggestion = closestMatch(groupReference.name, names);
        const problem = report(
          nameStart,
          nameEnd,
          'error',
          'unknown-group',
          `'${reference.fileName}' has no ManeuverGroup named '${groupReference.name}'` +
            (names.length ? `; it has: ${names.join(', ')}` : '; it has no ManeuverGroup'),
          suggestion ? `did you mean '${suggestion}'?` : undefined,
        );
        problem.data = { ...(suggestion ? { suggestion } : {}), groups: names };
        continue;
      }
      linked.target = targetGroup;
      const named = sourceModel.groups.filter((group) => group.name === groupReference.name);
      if (named.length > 1) {
        report(nameStart, nameEnd, 'warning', 'ambiguous-group', `'${reference.fileName}' has more than one ManeuverGroup named '${groupReference.name}'; the first one is used`);
        result.problems.push(...this.duplicateGroupProblems(source, named));
      }
      linked.overridable = overridableAttributes(sourceModel, targetGroup);
      const plan = planOverrides(linked.overridable, groupReference.parameters.filter((p) => p.keyAttribute));
      linked.plan = plan;
      this.checkMixedDefaults(plan, source, report);
      for (const unknown of plan.unknown) {
        const [start, end] = valueRange(unknown.parameter.keyAttribute, unknown.parameter.element);
        const listedVerbatim = linked.overridable.find((candidate) => candidate.attributeName === unknown.parameter.key);
        const verbatimOrigin = listedVerbatim ? originOf(source, listedVerbatim.element) : undefined;
        const hint = listedVerbatim
          ? `<${listedVerbatim.element.name}> in ${displayRef((verbatimOrigin as { source: FlatSource }).source.ref)} lists '${listedVerbatim.attributeName}', which names no attribute; list '${listedVerbatim.attributeName.split('.').pop()}' there instead`
          : unknown.suggestion
            ? `did you mean '${unknown.suggestion}'?`
            : 'list the attribute in parameterAttributes of its element in the simple scenario';
        const problem = report(
          start,
          end,
          'error',
          'unknown-key',
          `key '${unknown.parameter.key}' matches no attribute listed in a parameterAttributes of group '${groupReference.name}'`,
          hint,
        );
        if (listedVerbatim && verbatimOrigin) {
          problem.related = [declarationLocation(verbatimOrigin, listedVerbatim.attributeName, 'listed here as a whole key instead of an attribute name')];
          // The mistake lives in the simple scenario: a fix at this use site rewrites the listed name there.
          problem.data = { relatedReplacement: listedVerbatim.attributeName.split('.').pop() ?? listedVerbatim.attributeName };
        } else if (unknown.suggestion) {
          problem.data = { suggestion: unknown.suggestion };
        }
      }
      for (const { parameter, target: attributeTarget } of plan.withoutDefault) {
        const [start, end] = valueRange(parameter.keyAttribute, parameter.element);
        const problem = report(
          start,
          end,
          'error',
          'no-default',
          `no default value: <${attributeTarget.element.name}> lists '${attributeTarget.attributeName}' in parameterAttributes but has no such attribute`,
          `add ${attributeTarget.attributeName}="..." to <${attributeTarget.element.name}> in ${displayRef(originOf(source, attributeTarget.element).source.ref)}`,
        );
        problem.related = [declarationLocation(originOf(source, attributeTarget.element), attributeTarget.attributeName, 'listed here without a default value')];
      }
    }
    return link;
  }

  /** A key that sets several attributes whose defaults differ probably sets one it was not written for. */
  private checkMixedDefaults(plan: OverridePlan, source: FlatSource, report: (start: number, end: number, severity: Severity, code: ProblemCode, message: string, hint?: string) => Problem): void {
    for (const match of plan.matches) {
      const targets = match.targets.filter((target) => target.defaultValue !== undefined);
      if (new Set(targets.map((target) => target.defaultValue)).size < 2) continue;
      const [start, end] = valueRange(match.parameter.keyAttribute, match.parameter.element);
      const counts = new Map<string, number>();
      for (const target of targets) counts.set(target.defaultValue as string, (counts.get(target.defaultValue as string) ?? 0) + 1);
      const listed = [...counts].map(([value, count]) => `'${value}' (${count}×)`);
      const problem = report(
        start,
        end,
        'warning',
        'key-mixed-defaults',
        `key '${match.parameter.key}' sets ${targets.length} attributes whose defaults differ: ${listed.join(', ')}; all of them get '${match.parameter.value}'`,
        'write a longer key that reaches only the attributes you mean, or list the attribute in parameterAttributes only where it should be overridden',
      );
      problem.related = targets.map((target) => declarationLocation(originOf(source, target.element), target.attributeName, `'${target.attributeName}' with default '${target.defaultValue}'`));
    }
  }

  /** Writes the flattened text: each outer group replaced in place by its imported copies. */
  private render(result: FlatSource, text: string, model: ScenarioModel): void {
    const eol = detectEol(text);
    type Copy = { text: string; link: LinkedReference; linked: LinkedGroupReference };
    const replacements: { group: ManeuverGroupInfo; start: number; end: number; copies: Copy[] }[] = [];
    // Counted copy by copy, before the text is joined: a group imported twice at each of 20 levels must not fill memory.
    let projected = text.length;
    for (const group of model.groups) {
      if (group.references.length === 0) continue;
      projected -= group.element.end - group.element.start;
      const actorEntity = group.actor ? attribute(group.actor, 'entityRef')?.value : undefined;
      const targetIndent = indentationAt(text, group.element.start);
      const copies: Copy[] = [];
      for (const reference of group.references) {
        const link = result.links.find((candidate) => candidate.info === reference);
        if (!link?.source?.model || link.source.text === undefined) return;
        for (const linked of link.groups) {
          if (!linked.target || !linked.plan) return;
          const copy = this.copyGroup(link.source.text, link.source.model, linked, group.name, actorEntity, targetIndent, eol);
          projected += copy.length + eol.length + targetIndent.length;
          if (projected > this.store.limits.maxFlattenedChars) {
            this.reportTooLarge(result, model, link, projected);
            return;
          }
          copies.push({ text: copy, link, linked });
        }
      }
      replacements.push({ group, start: group.element.start, end: group.element.end, copies });
    }
    const write = (edits: CarryEdit[]): { out: string; insertions: Insertion[]; additions: Addition[] } => {
      const insertions: Insertion[] = [];
      const additions: Addition[] = [];
      // Carried text lands in the root before the Storyboard, so it never overlaps a replaced group.
      const regions = [
        ...edits.map((edit) => ({ start: edit.start, end: edit.end, edit, replacement: undefined })),
        ...replacements.map((replacement) => ({ start: replacement.start, end: replacement.end, edit: undefined, replacement })),
      ].sort((a, b) => a.start - b.start);
      let out = '';
      let position = 0;
      for (const region of regions) {
        out += text.slice(position, region.start);
        if (region.edit) {
          const start = out.length;
          out += region.edit.text;
          additions.push({
            start,
            end: out.length,
            replacedStart: region.edit.start,
            replacedEnd: region.edit.end,
            parts: region.edit.parts.map((part) => ({ ...part, start: start + part.start, end: start + part.end })),
          });
          position = region.end;
          continue;
        }
        const replacement = region.replacement as (typeof replacements)[number];
        const indent = indentationAt(text, replacement.start);
        replacement.copies.forEach((copy, index) => {
          if (index > 0) out += eol + indent;
          const start = out.length;
          out += copy.text;
          insertions.push({
            reference: copy.linked.info,
            outerGroup: replacement.group,
            link: copy.link,
            group: copy.linked,
            start,
            end: out.length,
            replacedStart: replacement.start,
            replacedEnd: replacement.end,
          });
        });
        position = replacement.end;
      }
      return { out: out + text.slice(position), insertions, additions };
    };
    let written = write([]);
    const origin = (source: FlatSource, element: XmlElement) => {
      const found = originOf(source, element);
      const document = (found.source.original ?? found.source.model)?.document;
      const named = attribute(found.element, 'name');
      return document ? { source: found.source.ref, range: document.lines.range(named?.valueStart ?? found.element.start, named?.valueEnd ?? found.element.nameEnd), message: '' } : undefined;
    };
    // One parse of the first rendering serves the carry plan and, when nothing is carried, the model.
    const firstDocument = this.store.parseFlattened(result.ref, written.out);
    const plan = planCarry(result, firstDocument, written.insertions, origin);
    const edits = carryEdits(result, plan, eol, this.outputDirectory ?? path.dirname(result.ref.disk));
    if (edits.length > 0) written = write(edits);
    result.carried = plan;
    result.problems.push(...plan.problems);
    result.allProblems = uniqueProblems([...result.allProblems, ...plan.problems]);
    result.insertions.push(...written.insertions);
    result.additions = written.additions;
    result.text = written.out;
    // The first rendering is what re-parses incrementally from one edit to the next; a carrying one is parsed anew.
    result.model = buildModel(edits.length > 0 ? parseXml(written.out) : firstDocument);
  }

  /**
   * Checks the flattened output (SPEC 11.5): every `$name` declared, every catalog entry and
   * storyboard reference resolving to exactly one target. Problems are reported where the element
   * was written, through originOf.
   */
  private async checkOutput(source: FlatSource): Promise<Problem[]> {
    if (!source.model || !source.original || source.model === source.original) return [];
    const model = semanticModelOf(source.model.document);
    const evaluator = new Evaluator(model);
    const directory = this.outputDirectory ?? path.dirname(source.ref.disk);
    const catalogs = await this.catalogs.resolve({ disk: path.join(directory, 'flattened.xosc'), entries: [] }, model, evaluator);
    const findings = runChecks({ ref: source.ref, model, evaluator, catalogs, modular: false, simulator: this.simulator }, OUTPUT_CHECKS);
    // The main file's own catalog locations are written as they are, relative to it; its own check covers them.
    const carried = (element: XmlElement) =>
      [...source.insertions, ...source.additions].some((region) => element.start >= region.start && element.end <= region.end);
    return findings.filter((finding) => !CATALOG_CODES.has(finding.code) || carried(finding.element)).map((finding) => this.problemAtOrigin(source, finding));
  }

  /** A finding on the flattened text, placed where its element was written. */
  private problemAtOrigin(source: FlatSource, finding: Finding): Problem {
    const origin = originOf(source, finding.element);
    const document = (origin.source.original ?? origin.source.model)?.document;
    const originAttribute = finding.attribute ? attribute(origin.element, finding.attribute.name) : undefined;
    let start = origin.element.start;
    let end = origin.element.nameEnd;
    if (finding.attribute && originAttribute) {
      const delta = finding.start - finding.attribute.valueStart;
      start = Math.min(originAttribute.valueStart + delta, originAttribute.valueEnd);
      end = Math.min(start + (finding.end - finding.start), originAttribute.valueEnd);
      if (end <= start) [start, end] = [originAttribute.valueStart, originAttribute.valueEnd];
    }
    return problemOfFinding(finding, origin.source.ref, document ? document.lines.range(start, end) : ZERO_RANGE);
  }

  /** Reports a flattened result over the bound at the reference that crossed it, naming the chain of the largest imports. */
  private reportTooLarge(result: FlatSource, model: ScenarioModel, link: LinkedReference, projected: number): void {
    const chain: SourceRef[] = [result.ref];
    for (let current: LinkedReference | undefined = link; current?.source; ) {
      chain.push(current.source.ref);
      let largest: LinkedReference | undefined;
      for (const candidate of current.source.links) {
        if (candidate.source?.text !== undefined && (!largest || candidate.source.text.length > (largest.source?.text?.length ?? 0))) largest = candidate;
      }
      current = largest;
    }
    const [start, end] = valueRange(link.info.fileAttribute, link.info.element);
    const limit = this.store.limits.maxFlattenedChars;
    const problem = problemAt(
      result.ref,
      model.document,
      start,
      end,
      'error',
      'too-large',
      `the flattened ${displayRef(result.ref)} would exceed ${limit.toLocaleString('en-US')} characters (${projected.toLocaleString('en-US')} so far): groups imported through ${describeChain(chain)} multiply at each level`,
      'import fewer copies, or raise the bound with --max-output-size',
    );
    result.problems.push(problem);
    result.allProblems = uniqueProblems([...result.allProblems, problem]);
    result.text = undefined;
    result.model = undefined;
  }

  private copyGroup(
    sourceText: string,
    sourceModel: ScenarioModel,
    linked: LinkedGroupReference,
    outerName: string,
    actorEntity: string | undefined,
    targetIndent: string,
    eol: string,
  ): string {
    const target = linked.target as ManeuverGroupInfo;
    const edits = new Map<number, TextEdit>();
    const setAttribute = (element: XmlElement, name: string, value: string) => {
      const existing = attribute(element, name);
      if (existing) {
        edits.set(existing.valueStart, { start: existing.valueStart, end: existing.valueEnd, text: escapeAttributeValue(value, existing.quote) });
      } else {
        edits.set(element.nameEnd, { start: element.nameEnd, end: element.nameEnd, text: ` ${name}="${escapeAttributeValue(value)}"` });
      }
    };
    setAttribute(target.element, 'name', `${outerName}.${target.name}`);
    if (target.actor && actorEntity !== undefined) setAttribute(target.actor, 'entityRef', actorEntity);
    for (const [overridden, parameter] of (linked.plan as OverridePlan).applied) {
      setAttribute(overridden.element, overridden.attributeName, parameter.value);
    }
    const entities = sourceModel.document.entities;
    if (entities) expandEntitiesInCopy(sourceText, target.element, entities, edits);
    const copied = applyEdits(sourceText, [...edits.values()], target.element.start, target.element.end);
    return reindent(copied, indentationAt(sourceModel.document.text, target.element.start), targetIndent, eol);
  }

  /** Warns where an imported group names an entity the outermost main file does not declare. */
  private entityProblems(source: FlatSource): Problem[] {
    const original = source.original;
    if (!original) return [];
    // Names and references may be `$parameters`: each is read with the declarations of the file it is written in.
    const main = source.semantics?.evaluator;
    const valueIn = (evaluator: Evaluator | undefined, element: XmlElement, attributeNode: XmlAttribute | undefined) =>
      attributeNode ? (evaluator?.textOf(element, attributeNode) ?? attributeNode.value) : undefined;
    const declared = new Set(original.entities.map((entity) => valueIn(main, entity.element, entity.nameAttribute) ?? entity.name));
    const problems: Problem[] = [];
    for (const link of source.links) {
      const actor = link.info.outerGroup?.actor;
      const actorEntity = actor ? valueIn(main, actor, attribute(actor, 'entityRef')) : undefined;
      const sourceEvaluator = link.source?.model ? new Evaluator(semanticModelOf(link.source.model.document)) : undefined;
      for (const linked of link.groups) {
        if (!linked.target || !linked.plan) continue;
        // The entities the copy will name: overrides first, then the outer actor, then the source's own value.
        const overridden = new Map<XmlElement, string>();
        for (const [target, parameter] of linked.plan.applied) {
          if (target.attributeName === 'entityRef') overridden.set(target.element, valueIn(main, parameter.element, parameter.valueAttribute) ?? parameter.value);
        }
        const missing = new Set<string>();
        for (const element of entityRefElements(linked.target.element)) {
          const value =
            overridden.get(element) ??
            (element === linked.target.actor && actorEntity !== undefined ? actorEntity : valueIn(sourceEvaluator, element, attribute(element, 'entityRef')));
          if (value !== undefined && !declared.has(value)) missing.add(value);
        }
        for (const name of missing) {
          const [start, end] = valueRange(linked.info.nameAttribute, linked.info.element);
          problems.push({
            ...problemAt(
              source.ref,
              original.document,
              start,
              end,
              'warning',
              'undeclared-entity',
              `the imported group '${linked.info.name}' uses entity '${name}', which this file does not declare in <Entities>`,
              `declare a ScenarioObject named '${name}', or override the key that sets it (for example 'entityRef')`,
            ),
            data: { entity: name },
          });
        }
      }
    }
    return problems;
  }
}
