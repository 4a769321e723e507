import { editDistance, ownString } from './text';
import { ManeuverGroupInfo, ParameterAttributeName, ParameterReferenceInfo, ScenarioModel } from './model';
import { XmlElement } from './xml';
import { coreMemo } from './memos';

/** An attribute of a group that a main file may override. */
export interface OverridableAttribute {
  element: XmlElement;
  /** The attribute's name, last part of every key that reaches it. */
  attributeName: string;
  declaration: ParameterAttributeName;
  /** Element names from the group element down to the element, both included. */
  path: string[];
  /** The default value, or undefined when the element lacks the attribute. */
  defaultValue: string | undefined;
}

export interface KeyMatch {
  parameter: ParameterReferenceInfo;
  targets: OverridableAttribute[];
}

export interface OverridePlan {
  /** For each overridable attribute, the parameter whose value applies (the most specific key). */
  applied: Map<OverridableAttribute, ParameterReferenceInfo>;
  /** For each parameter, the attributes its key matches. */
  matches: KeyMatch[];
  /** Parameters whose key matches no listed attribute, with the closest key that would. */
  unknown: { parameter: ParameterReferenceInfo; suggestion: string | undefined }[];
  /** Matched attributes that have no default value on their element. */
  withoutDefault: { parameter: ParameterReferenceInfo; target: OverridableAttribute }[];
}

function isWithin(element: XmlElement, ancestor: XmlElement): boolean {
  for (let current: XmlElement | undefined = element; current; current = current.parent) if (current === ancestor) return true;
  return false;
}

// Parse trees never change once built, so a group's list is computed once, however often it is imported.
const overridableCache = coreMemo<XmlElement, OverridableAttribute[]>('overridableAttributes');

/** Every attribute the group lists in a `parameterAttributes`, in document order. */
export function overridableAttributes(model: ScenarioModel, group: ManeuverGroupInfo): OverridableAttribute[] {
  const cached = overridableCache.get(group.element);
  if (cached) return cached;
  const result: OverridableAttribute[] = [];
  overridableCache.set(group.element, result);
  for (const declaration of model.declarations) {
    if (!isWithin(declaration.element, group.element)) continue;
    const path: string[] = [];
    for (let current: XmlElement | undefined = declaration.element; current; current = current.parent) {
      path.unshift(current.name);
      if (current === group.element) break;
    }
    for (const name of declaration.names) {
      result.push({
        element: declaration.element,
        attributeName: name.name,
        declaration: name,
        path,
        defaultValue: name.target?.value,
      });
    }
  }
  return result;
}

/** Whether `key` (a dotted path ending in an attribute name) reaches `target` (SPEC 5, and the project's `Element[n]`). */
export function keyMatches(key: string, target: OverridableAttribute): boolean {
  return partsMatch(key.split('.'), target);
}

/** A key segment `Event[2]`: the element name and, when given, its 1-based position among its parent's children of that name. */
const SEGMENT = /^([^[\]]+)(?:\[([1-9]\d*)\])?$/;

/** The 1-based position of `element` among its parent's children of the same name. */
function positionAmongNamesakes(element: XmlElement): number {
  const siblings = element.parent?.children ?? [element];
  let position = 0;
  for (const sibling of siblings) {
    if (sibling.name === element.name) position++;
    if (sibling === element) return position;
  }
  return 1;
}

/** keyMatches for a key already split at its dots (a key is matched against every attribute of a group). */
function partsMatch(parts: string[], target: OverridableAttribute): boolean {
  const last = parts.length - 1;
  if (parts[last] !== target.attributeName) return false;
  if (last > target.path.length) return false;
  const offset = target.path.length - last;
  let element: XmlElement | undefined = target.element;
  // Read upwards from the element, so each indexed segment is checked on the element it names.
  for (let i = last - 1; i >= 0; i--, element = element?.parent) {
    const segment = SEGMENT.exec(parts[i]);
    if (!segment || segment[1] !== target.path[offset + i]) return false;
    if (segment[2] !== undefined && (!element || positionAmongNamesakes(element) !== Number(segment[2]))) return false;
  }
  return true;
}

/** How specific a key is, for "the most specific key wins": its length, then how many of its segments give a position. */
function specificity(key: string): number {
  const parts = key.split('.');
  return parts.length * 1000 + parts.filter((part) => part.endsWith(']')).length;
}

/** Every key that reaches the attribute, shortest first: `attr`, `Element.attr`, `Parent.Element.attr`, ... */
export function keyForms(target: OverridableAttribute): string[] {
  const forms: string[] = [];
  for (let length = 0; length <= target.path.length; length++) {
    forms.push([...target.path.slice(target.path.length - length), target.attributeName].join('.'));
  }
  return forms;
}

/**
 * Keys that give positions (`Event[2].Action.name`), for attributes whose element paths are equal
 * (two Events of one Maneuver): shortest first, and among keys of one length those with one position,
 * then two (`Event[1].StartTrigger.ConditionGroup.Condition[2]....`), then every segment positioned.
 * The group element itself is never positioned.
 */
