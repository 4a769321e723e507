import * as path from 'node:path';
import { undeclaredImportedEntityWording } from '../diagnostics/undeclaredEntity';
import { unknownParameterAttributeWording } from '../diagnostics/unknownParameterAttribute';
import { PARAMETER_ATTRIBUTES, ScenarioModel } from '../model';
import { Problem, ProblemCode, ZERO_RANGE } from '../problems';
import { CarlaRelease, Simulator } from '../profiles/simulators';
import {
  carlaSemantics,
  CatalogLoader,
  Evaluator,
  Finding,
  OUTPUT_CHECKS,
  problemOfFinding,
  readingOf,
  runChecks,
  SemanticModel,
  semanticModelOf,
} from '../semantics';
import { closestMatch } from '../text';
import { attribute, selfAndDescendants, XmlAttribute, XmlElement } from '../xml';
import { originOf } from './origin';
import { problemAt, valueRange } from './report';
import { FlatSource, LinkedReference } from './types';
import { coreMemo } from '../memos';

const entityRefCache = coreMemo<XmlElement, XmlElement[]>('entityReferences');

/** The elements of a group that carry an entityRef; computed once per parsed group. */
function entityRefElements(group: XmlElement): XmlElement[] {
  let found = entityRefCache.get(group);
  if (!found) {
    found = selfAndDescendants(group).filter((element) => element.name === 'EntityRef' || attribute(element, 'entityRef') !== undefined);
    entityRefCache.set(group, found);
  }
  return found;
}

/** Catalog problems, which the output check reports only for what flattening carried (and modularize's check takes as its input's own). */
export const CATALOG_CODES: ReadonlySet<ProblemCode> = new Set<ProblemCode>([
  'catalog-directory',
  'unknown-catalog',
  'unknown-catalog-entry',
  'unknown-assigned-parameter',
]);

/** Warns on each name in `parameterAttributes` that names no attribute of its element. */
export function checkDeclarations(result: FlatSource, model: ScenarioModel): void {
  for (const declaration of model.declarations) {
    for (const name of declaration.names) {
      if (name.target) continue;
      const attributes = declaration.element.attributes.map((a) => a.name).filter((n) => n !== PARAMETER_ATTRIBUTES);
      const suggestion = closestMatch(name.name.split('.').pop() ?? name.name, attributes);
      const problem = problemAt({
        source: result.ref,
        document: model.document,
        start: name.start,
        end: name.end,
        ...unknownParameterAttributeWording(name.name, declaration.element.name, attributes, suggestion),
      });
      if (suggestion) problem.data = { suggestion };
      result.problems.push(problem);
    }
  }
}

// An evaluator is a pure function of its model: one per imported file's model, not one per reference and edit.
const standardEvaluators = coreMemo<SemanticModel, Evaluator>('standardEvaluators');

function standardEvaluatorOf(model: SemanticModel): Evaluator {
  let evaluator = standardEvaluators.get(model);
  if (!evaluator) standardEvaluators.set(model, (evaluator = new Evaluator(model)));
  return evaluator;
}

/** What the check of imported entities reads of the main file for every reference: the entities it declares. */
export interface EntityContext {
  /** The evaluator of the main file's values (`$name` entities and overrides). */
  readonly main: Evaluator | undefined;
  /** The names of the entities the main file declares, evaluated. */
  readonly declared: ReadonlySet<string>;
}

/** A value as the file it is written in reads it; `parameters` learns when it read a parameter of that file. */
function valueIn(
  evaluator: Evaluator | undefined,
  element: XmlElement,
  attributeNode: XmlAttribute | undefined,
  parameters?: { read: boolean },
): string | undefined {
  if (!attributeNode) return undefined;
  if (parameters && evaluator?.model.siteOf.has(attributeNode)) parameters.read = true;
  return evaluator?.textOf(element, attributeNode) ?? attributeNode.value;
}

/** The entities the main file declares, for `referenceEntityProblems`; undefined when it was not read. */
export function entityContextOf(source: FlatSource): EntityContext | undefined {
  const original = source.original;
  if (!original) return undefined;
  // Names and references may be `$parameters`: each is read with the declarations of the file it is written in.
  const main = source.semantics?.evaluator;
  return { main, declared: new Set(original.entities.map((entity) => valueIn(main, entity.element, entity.nameAttribute) ?? entity.name)) };
}

