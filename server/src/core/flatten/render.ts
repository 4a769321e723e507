import { buildModel, ManeuverGroupInfo, ScenarioModel, ScenarioReferenceInfo } from '../model';
import { RelatedProblemLocation, uniqueProblems } from '../problems';
import { ScenarioStore, SourceRef } from '../sources';
import { detectEol, indentationAt } from '../text';
import { attribute, parseXml, XmlElement } from '../xml';
import { carryEdits, planCarry } from './carry';
import { copyGroup, storyboardNameKey, storyboardNamesBelow } from './edits';
import { STORYBOARD_ELEMENT_NAMES } from '../semantics/storyboard';
import { originOf } from './origin';
import { describeChain, problemAt, valueRange } from './report';
import { Addition, CarryEdit, FlatSource, Insertion, LinkedGroupReference, LinkedReference } from './types';
import { tooLargeWording } from '../diagnostics/tooLarge';
import { statedVersion } from './versionUpgrade';

/** One imported group's text, ready to replace its outer group. */
interface Copy {
  text: string;
  link: LinkedReference;
  linked: LinkedGroupReference;
}

/** An outer group of the original text and the copies that take its place. */
interface Replacement {
  group: ManeuverGroupInfo;
  start: number;
  end: number;
  copies: Copy[];
}

interface Written {
  out: string;
  insertions: Insertion[];
  additions: Addition[];
}

/**
 * Writes the flattened text of `result` (read as `model`): each outer group replaced in place by its
 * imported copies, then what they need carried into the root, with catalog locations relative to
 * `sourceFolder` as the source's own paths are (flatten rebases them all onto the output's folder).
 * Leaves the text undefined when a copy is missing or the output grows too large.
 */
export function render(store: ScenarioStore, result: FlatSource, model: ScenarioModel, sourceFolder: string): void {
  const text = model.document.text;
  const eol = detectEol(text);
  const replacements = plannedReplacements(store, result, model, eol);
  if (!replacements) return;
  let written = write(text, eol, replacements, []);
  // One parse of the first rendering serves the carry plan and, when nothing is carried, the model.
  const firstDocument = store.parseFlattened(result.ref, written.out);
  const plan = planCarry(result, firstDocument, written.insertions, carryOrigin, store.workingDirectory);
  const edits = carryEdits(result, plan, eol, sourceFolder);
  if (edits.length > 0) written = write(text, eol, replacements, edits);
  result.carried = plan;
  result.problems.push(...plan.problems);
  result.allProblems = uniqueProblems([...result.allProblems, ...plan.problems]);
  result.insertions.push(...written.insertions);
  result.additions = written.additions;
  result.text = written.out;
  // The first rendering is what re-parses incrementally from one edit to the next; a carrying one is parsed anew.
  result.model = buildModel(edits.length > 0 ? parseXml(written.out) : firstDocument);
}

type LinkOfReference = (reference: ScenarioReferenceInfo) => LinkedReference | undefined;

/** The first link made for each reference, found in one lookup: a main with 400 references would otherwise search 400 links 400 times. */
function linkLookup(result: FlatSource): LinkOfReference {
  const byReference = new Map<ScenarioReferenceInfo, LinkedReference>();
  for (const link of result.links) if (!byReference.has(link.info)) byReference.set(link.info, link);
  return (reference) => byReference.get(reference);
}

/**
 * The storyboard elements (storyboardNameKey) the output holds more than once: the main's own, outside the groups
 * that copies replace, and those below each copy.
 */
function namesHeldTwice(model: ScenarioModel, linkOf: LinkOfReference): Set<string> {
  const replaced = new Set(model.groups.filter((group) => group.references.length > 0).map((group) => group.element));
  const names: string[] = [];
  const visit = (element: XmlElement) => {
    if (replaced.has(element)) return;
    if (STORYBOARD_ELEMENT_NAMES.has(element.name)) names.push(storyboardNameKey(element.name, attribute(element, 'name')?.value ?? ''));
    element.children.forEach(visit);
  };
  if (model.document.root) visit(model.document.root);
  for (const group of model.groups)
    for (const reference of group.references)
      for (const linked of linkOf(reference)?.groups ?? []) if (linked.target) names.push(...storyboardNamesBelow(linked.target.element));
  const seen = new Set<string>();
  const twice = new Set<string>();
  for (const name of names) (seen.has(name) ? twice : seen).add(name);
  return twice;
}

