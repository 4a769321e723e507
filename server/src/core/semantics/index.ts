/**
 * OpenSCENARIO semantics of one document, for the checks, the flattener and every editor feature.
 * Nothing here imports the editor; every feature queries this model instead of re-deriving it.
 *
 * Getting the model:
 * - `FlatSource.semantics` (core/flatten.ts) holds the DocumentSemantics of every file the flattener
 *   read (the editor's Workspace reads files through it, with unsaved text and packages); or
 * - `analyzeDocument(ref, document, new CatalogLoader(store), modular)` for any parsed document.
 *
 * Queries (offsets are document offsets; `semantics` is a DocumentSemantics):
 * - scope tree: `semantics.model.root` (Scope: element, parent, children, declarations, byName);
 *   `scopeAt(semantics, offset)` is the innermost scope at an offset.
 * - the `$name` at an offset and its declaration: `parameterUseAt` (ParameterUse, with `.declaration`);
 *   `declarationAt` (from a use or from the declaration's own name); all references of a
 *   declaration: `referencesOf(semantics, declaration)`. Rename must change exactly those uses and the
 *   declaration's `nameAttribute`: a same-named parameter of another scope is another Declaration.
 * - parameters in scope at an offset (completion after `$`): `parametersInScopeAt` (innermost first,
 *   shadowed ones left out, each with its evaluated value and type).
 * - the value of an attribute or `${...}` at an offset: `valueAt` -> { attribute, result } where
 *   `result` is a ValueResult: value, type and Provenance (`declaration`, or `assignment` for a catalog
 *   entry's parameter set by a CatalogReference: see `entryParameterValue`). Across a composition,
 *   core/flatten/carry.ts `composedValues(mainSource, element, attributeName, base)` gives the value an imported
 *   group's attribute takes in the main file's output, with Provenance `override` (the
 *   ParameterReference) or `carried` (the source declaration carried into the output), and
 *   `carriedDeclaration(mainSource, name)` what flattening carried under a name (after rendering;
 *   `FlatSource.carried` holds the whole plan).
 * - a CatalogReference's catalog and entry: `catalogReferenceAt` / `catalogEntryFor`
 *   (CatalogReferenceResolution: catalogs, entry with its file and element); the value an entry's
 *   parameter takes for one reference: `entryParameterValue`.
 * - problems: `semanticProblems(semantics)` runs every check of SEMANTIC_CHECKS (./checks.ts).
 */
