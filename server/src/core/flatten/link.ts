import { ambiguousGroupWording } from '../diagnostics/ambiguousGroup';
import { cycleWording } from '../diagnostics/cycle';
import {
  DUPLICATE_GROUP_FIRST_NOTE,
  DUPLICATE_OUTER_GROUP_FIRST_NOTE,
  duplicateGroupWording,
  duplicateOuterGroupWording,
} from '../diagnostics/duplicateGroup';
import { keyMixedDefaultsNote, keyMixedDefaultsWording } from '../diagnostics/keyMixedDefaults';
import { noActorsWording, noEntityRefAttributeWording } from '../diagnostics/noEntityRef';
import { referenceOutsideGroupWording } from '../diagnostics/referenceOutsideGroup';
import { tooDeepWording } from '../diagnostics/tooDeep';
import { unreadablePackageWording } from '../diagnostics/badPackage';
import { invalidReferenceWording } from '../diagnostics/invalidReference';
import {
  incompleteParameterReferenceWording,
  missingGroupNameWording,
  missingScenarioFileNameWording,
} from '../diagnostics/missingAttribute';
import { missingFileWording } from '../diagnostics/missingFile';
import { sourceErrorsCause, sourceErrorsWording } from '../diagnostics/sourceErrors';
import { unknownGroupData, unknownGroupWording } from '../diagnostics/unknownGroup';
import { fallbackPackageName, xoscFallbackWording } from '../diagnostics/xoscFallback';
import { NO_DEFAULT_LISTED_NOTE, noDefaultWording } from '../diagnostics/noDefault';
import { UNKNOWN_KEY_LISTED_NOTE, unknownKeyData, UnknownKeyFacts, unknownKeyWording } from '../diagnostics/unknownKey';
import { OverridableAttribute, overridableAttributes, OverridePlan, planOverrides } from '../keys';
import { findGroup, ManeuverGroupInfo, ManeuverGroupReferenceInfo, ScenarioModel, ScenarioReferenceInfo } from '../model';
import { Problem } from '../problems';
import { displayRef, refId, ScenarioStore, SourceRef } from '../sources';
import { closestMatch } from '../text';
import { attribute, XmlElement } from '../xml';
import { SCHEMA_PROBLEM_CODES } from '../schema/validate';
import { declarationLocation, originOf } from './origin';
import { describeChain, problemAt, ProblemWords, valueRange } from './report';
import { concernsImporter, FlatSource, LinkedGroupReference, LinkedReference, OVERRIDE_PROBLEM_CODES } from './types';

/** What linking needs of the flattener: the store, and the (cached) reading and rendering of referenced files. */
export interface LinkContext {
  readonly store: ScenarioStore;
  source(ref: SourceRef, stack: SourceRef[]): Promise<FlatSource>;
  /** What `source` would give now, when it is already read; undefined when it would read (a flattener sharing no sources across edits). */
  knownSource?(ref: SourceRef, stack: SourceRef[]): FlatSource | undefined;
  rendered(source: FlatSource): FlatSource;
}

/** Reports a problem at offsets of the referencing file, as one of its own problems. */
type Report = (words: ProblemWords) => Problem;

/**
 * Follows one ScenarioReference of `result` (the file `from`, read as `model`): resolves and reads the
 * referenced file, selects its groups and plans their overrides, reporting every problem on the way.
 */
export async function link(
  context: LinkContext,
  reference: ScenarioReferenceInfo,
  from: SourceRef,
  model: ScenarioModel,
  stack: SourceRef[],
  result: FlatSource,
): Promise<LinkedReference> {
  const document = model.document;
  const report: Report = (words) => {
    const problem = problemAt({ source: from, document, ...words });
    result.problems.push(problem);
    return problem;
  };
  const link: LinkedReference = {
    info: reference,
    resolution: { kind: 'invalid', message: '' },
    source: undefined,
    groups: [],
    cycle: undefined,
  };
  checkReferenceShape(reference, report);
  if (!reference.fileAttribute) {
    report({
      start: reference.element.start,
      end: reference.element.nameEnd,
      ...missingScenarioFileNameWording(),
    });
    return link;
  }
  checkReferenceChildren(reference, report);
  const target = await resolveTarget(context, reference, from, stack, link, report);
  if (!target) return link;
  const source = context.rendered(await context.source(target, stack));
  link.source = source;
  reportSourceErrors(reference, source, report);
  for (const groupReference of reference.groupReferences) {
    link.groups.push(linkGroup(reference, groupReference, source, result, report, context.store.workingDirectory));
  }
  return link;
}