/**
 * The copies of every outer group that holds references; undefined when one cannot be made (a copy
 * missing, or the output over the bound, which is reported).
 */
function plannedReplacements(store: ScenarioStore, result: FlatSource, model: ScenarioModel, eol: string): Replacement[] | undefined {
  const text = model.document.text;
  const replacements: Replacement[] = [];
  const linkOf = linkLookup(result);
  const sharedNames = namesHeldTwice(model, linkOf);
  const version = statedVersion(model.document);
  // Counted copy by copy, before the text is joined: a group imported twice at each of 20 levels must not fill memory.
  let projected = text.length;
  for (const group of model.groups) {
    if (group.references.length === 0) continue;
    projected -= group.element.end - group.element.start;
    const actorEntity = group.actor ? attribute(group.actor, 'entityRef')?.value : undefined;
    const targetIndent = indentationAt(text, group.element.start);
    const copies: Copy[] = [];
    for (const reference of group.references) {
      const link = linkOf(reference);
      if (!link?.source?.model || link.source.text === undefined) return undefined;
      for (const linked of link.groups) {
        if (!linked.target || !linked.plan) return undefined;
        const copy = copyGroup(link.source.text, link.source.model, linked, {
          outerName: group.name,
          actorEntity,
          indent: targetIndent,
          eol,
          sharedNames,
          version,
        });
        projected += copy.length + eol.length + targetIndent.length;
        if (projected > store.limits.maxFlattenedChars) {
          reportTooLarge(store, result, model, link, projected);
          return undefined;
        }
        copies.push({ text: copy, link, linked });
      }
    }
    replacements.push({ group, start: group.element.start, end: group.element.end, copies });
  }
  return replacements;
}

/** The original text with the groups replaced by their copies and the carry edits applied, and where each landed. */
function write(text: string, eol: string, replacements: Replacement[], edits: CarryEdit[]): Written {
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
    const replacement = region.replacement as Replacement;
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
}

/** Where the carry plan reports an element of a source's flattened model: at its name where it was written. */
function carryOrigin(source: FlatSource, element: XmlElement): RelatedProblemLocation | undefined {
  const found = originOf(source, element);
  const document = (found.source.original ?? found.source.model)?.document;
  const named = attribute(found.element, 'name');
  return document
    ? {
        source: found.source.ref,
        range: document.lines.range(named?.valueStart ?? found.element.start, named?.valueEnd ?? found.element.nameEnd),
        message: '',
      }
    : undefined;
}

/** Reports a flattened result over the bound at the reference that crossed it, naming the chain of the largest imports. */
function reportTooLarge(store: ScenarioStore, result: FlatSource, model: ScenarioModel, link: LinkedReference, projected: number): void {
  const chain: SourceRef[] = [result.ref];
  for (let current: LinkedReference | undefined = link; current?.source;) {
    chain.push(current.source.ref);
    let largest: LinkedReference | undefined;
    for (const candidate of current.source.links) {
      if (candidate.source?.text !== undefined && (!largest || candidate.source.text.length > (largest.source?.text?.length ?? 0)))
        largest = candidate;
    }
    current = largest;
  }
  const [start, end] = valueRange(link.info.fileAttribute, link.info.element);
  const limit = store.limits.maxFlattenedChars;
  const problem = problemAt({
    source: result.ref,
    document: model.document,
    start,
    end,
    ...tooLargeWording(store.display(result.ref), limit, projected, describeChain(chain, store.workingDirectory)),
  });
  result.problems.push(problem);
  result.allProblems = uniqueProblems([...result.allProblems, problem]);
  result.text = undefined;
  result.model = undefined;
}
