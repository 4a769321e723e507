import * as path from 'node:path';
import type { CarriedDeclaration, CarriedLocation, CarryEdit, CarryPlan, FlatSource, Insertion, LinkedGroupReference } from './types';
import { problemData, RelatedProblemLocation } from '../problems';
import { Declaration, Evaluator, ParameterUse, SemanticModel, semanticModelOf, ValueResult } from '../semantics';
import { displayRef } from '../sources';
import { indentationAt } from '../text';
import { attribute, elementStartingAt, escapeAttributeValue, isWithin, selfAndDescendants, XmlDocument, XmlElement } from '../xml';
import { coreMemo } from '../memos';
import { ProblemWording } from '../diagnostics/definition';
import { catalogLocationConflictKey, catalogLocationConflictWording } from '../diagnostics/catalogLocationConflict';
import {
  declaredAroundGroupWording,
  firstCarriedKeptWording,
  keptDeclarationNote,
  mainDeclarationKeptWording,
  sourceDeclarationNote,
} from '../diagnostics/parameterConflict';

/**
 * What flattening carries from imported groups' sources into the output (SPEC 11): the parameter
 * declarations a copied group uses but that lie outside it, and the catalog locations its
 * CatalogReferences need. Computed on a first rendering of the output, then applied as text edits
 * to the main file's root (after its own declarations), so that the output keeps the main file's text.
 */

export type { CarriedDeclaration, CarriedLocation, CarryEdit, CarryPlan } from './types';

/** Whether two declarations give a parameter one value: the same text and type. */
export function sameValue(a: Declaration, b: Declaration): boolean {
  return a.value === b.value && (a.type ?? a.writtenType) === (b.type ?? b.writtenType);
}

/**
 * Decides what to carry. `first` is the output rendered without carrying (parsed), `insertions` the copies in
 * it; `origin` maps an element of a source's flattened model to where it was written; messages show files relative to `base`.
 */
export function planCarry(
  main: FlatSource,
  first: XmlDocument,
  insertions: Insertion[],
  origin: (source: FlatSource, element: XmlElement) => RelatedProblemLocation | undefined,
  base: string | undefined,
): CarryPlan {
  // Nothing reaches outside the copied groups: nothing to carry, and no model of the whole output to build.
  if (carryShortcut.enabled && !insertions.some(mayCarry)) return { declarations: [], locations: [], problems: [] };
  return planCarryOnOutput(main, first, insertions, origin, base);
}

/** Whether planCarry skips outputs whose copies reach nothing outside them (off only in the test that compares both ways). */
export const carryShortcut = { enabled: true };