/** A reference must stand in a ManeuverGroup whose actor the imported groups take. */
function checkReferenceShape(reference: ScenarioReferenceInfo, report: Report): void {
  if (!reference.outerGroup) {
    report({ start: reference.element.start, end: reference.element.nameEnd, ...referenceOutsideGroupWording() });
  } else if (!reference.outerGroup.actor) {
    const group = reference.outerGroup;
    const [start, end] = valueRange(group.nameAttribute, group.element);
    report({ start, end, ...noActorsWording(group.name) });
  } else if (!attribute(reference.outerGroup.actor, 'entityRef')) {
    const actor = reference.outerGroup.actor;
    report({ start: actor.start, end: actor.nameEnd, ...noEntityRefAttributeWording() });
  }
}

/** Group and parameter references need their attributes. */
function checkReferenceChildren(reference: ScenarioReferenceInfo, report: Report): void {
  for (const groupReference of reference.groupReferences) {
    if (!groupReference.nameAttribute) {
      report({
        start: groupReference.element.start,
        end: groupReference.element.nameEnd,
        ...missingGroupNameWording(),
      });
    }
    for (const parameter of groupReference.parameters) {
      if (!parameter.keyAttribute || !parameter.valueAttribute) {
        report({
          start: parameter.element.start,
          end: parameter.element.nameEnd,
          ...incompleteParameterReferenceWording(),
        });
      }
    }
  }
}

/** The file a reference reads (a package's main file for a `.mosc`); undefined, reported, when it cannot be read here. */
async function resolveTarget(
  context: LinkContext,
  reference: ScenarioReferenceInfo,
  from: SourceRef,
  stack: SourceRef[],
  link: LinkedReference,
  report: Report,
): Promise<SourceRef | undefined> {
  const [start, end] = valueRange(reference.fileAttribute, reference.element);
  const resolution = await context.store.resolve(reference.fileName, from);
  link.resolution = resolution;
  if (resolution.kind === 'invalid') {
    report({ start, end, ...invalidReferenceWording(resolution.message) });
    return undefined;
  }
  if (resolution.kind === 'unreadable') {
    report({
      start,
      end,
      ...unreadablePackageWording(reference.fileName, resolution.message, resolution.hint),
    });
    return undefined;
  }
  if (resolution.kind === 'missing') {
    const { suggestion } = resolution;
    const problem = report({ start, end, ...missingFileWording(reference.fileName, resolution.searched, suggestion, resolution.hint) });
    if (suggestion) problem.data = { suggestion };
    return undefined;
  }
  if (resolution.kind === 'package' && resolution.fallbackFrom) {
    const packageName = fallbackPackageName(resolution.fallbackFrom);
    const problem = report({ start, end, ...xoscFallbackWording(resolution.fallbackFrom, packageName, 'used') });
    problem.data = { replacement: packageName };
  }
  const target = resolution.kind === 'package' ? resolution.main : resolution.ref;
  const targetId = refId(target);
  const cycleStart = stack.findIndex((entry) => refId(entry) === targetId);
  if (cycleStart >= 0) {
    const cycle = [...stack.slice(cycleStart), target];
    link.cycle = cycle;
    report({ start, end, ...cycleWording(cycle.map((entry) => context.store.display(entry))) });
    return undefined;
  }
  const maxDepth = context.store.limits.maxDepth;
  if (stack.length >= maxDepth) {
    report({ start, end, ...tooDeepWording(maxDepth, describeChain([...stack, target], context.store.workingDirectory)) });
    return undefined;
  }
  return target;
}

/**
 * Errors in the referenced file stop flattening; schema problems do not (they are reported in their own file and checked
 * again in the output), nor does what does not concern the importer (concernsImporter): a road file the source names but
 * no run of the output reads, a simulator's finding outside the imported groups.
 */