import { Problem } from '../problems';
import { CarlaRelease, Simulator } from '../profiles/simulators';
import { SourceRef } from '../sources';
import { Range } from '../text';
import { elementAt, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { carlaFilesOf } from './carlaFiles';
import { assignmentsOf, CatalogLoader, CatalogReferenceResolution, CatalogResolution } from './catalogs';
import { Finding, runChecks, SemanticContext } from './checks';
import { Reading } from './evaluator';
import { elementsNamed } from './elementIndex';
import { roadSignalsOf } from './roadNetwork';
import { locateRoadFile } from './roadFiles';
import { Declaration, Evaluator, ParameterUse, Scope, SemanticModel, semanticModelOf, ValueResult, visibleDeclarations } from './model';

export * from './values';
export * from './expressionParser';
export * from './expressionEvaluation';
export * from './model';
export * from './catalogs';
export * from './checks';

/** Everything known about one document: its model, an evaluator and its catalogs. */
export type DocumentSemantics = SemanticContext;

/** Builds the semantics of a parsed document and resolves its catalogs. */
export async function analyzeDocument(
  ref: SourceRef,
  document: XmlDocument,
  loader: CatalogLoader,
  modular: boolean,
  simulator?: Simulator,
  carlaRelease?: CarlaRelease,
): Promise<DocumentSemantics> {
  const model = semanticModelOf(document);
  const evaluator = new Evaluator(model, undefined, readingOf(simulator));
  const catalogs: CatalogResolution = await loader.resolve(ref, model, evaluator);
  // A run hands esmini the scenario's catalog folders as --path too, where it finds a road by its file name.
  const catalogFolders = catalogs.locations.flatMap((location) =>
    location.directories.flatMap((directory) => (directory.packageRef ? [] : [directory.directory])),
  );
  const roadFile = await locateRoadFile(loader.store, ref, document, evaluator, catalogFolders);
  // The road's signals serve the signal rule alone, which reads them for a TrafficSignalStateAction: a scenario that
  // sets no signal's state does not parse its road (tens of ms for a town's, at every check and debug launch).
  const road = elementsNamed(model, 'TrafficSignalStateAction').length > 0 ? await roadSignalsOf(loader.store, roadFile) : undefined;
  const carla = simulator === 'carla' ? await carlaSemantics(loader, ref, model, carlaRelease) : {};
  return { ref, model, evaluator, catalogs, modular, simulator, ...carla, ...(roadFile ? { roadFile } : {}), ...(road ? { road } : {}) };
}

/** What the CARLA checks need beyond the document: the release, and the files ScenarioRunner reads beside it. */
export async function carlaSemantics(
  loader: CatalogLoader,
  ref: SourceRef,
  model: SemanticModel,
  carlaRelease: CarlaRelease | undefined,
): Promise<Pick<SemanticContext, 'carlaRelease' | 'carlaFiles'>> {
  const carlaFiles = await carlaFilesOf(loader.store, loader, ref, model);
  return { ...(carlaRelease ? { carlaRelease } : {}), ...(carlaFiles ? { carlaFiles } : {}) };
}

/** The reading values are computed in for a simulator (SPEC 12): esmini's own for esmini, else the standard's. */
export function readingOf(simulator: Simulator | undefined): Reading {
  return simulator === 'esmini' ? 'esmini' : 'standard';
}

/** A finding as a problem of `ref` at `range` (its own position, or where a flattened element came from). */
export function problemOfFinding(finding: Finding, ref: SourceRef, range: Range): Problem {
  const problem: Problem = { source: ref, range, severity: finding.severity, code: finding.code, message: finding.message };
  if (finding.hint) problem.hint = finding.hint;
  if (finding.related) problem.related = finding.related;
  if (finding.data) problem.data = finding.data;
  if (finding.subject) problem.subject = finding.subject;
  return problem;
}

/** Problems at the findings' own positions in the document. */
export function findingsToProblems(ref: SourceRef, document: XmlDocument, findings: Finding[]): Problem[] {
  return findings.map((finding) => problemOfFinding(finding, ref, document.lines.range(finding.start, finding.end)));
}

export function semanticProblems(semantics: DocumentSemantics): Problem[] {
  return findingsToProblems(semantics.ref, semantics.model.document, runChecks(semantics));
}

export function scopeAt(semantics: DocumentSemantics, offset: number): Scope | undefined {
  const element = elementAt(semantics.model.document, offset);
  return element ? semantics.model.scopeOf(element) : semantics.model.root;
}

/** The `$name` (or parameterRef name) whose text holds the offset (its end included, as a cursor after it). */
export function parameterUseAt(semantics: DocumentSemantics, offset: number): ParameterUse | undefined {
  return semantics.model.uses.find((use) => offset >= use.start && offset <= use.end);
}

/** The declaration named at an offset: through a use, or the `name` of a ParameterDeclaration itself. */
export function declarationAt(semantics: DocumentSemantics, offset: number): Declaration | undefined {
  const use = parameterUseAt(semantics, offset);
  if (use) return use.declaration;
  return semantics.model.declarations.find((declaration) => {
    const name = declaration.nameAttribute;
    return name !== undefined && offset >= name.valueStart && offset <= name.valueEnd;
  });
}

/** Every use of a declaration, in document order. */
export function referencesOf(semantics: DocumentSemantics, declaration: Declaration): ParameterUse[] {
  return semantics.model.usesOf.get(declaration) ?? [];
}

/** The parameters a `$` typed at the offset may name, innermost first, with their values. */
export function parametersInScopeAt(semantics: DocumentSemantics, offset: number): { declaration: Declaration; value: ValueResult }[] {
  const element = elementAt(semantics.model.document, offset);
  const scope = element ? semantics.model.scopeOf(element) : semantics.model.root;
  // Inside a declaration's value only the earlier declarations of its scope are visible.
  const within =
    element && element.name === 'ParameterDeclaration'
      ? semantics.model.declarations.find((candidate) => candidate.element === element)
      : undefined;
  return visibleDeclarations(scope, within)
    .filter((declaration) => declaration.kind === 'parameter')
    .map((declaration) => ({ declaration, value: semantics.evaluator.declarationValue(declaration) }));
}

/** The attribute value holding the offset, evaluated (a literal evaluates to itself with type string). */
export function valueAt(
  semantics: DocumentSemantics,
  offset: number,
): { element: XmlElement; attribute: XmlAttribute; result: ValueResult } | undefined {
  const element = elementAt(semantics.model.document, offset);
  const attr = element?.attributes.find((candidate) => offset >= candidate.valueStart && offset <= candidate.valueEnd);
  if (!element || !attr) return undefined;
  return { element, attribute: attr, result: semantics.evaluator.attributeValue(element, attr) };
}

export function catalogEntryFor(semantics: DocumentSemantics, catalogReference: XmlElement): CatalogReferenceResolution | undefined {
  return semantics.catalogs.references.find((resolution) => resolution.reference.element === catalogReference);
}

/** The CatalogReference whose start tag holds the offset (or one of whose assignments does). */
export function catalogReferenceAt(semantics: DocumentSemantics, offset: number): CatalogReferenceResolution | undefined {
  return semantics.catalogs.references.find((resolution) => {
    const element = resolution.reference.element;
    if (offset >= element.start && offset <= element.startTagEnd) return true;
    return resolution.reference.assignments.some((assignment) => offset >= assignment.element.start && offset <= assignment.element.end);
  });
}

/** The value a catalog entry's parameter takes when the entry is used by this reference (its assignment, else its default). */
export function entryParameterValue(
  semantics: DocumentSemantics,
  resolution: CatalogReferenceResolution,
  declaration: Declaration,
): ValueResult {
  const entryModel = resolution.entry?.file.model ?? semantics.model;
  return new Evaluator(entryModel, assignmentsOf(resolution.reference, semantics.evaluator), semantics.evaluator.reading).declarationValue(
    declaration,
  );
}