/** Reads every copy in a model of the whole output. */
function planCarryOnOutput(
  main: FlatSource,
  first: XmlDocument,
  insertions: Insertion[],
  origin: (source: FlatSource, element: XmlElement) => RelatedProblemLocation | undefined,
  base: string | undefined,
): CarryPlan {
  const plan: CarryPlan = { declarations: [], locations: [], problems: [] };
  const mainSemantics = main.semantics;
  const mainModel = main.original;
  if (!mainSemantics || !mainModel || insertions.length === 0) return plan;
  // The output's model is cached with its parse: the output check reads the same one.
  const output = semanticModelOf(first);
  const carried = new Map<string, CarriedDeclaration>();
  const reported = new Set<string>();

  const conflict = (
    name: string,
    kept: RelatedProblemLocation,
    dropped: RelatedProblemLocation | undefined,
    wording: ProblemWording<'parameter-conflict'>,
  ) => {
    if (reported.has(name)) return;
    reported.add(name);
    plan.problems.push({ source: kept.source, range: kept.range, ...wording, related: dropped ? [dropped] : undefined });
  };

  const mainRoot = mainSemantics.model.root;
  /** The main file's root declaration of a name wins over a source's, with a warning when the values differ. */
  const keptByMain = (declaration: Declaration, source: FlatSource, group: string): boolean => {
    const mainDeclaration = mainRoot?.byName.get(declaration.name);
    if (!mainDeclaration) return false;
    if (!sameValue(mainDeclaration, declaration) && mainDeclaration.nameAttribute) {
      const dropped = origin(source, declaration.element);
      conflict(
        declaration.name,
        {
          source: main.ref,
          range: mainModel.document.lines.range(mainDeclaration.nameAttribute.valueStart, mainDeclaration.nameAttribute.valueEnd),
          message: '',
        },
        dropped && { ...dropped, message: sourceDeclarationNote(declaration.value) },
        mainDeclarationKeptWording(
          declaration.name,
          mainDeclaration.value,
          group,
          `${displayRef(dropped?.source ?? source.ref, base)}${dropped ? `:${dropped.range.start.line + 1}` : ''}`,
          declaration.value,
        ),
      );
    }
    return true;
  };

  const carry = (declaration: Declaration, source: FlatSource, model: SemanticModel, group: string) => {
    if (keptByMain(declaration, source, group)) return;
    const existing = carried.get(declaration.name);
    if (existing) {
      const dropped = origin(source, declaration.element);
      if (existing.declaration !== declaration && !sameValue(existing.declaration, declaration) && dropped) {
        const kept = origin(existing.source, existing.declaration.element);
        conflict(
          declaration.name,
          dropped,
          kept && { ...kept, message: keptDeclarationNote(existing.declaration.value) },
          firstCarriedKeptWording(declaration.name, existing.declaration.value, declaration.value),
        );
      }
      return;
    }
    const text = model.document.text.slice(declaration.element.start, declaration.element.end);
    carried.set(declaration.name, { name: declaration.name, declaration, source, text });
    // The declarations its value uses come along (they precede it in the source).
    for (const use of usesIn(model, declaration.element)) {
      if (use.declaration) carry(use.declaration, source, model, group);
    }
  };

  const firstCopy = Math.min(...insertions.map((insertion) => insertion.start));
  for (const insertion of insertions) {
    const source = insertion.link.source;
    const target = insertion.group.target;
    const copyRoot = elementStartingAt(output.document.root, insertion.start);
    if (!source?.model || !target || !copyRoot) continue;
    const sourceModel = semanticModelOf(source.model.document);
    const copied = selfAndDescendants(copyRoot);
    const originals = selfAndDescendants(target.element);
    if (copied.length !== originals.length) continue;
    const counterpart = new Map<XmlElement, XmlElement>();
    copied.forEach((element, index) => counterpart.set(element, originals[index]));
    for (const use of output.uses) {
      if (use.start < insertion.start || use.end > insertion.end) continue;
      const original = counterpart.get(use.element);
      const sourceUse = original
        ? usesIn(sourceModel, original).find((candidate) => candidate.attribute.name === use.attribute.name && candidate.name === use.name)
        : undefined;
      const declaration = sourceUse?.declaration;
      if (!declaration || isWithin(declaration.element, target.element)) continue;
      if (!use.declaration || use.declaration.scope === output.root) {
        carry(declaration, source, sourceModel, insertion.reference.name);
        continue;
      }
      // Declared by the main file around the outer group (its Story, say): that declaration is the one used.
      if (!sameValue(use.declaration, declaration) && use.declaration.nameAttribute) {
        const dropped = origin(source, declaration.element);
        // Before the first copy the first rendering is the main file's text; past it, the reference stands for the place.
        const name = use.declaration.nameAttribute;
        const here =
          name.valueEnd <= firstCopy
            ? { start: name.valueStart, end: name.valueEnd }
            : { start: insertion.reference.element.start, end: insertion.reference.element.nameEnd };
        conflict(
          use.name,
          { source: main.ref, range: mainModel.document.lines.range(here.start, here.end), message: '' },
          dropped && { ...dropped, message: sourceDeclarationNote(declaration.value) },
          declaredAroundGroupWording(insertion.reference.name, use.name, declaration.value, use.declaration.value),
        );
      }
    }
    planLocations(plan, main, source, output, insertion, counterpart);
  }
  // In each source's order, sources in the order they were first needed.
  const sourceOrder: FlatSource[] = [];
  for (const entry of carried.values()) if (!sourceOrder.includes(entry.source)) sourceOrder.push(entry.source);
  plan.declarations = [...carried.values()].sort(
    (a, b) => sourceOrder.indexOf(a.source) - sourceOrder.indexOf(b.source) || a.declaration.element.start - b.declaration.element.start,
  );
  return plan;
}

const reachesOutside = coreMemo<XmlElement, boolean>('reachesOutside');

/**
 * Whether a copied group can need anything carried: a use in the source's group of a declaration
 * outside it, or a CatalogReference. Neither means the plan has nothing to do for that copy.
 */
function mayCarry(insertion: Insertion): boolean {
  const source = insertion.link.source;
  const target = insertion.group.target;
  if (!source?.model || !target) return false;
  const known = reachesOutside.get(target.element);
  if (known !== undefined) return known;
  const model = semanticModelOf(source.model.document);
  const inside = (element: XmlElement) => isWithin(element, target.element);
  const reaches =
    model.uses.some((use) => inside(use.element) && use.declaration !== undefined && !isWithin(use.declaration.element, target.element)) ||
    model.catalogReferences.some((reference) => inside(reference.element));
  reachesOutside.set(target.element, reaches);
  return reaches;
}

const usesByElement = coreMemo<SemanticModel, Map<XmlElement, ParameterUse[]>>('parameterUses');