function reportSourceErrors(reference: ScenarioReferenceInfo, source: FlatSource, report: Report): void {
  const groupNames = reference.groupReferences.map((groupReference) => groupReference.name);
  const sourceErrors = source.allProblems.filter(
    (problem) =>
      problem.severity === 'error' &&
      concernsImporter(problem, source, groupNames) &&
      !OVERRIDE_PROBLEM_CODES.has(problem.code) &&
      !SCHEMA_PROBLEM_CODES.has(problem.code),
  );
  if (sourceErrors.length === 0) return;
  const [start, end] = valueRange(reference.fileAttribute, reference.element);
  const problem = report({ start, end, ...sourceErrorsWording(reference.fileName, sourceErrors) });
  problem.related = sourceErrors.slice(0, 20).map((item) => ({ source: item.source, range: item.range, message: item.message }));
  problem.cause = sourceErrorsCause(sourceErrors);
}

/** Selects the group a ManeuverGroupReference names in the referenced file and plans its overrides. */
function linkGroup(
  reference: ScenarioReferenceInfo,
  groupReference: ManeuverGroupReferenceInfo,
  source: FlatSource,
  result: FlatSource,
  report: Report,
  base: string | undefined,
): LinkedGroupReference {
  const linked: LinkedGroupReference = { info: groupReference, target: undefined, overridable: [], plan: undefined };
  const sourceModel = source.model;
  if (!sourceModel || !groupReference.nameAttribute) return linked;
  const [start, end] = valueRange(groupReference.nameAttribute, groupReference.element);
  const targetGroup = findGroup(sourceModel, groupReference.name);
  if (!targetGroup) {
    const names = [...new Set(sourceModel.groups.map((group) => group.name))];
    const suggestion = closestMatch(groupReference.name, names);
    const problem = report({ start, end, ...unknownGroupWording(reference.fileName, groupReference.name, names, suggestion) });
    problem.data = unknownGroupData(names, suggestion);
    return linked;
  }
  linked.target = targetGroup;
  const named = sourceModel.groups.filter((group) => group.name === groupReference.name);
  if (named.length > 1) {
    report({ start, end, ...ambiguousGroupWording(reference.fileName, groupReference.name) });
    result.problems.push(...duplicateGroupProblems(source, named));
  }
  linked.overridable = overridableAttributes(sourceModel, targetGroup);
  const plan = planOverrides(
    linked.overridable,
    groupReference.parameters.filter((p) => p.keyAttribute),
  );
  linked.plan = plan;
  checkMixedDefaults(plan, source, report);
  reportUnknownKeys(linked, plan, source, report, base);
  reportMissingDefaults(plan, source, report, base);
  return linked;
}

/**
 * Warns on each later group of a name that a reference uses, where it is written: a duplicate
 * name nothing refers to (common in plain scenarios) harms nobody and is not reported.
 */
function duplicateGroupProblems(source: FlatSource, named: ManeuverGroupInfo[]): Problem[] {
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
    const problem = problemAt({
      source: place.ref,
      document: place.document,
      start: place.start,
      end: place.end,
      ...duplicateGroupWording(group.name),
    });
    problem.related = [
      { source: first.ref, range: first.document.lines.range(first.start, first.end), message: DUPLICATE_GROUP_FIRST_NOTE },
    ];
    problems.push(problem);
  }
  return problems;
}

/**
 * Warns on each ManeuverGroup of an Act that repeats the name of an earlier one of that Act where either
 * imports groups (a group without ScenarioReference is left to duplicateNames, core/semantics/checks/names.ts).
 */
export function duplicateOuterGroupProblems(model: ScenarioModel, from: SourceRef): Problem[] {
  const problems: Problem[] = [];
  const acts = new Set(model.groups.map((group) => group.element.parent).filter((parent): parent is XmlElement => parent?.name === 'Act'));
  const imported = (group: ManeuverGroupInfo) =>
    group.references.flatMap((reference) => reference.groupReferences.map((inner) => inner.name));
  for (const act of acts) {
    const first = new Map<string, ManeuverGroupInfo>();
    for (const group of model.groups) {
      if (group.element.parent !== act || group.name === '') continue;
      const earlier = first.get(group.name);
      if (!earlier) {
        first.set(group.name, group);
        continue;
      }
      if (group.references.length === 0 && earlier.references.length === 0) continue;
      const earlierCopies = new Set(imported(earlier));
      const shared = [...new Set(imported(group).filter((inner) => earlierCopies.has(inner)))];
      const [start, end] = valueRange(group.nameAttribute, group.element);
      const [firstStart, firstEnd] = valueRange(earlier.nameAttribute, earlier.element);
      const problem = problemAt({
        source: from,
        document: model.document,
        start,
        end,
        ...duplicateOuterGroupWording(group.name, attribute(act, 'name')?.value ?? '', shared),
      });
      problem.related = [
        { source: from, range: model.document.lines.range(firstStart, firstEnd), message: DUPLICATE_OUTER_GROUP_FIRST_NOTE },
      ];
      problems.push(problem);
    }
  }
  return problems;
}

