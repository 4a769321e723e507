import { ManeuverGroupInfo, ScenarioModel } from '../model';
import { OverridePlan } from '../keys';
import { indentationAt } from '../text';
import { attribute, attributeValue, endTagStart, escapeAttributeValue, selfAndDescendants, XmlAttribute, XmlElement } from '../xml';
import { STORYBOARD_ELEMENT_NAMES, STORYBOARD_ELEMENT_TYPES } from '../semantics/storyboard';
import { LinkedGroupReference } from './types';
import { statedVersion, versionUpgrades } from './versionUpgrade';

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

export interface TextEdit {
  start: number;
  end: number;
  text: string;
}

export function applyEdits(text: string, edits: TextEdit[], from = 0, to = text.length): string {
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
  return applyEdits(
    model.document.text,
    parameterAttributeSpans(model).map((span) => ({ ...span, text: '' })),
  );
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
      if (
        edits.has(attributeNode.valueStart) ||
        !/&(?!(?:lt|gt|amp|quot|apos);|#)/.test(text.slice(attributeNode.valueStart, attributeNode.valueEnd))
      )
        continue;
      edits.set(attributeNode.valueStart, {
        start: attributeNode.valueStart,
        end: attributeNode.valueEnd,
        text: escapeAttributeValue(attributeNode.value, attributeNode.quote),
      });
    }
    if (element.selfClosing) continue;
    // Text runs: between the start tag, the children and the end tag.
    const textEnd = element.closed ? endTagStart(text, element) : element.end;
    let from = element.startTagEnd;
    for (const child of [...element.children, undefined]) {
      const to = child ? child.start : Math.max(from, textEnd);
      ENTITY_REFERENCE.lastIndex = 0;
      const run = text.slice(from, to);
      for (let match = ENTITY_REFERENCE.exec(run); match; match = ENTITY_REFERENCE.exec(run)) {
        const name = match[1];
        if (name === undefined || PREDEFINED.has(name)) continue;
        const value = entities.get(name);
        if (value === undefined) continue;
        const start = from + match.index;
        edits.set(start, {
          start,
          end: start + match[0].length,
          text: value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;'),
        });
      }
      if (child) from = child.end;
    }
  }
}

/** Where a copied group lands: the outer group it replaces and the text around it. */
export interface CopyPlace {
  outerName: string;
  /** The outer group's actor, which the copy's actor becomes. */
  actorEntity: string | undefined;
  indent: string;
  eol: string;
  /**
   * Storyboard elements the output holds more than once (`Event:Name`, see storyboardNameKey): a reference of the
   * copy to its own element of such a name would reach another copy's, so both are renamed in the copy.
   */
  sharedNames: ReadonlySet<string>;
  /** The OpenSCENARIO version the output states (1.3), for the attributes of an earlier source that it renames (versionUpgrade.ts). */
  version?: number;
}

/** How a storyboard element's kind and name are counted across the output: `Event:Name`. */
export const storyboardNameKey = (element: string, name: string): string => `${element}:${name}`;

/** The storyboard elements below a group (not the group itself, which a copy renames), as storyboardNameKey gives them. */
export function storyboardNamesBelow(group: XmlElement): string[] {
  return selfAndDescendants(group)
    .filter((element) => element !== group && STORYBOARD_ELEMENT_NAMES.has(element.name))
    .map((element) => storyboardNameKey(element.name, attributeValue(element, 'name') ?? ''));
}

/** The text of one imported group as the output holds it: renamed, its actor and overrides set, re-indented. */
export function copyGroup(
  sourceText: string,
  sourceModel: ScenarioModel,
  linked: LinkedGroupReference,
  { outerName, actorEntity, indent: targetIndent, eol, sharedNames, version }: CopyPlace,
): string {
  const target = linked.target as ManeuverGroupInfo;
  const edits = new Map<number, TextEdit>();
  const setAttribute = (element: XmlElement, name: string, value: string) => {
    const existing = attribute(element, name);
    if (existing) {
      edits.set(existing.valueStart, {
        start: existing.valueStart,
        end: existing.valueEnd,
        text: escapeAttributeValue(value, existing.quote),
      });
    } else {
      edits.set(element.nameEnd, { start: element.nameEnd, end: element.nameEnd, text: ` ${name}="${escapeAttributeValue(value)}"` });
    }
  };
  setAttribute(target.element, 'name', `${outerName}.${target.name}`);
  if (target.actor && actorEntity !== undefined) setAttribute(target.actor, 'entityRef', actorEntity);
  const overrides = new Map<XmlAttribute, string>();
  for (const [overridden, parameter] of (linked.plan as OverridePlan).applied) {
    setAttribute(overridden.element, overridden.attributeName, parameter.value);
    const written = attribute(overridden.element, overridden.attributeName);
    if (written) overrides.set(written, parameter.value);
  }
  const valueOf = (_element: XmlElement, written: XmlAttribute) => overrides.get(written) ?? written.value;
  for (const upgrade of versionUpgrades(target.element, statedVersion(sourceModel.document), version, valueOf)) {
    const { nameStart, valueStart, valueEnd, quote } = upgrade.attribute;
    edits.delete(valueStart);
    edits.set(nameStart, {
      start: nameStart,
      end: valueEnd,
      text: `${upgrade.name}=${quote}${escapeAttributeValue(upgrade.value, quote)}`,
    });
  }
  // Two copies of a group whose second event waits for its first by name (double-lane-change) would both wait for the
  // first copy's (esmini takes the first element of a name, ScenarioRunner one blackboard entry per name): each copy
  // names its own element, and the condition it, OUTER.NAME as the group itself is named.
  for (const condition of selfAndDescendants(target.element)) {
    if (condition.name !== 'StoryboardElementStateCondition') continue;
    const kind = STORYBOARD_ELEMENT_TYPES[attributeValue(condition, 'storyboardElementType') ?? ''];
    const written = attributeValue(condition, 'storyboardElementRef') ?? '';
    if (!kind || written.includes('::') || !sharedNames.has(storyboardNameKey(kind, written))) continue;
    const own = selfAndDescendants(target.element).filter(
      (element) => element !== target.element && element.name === kind && attributeValue(element, 'name') === written,
    );
    if (own.length !== 1) continue;
    setAttribute(own[0], 'name', `${outerName}.${written}`);
    setAttribute(condition, 'storyboardElementRef', `${outerName}.${written}`);
  }
  const entities = sourceModel.document.entities;
  if (entities) expandEntitiesInCopy(sourceText, target.element, entities, edits);
  const copied = applyEdits(sourceText, [...edits.values()], target.element.start, target.element.end);
  return reindent(copied, indentationAt(sourceModel.document.text, target.element.start), targetIndent, eol);
}