/** The uses written in one element's attributes. */
function usesIn(model: SemanticModel, element: XmlElement): ParameterUse[] {
  let index = usesByElement.get(model);
  if (!index) {
    index = new Map();
    for (const use of model.uses) {
      const list = index.get(use.element);
      if (list) list.push(use);
      else index.set(use.element, [use]);
    }
    usesByElement.set(model, index);
  }
  return index.get(element) ?? [];
}

/** The catalog locations an imported group's CatalogReferences need and the main file lacks. */
function planLocations(
  plan: CarryPlan,
  main: FlatSource,
  source: FlatSource,
  output: SemanticModel,
  insertion: Insertion,
  counterpart: Map<XmlElement, XmlElement>,
): void {
  const mainLocations = main.semantics?.catalogs.locations ?? [];
  const references = output.catalogReferences.filter(
    (reference) => reference.element.start >= insertion.start && reference.element.end <= insertion.end,
  );
  if (references.length === 0 || !source.model) return;
  const sourceEvaluator = new Evaluator(semanticModelOf(source.model.document));
  const needed: CarriedLocation[] = [];
  for (const reference of references) {
    // The catalog name as the source reads it (it may be one of its parameters).
    const original = counterpart.get(reference.element);
    const name = original ? sourceEvaluator.textOf(original, attribute(original, 'catalogName'))?.trim() : undefined;
    const place = name === undefined ? undefined : source.catalogIndex.get(name);
    if (place) needed.push({ kind: place.kind, directory: place.directory, source });
  }
  for (const need of needed) {
    const own = mainLocations.find((location) => location.location.kind === need.kind);
    if (own) {
      if (own.directories.some((directory) => directory.directory === need.directory)) continue;
      const key = catalogLocationConflictKey(need.kind);
      if (plan.problems.some((problem) => problemData(problem, 'catalog-location-conflict')?.key === key)) continue;
      const attr = own.location.pathAttribute;
      const model = main.original;
      if (!model) continue;
      plan.problems.push({
        source: main.ref,
        range: attr
          ? model.document.lines.range(attr.valueStart, attr.valueEnd)
          : model.document.lines.range(own.location.directory.start, own.location.directory.nameEnd),
        ...catalogLocationConflictWording(need.kind, need.directory, own.path),
      });
      continue;
    }
    if (!plan.locations.some((known) => known.kind === need.kind)) plan.locations.push(need);
  }
}

/** Re-indents a copied element (its first line stands at `from`) to `to`. */
function reindentBlock(block: string, from: string, to: string, eol: string): string {
  return block
    .split(/\r\n|\r|\n/)
    .map((line, index) => (index === 0 ? line : line.startsWith(from) ? to + line.slice(from.length) : to + line.trimStart()))
    .join(eol);
}

/**
 * The edits of the main file's text that add the carried declarations (after the root's own, in a
 * new root ParameterDeclarations when it has none) and catalog locations (paths relative to
 * `mainFolder`, as the main file's own are: rebase.ts moves them all onto the output's folder).
 */