/**
 * Where one reference's imported groups name an entity the main file does not declare; `readsParameters` when a value
 * it read is a parameter of the main file (its problems then depend on declarations outside the reference).
 */
export function referenceEntityProblems(
  source: FlatSource,
  link: LinkedReference,
  context: EntityContext,
): { problems: Problem[]; readsParameters: boolean } {
  const problems: Problem[] = [];
  const original = source.original;
  if (!original) return { problems, readsParameters: false };
  const { main, declared } = context;
  const parameters = { read: false };
  const actor = link.info.outerGroup?.actor;
  const actorEntity = actor ? valueIn(main, actor, attribute(actor, 'entityRef'), parameters) : undefined;
  const sourceEvaluator = link.source?.model ? standardEvaluatorOf(semanticModelOf(link.source.model.document)) : undefined;
  for (const linked of link.groups) {
    if (!linked.target || !linked.plan) continue;
    // The entities the copy will name: overrides first, then the outer actor, then the source's own value.
    const overridden = new Map<XmlElement, string>();
    for (const [target, parameter] of linked.plan.applied) {
      if (target.attributeName === 'entityRef')
        overridden.set(target.element, valueIn(main, parameter.element, parameter.valueAttribute, parameters) ?? parameter.value);
    }
    const missing = new Set<string>();
    for (const element of entityRefElements(linked.target.element)) {
      const value =
        overridden.get(element) ??
        (element === linked.target.actor && actorEntity !== undefined
          ? actorEntity
          : valueIn(sourceEvaluator, element, attribute(element, 'entityRef')));
      if (value !== undefined && !declared.has(value)) missing.add(value);
    }
    for (const name of missing) {
      const [start, end] = valueRange(linked.info.nameAttribute, linked.info.element);
      problems.push({
        ...problemAt({
          source: source.ref,
          document: original.document,
          start,
          end,
          ...undeclaredImportedEntityWording(linked.info.name, name),
        }),
        data: { entity: name },
      });
    }
  }
  return { problems, readsParameters: parameters.read };
}

/** What the output check needs of the flattener: its catalogs and the simulator it checks for. */
export interface OutputCheckContext {
  readonly catalogs: CatalogLoader;
  readonly simulator: Simulator;
  readonly carlaRelease: CarlaRelease;
}

/**
 * Checks the flattened output (SPEC 11.5): every `$name` declared, every catalog entry and
 * storyboard reference resolving to exactly one target. Problems are reported where the element
 * was written, through originOf. `mainFolder`: the folder the rendered text's paths are relative to (before rebasing).
 */
export async function checkOutput(context: OutputCheckContext, source: FlatSource, mainFolder: string): Promise<Problem[]> {
  if (!source.model || !source.original || source.model === source.original) return [];
  const model = semanticModelOf(source.model.document);
  const evaluator = new Evaluator(model, undefined, readingOf(context.simulator));
  const outputRef = { disk: path.join(mainFolder, 'flattened.xosc'), entries: [] };
  const catalogs = await context.catalogs.resolve(outputRef, model, evaluator);
  const carla = context.simulator === 'carla' ? await carlaSemantics(context.catalogs, outputRef, model, context.carlaRelease) : {};
  const findings = runChecks(
    { ref: source.ref, model, evaluator, catalogs, modular: false, simulator: context.simulator, ...carla },
    OUTPUT_CHECKS,
  );
  // The main file's own catalog locations are written as they are, relative to it; its own check covers them.
  const carried = (element: XmlElement) =>
    [...source.insertions, ...source.additions].some((region) => element.start >= region.start && element.end <= region.end);
  return findings
    .filter((finding) => !CATALOG_CODES.has(finding.code) || carried(finding.element))
    .map((finding) => problemAtOrigin(source, finding));
}

/** A finding on the flattened text, placed where its element was written. */
function problemAtOrigin(source: FlatSource, finding: Finding): Problem {
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