export function positionedKeyForms(target: OverridableAttribute): string[] {
  const chain: XmlElement[] = [];
  for (let element: XmlElement | undefined = target.element; chain.length < target.path.length && element; element = element.parent)
    chain.unshift(element);
  const positioned = (element: XmlElement) => `${element.name}[${positionAmongNamesakes(element)}]`;
  const forms: string[] = [];
  for (let length = 1; length <= chain.length; length++) {
    const suffix = chain.slice(chain.length - length);
    // The group element (chain[0]) is named plainly: the key is read from the group down.
    const indexable = suffix.map((element) => element !== chain[0]);
    const keyWith = (positions: number[]) =>
      [...suffix.map((element, j) => (positions.includes(j) ? positioned(element) : element.name)), target.attributeName].join('.');
    for (let i = suffix.length - 1; i >= 0; i--) if (indexable[i]) forms.push(keyWith([i]));
    for (let i = suffix.length - 1; i >= 0; i--)
      for (let j = i - 1; j >= 0; j--)
        if (indexable[i] && indexable[j] && indexable.filter(Boolean).length > 2) forms.push(keyWith([j, i]));
    if (indexable.filter(Boolean).length > 1)
      forms.push([...suffix.map((element, j) => (indexable[j] ? positioned(element) : element.name)), target.attributeName].join('.'));
  }
  return forms;
}

/**
 * The shortest key that reaches this attribute and no other attribute of the group: a plain key
 * (SPEC 5) where one does, else one that gives the position of the elements whose paths are equal.
 */
export function shortestUnambiguousKey(target: OverridableAttribute, all: OverridableAttribute[]): string {
  const alone = (form: string) => all.every((other) => other === target || !keyMatches(form, other));
  const forms = keyForms(target);
  return forms.find(alone) ?? positionedKeyForms(target).find(alone) ?? forms[forms.length - 1];
}

/** The edit distance of two names when it is no more than a typo (one edit per three characters, at least one). */
function nearlyEqual(a: string, b: string): number | undefined {
  const distance = editDistance(a.toLowerCase(), b.toLowerCase());
  return distance <= Math.max(1, Math.round(Math.max(a.length, b.length) / 3)) ? distance : undefined;
}

/**
 * The key a mistyped one most likely meant: an attribute of nearly the same name, on an element of
 * nearly the same name when the key names one, qualified as the key was (or more, where needed). Nothing
 * when no attribute is that close: a key of another element and attribute would mean something else.
 */
export function suggestKey(key: string, targets: OverridableAttribute[]): string | undefined {
  const parts = key.split('.');
  const attributeName = parts[parts.length - 1];
  const elementName = parts.length > 1 ? parts[parts.length - 2].replace(/\[\d*\]$/, '') : undefined;
  let best: { target: OverridableAttribute; distance: number } | undefined;
  for (const target of targets) {
    const forms = keyForms(target);
    if (!keyMatches(forms[forms.length - 1], target)) continue;
    const attributeDistance = nearlyEqual(attributeName, target.attributeName);
    const elementDistance = elementName === undefined ? 0 : nearlyEqual(elementName, target.element.name);
    if (attributeDistance === undefined || elementDistance === undefined) continue;
    const distance = attributeDistance + elementDistance;
    if (!best || distance < best.distance) best = { target, distance };
  }
  if (!best) return undefined;
  const meant = best.target;
  // As qualified as the key written (the writer chose that level), and never reaching another attribute.
  const unambiguous = keyForms(meant).filter((form) => targets.every((other) => other === meant || !keyMatches(form, other)));
  return (
    unambiguous.find((form) => form.split('.').length >= parts.length) ??
    unambiguous[unambiguous.length - 1] ??
    shortestUnambiguousKey(meant, targets)
  );
}

/** What one key reaches among a group's attributes: the same for every reference writing it. */
interface KeyReach {
  reached: OverridableAttribute[];
  /** The key a key reaching nothing most likely meant. */
  suggestion: string | undefined;
  specificity: number;
}

/** Above this many keys a group's memo starts again (keys typed one character at a time are each a new key). */
const MAX_REMEMBERED_KEYS = 512;

// A group's attributes and their parse tree never change, so what a key reaches is found once per key, not per reference and edit.
const keyReaches = coreMemo<readonly OverridableAttribute[], Map<string, KeyReach>>('keyReaches');

function reachOf(key: string, targets: OverridableAttribute[]): KeyReach {
  let known = keyReaches.get(targets);
  if (!known || known.size >= MAX_REMEMBERED_KEYS) keyReaches.set(targets, (known = new Map()));
  let reach = known.get(key);
  if (!reach) {
    const parts = key.split('.');
    const reached = targets.filter((target) => partsMatch(parts, target));
    reach = { reached, suggestion: reached.length === 0 ? suggestKey(key, targets) : undefined, specificity: specificity(key) };
    known.set(ownString(key), reach);
  }
  return reach;
}

/** Decides which parameter sets which attribute: the longest matching key wins (on a tie, the one giving more positions), then the last one written. */
export function planOverrides(targets: OverridableAttribute[], parameters: ParameterReferenceInfo[]): OverridePlan {
  const applied = new Map<OverridableAttribute, ParameterReferenceInfo>();
  const matches: KeyMatch[] = [];
  const unknown: OverridePlan['unknown'] = [];
  const withoutDefault: OverridePlan['withoutDefault'] = [];
  for (const parameter of parameters) {
    const { reached, suggestion, specificity: specific } = reachOf(parameter.key, targets);
    matches.push({ parameter, targets: reached });
    if (reached.length === 0) {
      unknown.push({ parameter, suggestion });
      continue;
    }
    for (const target of reached) {
      if (target.defaultValue === undefined) {
        withoutDefault.push({ parameter, target });
        continue;
      }
      const previous = applied.get(target);
      if (!previous || reachOf(previous.key, targets).specificity <= specific) applied.set(target, parameter);
    }
  }
  return { applied, matches, unknown, withoutDefault };
}