export function carryEdits(main: FlatSource, plan: CarryPlan, eol: string, mainFolder: string): CarryEdit[] {
  const model = main.original;
  const root = model?.document.root;
  if (!model || !root || (plan.declarations.length === 0 && plan.locations.length === 0)) return [];
  const text = model.document.text;
  const child = (name: string) => root.children.find((candidate) => candidate.name === name);
  const rootIndent = indentationAt(text, root.start);
  const firstChild = root.children[0];
  const childIndent = firstChild ? indentationAt(text, firstChild.start) : rootIndent + '  ';
  const unit = childIndent.length > rootIndent.length ? childIndent.slice(rootIndent.length) : '  ';
  const edits: CarryEdit[] = [];
  const after = child('FileHeader');
  const anchor = after ? after.end : root.startTagEnd;

  if (plan.declarations.length > 0) {
    const declarations = child('ParameterDeclarations');
    const inner = declarations?.children[0] ? indentationAt(text, declarations.children[0].start) : childIndent + unit;
    const parts: CarryEdit['parts'] = [];
    let body = '';
    for (const entry of plan.declarations) {
      body += eol + inner;
      const start = body.length;
      const sourceText = entry.source.model?.document.text ?? '';
      body += reindentBlock(entry.text, indentationAt(sourceText, entry.declaration.element.start), inner, eol);
      parts.push({ start, end: body.length, source: entry.source, element: entry.declaration.element });
    }
    if (declarations && !declarations.selfClosing) {
      const at = declarations.children.length > 0 ? declarations.children[declarations.children.length - 1].end : declarations.startTagEnd;
      const suffix = declarations.children.length > 0 ? '' : eol + childIndent;
      edits.push({ start: at, end: at, text: body + suffix, parts });
    } else {
      const open = `<ParameterDeclarations>`;
      const whole = open + body + eol + childIndent + '</ParameterDeclarations>';
      const shifted = parts.map((part) => ({ ...part, start: part.start + open.length, end: part.end + open.length }));
      if (declarations) edits.push({ start: declarations.start, end: declarations.end, text: whole, parts: shifted });
      else {
        const prefix = eol + childIndent;
        edits.push({
          start: anchor,
          end: anchor,
          text: prefix + whole,
          parts: shifted.map((part) => ({ ...part, start: part.start + prefix.length, end: part.end + prefix.length })),
        });
      }
    }
  }

  if (plan.locations.length > 0) {
    const locations = child('CatalogLocations');
    const inner = locations?.children[0] ? indentationAt(text, locations.children[0].start) : childIndent + unit;
    let body = '';
    for (const location of plan.locations) {
      const relative = path.relative(mainFolder, location.directory).split(path.sep).join('/') || '.';
      body += `${eol}${inner}<${location.kind}>${eol}${inner}${unit}<Directory path="${escapeAttributeValue(relative)}"/>${eol}${inner}</${location.kind}>`;
    }
    if (locations && !locations.selfClosing) {
      const at = locations.children.length > 0 ? locations.children[locations.children.length - 1].end : locations.startTagEnd;
      edits.push({ start: at, end: at, text: body + (locations.children.length > 0 ? '' : eol + childIndent), parts: [] });
    } else {
      const whole = `<CatalogLocations>${body}${eol}${childIndent}</CatalogLocations>`;
      if (locations) edits.push({ start: locations.start, end: locations.end, text: whole, parts: [] });
      else {
        // Schema order: FileHeader, ParameterDeclarations, (VariableDeclarations, MonitorDeclarations), CatalogLocations, RoadNetwork.
        const before = child('RoadNetwork');
        const preceding = ['MonitorDeclarations', 'VariableDeclarations', 'ParameterDeclarations']
          .map(child)
          .find((candidate) => candidate !== undefined);
        if (preceding) edits.push({ start: preceding.end, end: preceding.end, text: eol + childIndent + whole, parts: [] });
        else if (before) edits.push({ start: before.start, end: before.start, text: whole + eol + childIndent, parts: [] });
        else edits.push({ start: anchor, end: anchor, text: eol + childIndent + whole, parts: [] });
      }
    }
  }
  return edits;
}

/** The declaration carried into `main`'s flattened output under a name, with the source it came from. */
export function carriedDeclaration(main: FlatSource, name: string): CarriedDeclaration | undefined {
  return main.carried?.declarations.find((entry) => entry.name === name);
}

/**
 * The value an attribute of an imported group takes in `main`'s flattened output, for each group
 * reference of `main` that imports the element: a ParameterReference override (evaluated in the
 * main file), or the attribute's own value read with the source's declarations, which is then either
 * the main file's root declaration of that name (it wins) or carried from the source (named relative to `base`).
 */
export function composedValues(
  main: FlatSource,
  element: XmlElement,
  attributeName: string,
  base?: string,
): { group: LinkedGroupReference; result: ValueResult }[] {
  const results: { group: LinkedGroupReference; result: ValueResult }[] = [];
  const mainEvaluator = main.semantics?.evaluator;
  for (const link of main.links) {
    const source = link.source;
    if (!source?.model) continue;
    for (const group of link.groups) {
      if (!group.target || !isWithin(element, group.target.element)) continue;
      const override = group.plan
        ? [...group.plan.applied].find(([target]) => target.element === element && target.attributeName === attributeName)?.[1]
        : undefined;
      if (override?.valueAttribute && mainEvaluator) {
        const value = mainEvaluator.attributeValue(override.element, override.valueAttribute);
        const provenance = { kind: 'override' as const, parameterReference: override.element, key: override.key };
        results.push({ group, result: { ...value, provenance } });
        continue;
      }
      const own = attribute(element, attributeName);
      if (!own) continue;
      const model = semanticModelOf(source.model.document);
      const value = new Evaluator(model).attributeValue(element, own);
      const declaration = value.provenance.kind === 'declaration' ? value.provenance.declaration : undefined;
      if (!declaration || isWithin(declaration.element, group.target.element)) {
        results.push({ group, result: value });
        continue;
      }
      const mainDeclaration = main.semantics?.model.root?.byName.get(declaration.name);
      if (mainDeclaration && mainEvaluator) {
        results.push({ group, result: mainEvaluator.declarationValue(mainDeclaration) });
        continue;
      }
      results.push({ group, result: { ...value, provenance: { kind: 'carried', declaration, from: displayRef(source.ref, base) } } });
    }
  }
  return results;
}