/** Whether two of the attributes have different defaults (asked for every key of every reference on each edit: no array or set made). */
function defaultsDiffer(targets: readonly OverridableAttribute[]): boolean {
  let first: string | undefined;
  for (const target of targets) {
    if (target.defaultValue === undefined) continue;
    if (first === undefined) first = target.defaultValue;
    else if (target.defaultValue !== first) return true;
  }
  return false;
}

/** A key that sets several attributes whose defaults differ probably sets one it was not written for. */
function checkMixedDefaults(plan: OverridePlan, source: FlatSource, report: Report): void {
  for (const match of plan.matches) {
    if (!defaultsDiffer(match.targets)) continue;
    const targets = match.targets.filter((target) => target.defaultValue !== undefined);
    const [start, end] = valueRange(match.parameter.keyAttribute, match.parameter.element);
    const counts = new Map<string, number>();
    for (const target of targets) counts.set(target.defaultValue as string, (counts.get(target.defaultValue as string) ?? 0) + 1);
    const problem = report({ start, end, ...keyMixedDefaultsWording(match.parameter.key, targets.length, counts, match.parameter.value) });
    problem.related = targets.map((target) =>
      declarationLocation(
        originOf(source, target.element),
        target.attributeName,
        keyMixedDefaultsNote(target.attributeName, target.defaultValue),
      ),
    );
  }
}

/** Keys that match no listed attribute, with the likely fix (a whole key listed in the simple scenario, or a near name). */
function reportUnknownKeys(
  linked: LinkedGroupReference,
  plan: OverridePlan,
  source: FlatSource,
  report: Report,
  base: string | undefined,
): void {
  for (const unknown of plan.unknown) {
    const [start, end] = valueRange(unknown.parameter.keyAttribute, unknown.parameter.element);
    const listedVerbatim = linked.overridable.find((candidate) => candidate.attributeName === unknown.parameter.key);
    const verbatimOrigin = listedVerbatim ? originOf(source, listedVerbatim.element) : undefined;
    const facts: UnknownKeyFacts = {
      key: unknown.parameter.key,
      group: linked.info.name,
      listedVerbatim:
        listedVerbatim && verbatimOrigin
          ? { element: listedVerbatim.element.name, name: listedVerbatim.attributeName, file: displayRef(verbatimOrigin.source.ref, base) }
          : undefined,
      suggestion: unknown.suggestion,
    };
    const problem = report({ start, end, ...unknownKeyWording(facts) });
    if (listedVerbatim && verbatimOrigin) {
      problem.related = [declarationLocation(verbatimOrigin, listedVerbatim.attributeName, UNKNOWN_KEY_LISTED_NOTE)];
    }
    const data = unknownKeyData(facts);
    if (data) problem.data = data;
  }
}

/** Keys that set an attribute listed in parameterAttributes but not written, so with no default. */
function reportMissingDefaults(plan: OverridePlan, source: FlatSource, report: Report, base: string | undefined): void {
  for (const { parameter, target: attributeTarget } of plan.withoutDefault) {
    const [start, end] = valueRange(parameter.keyAttribute, parameter.element);
    const origin = originOf(source, attributeTarget.element);
    const problem = report({
      start,
      end,
      ...noDefaultWording(attributeTarget.element.name, attributeTarget.attributeName, displayRef(origin.source.ref, base)),
    });
    problem.related = [declarationLocation(origin, attributeTarget.attributeName, NO_DEFAULT_LISTED_NOTE)];
  }
}
