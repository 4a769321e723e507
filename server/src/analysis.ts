import { FlatSource, LinkedGroupReference, LinkedReference, originOf } from './core/flatten';
import { KeyMatch, keyForms, keyMatches, OverridableAttribute, positionedKeyForms } from './core/keys';
import { findGroup, listedName, ManeuverGroupInfo } from './core/model';
import { Resolution, SourceRef } from './core/sources';
import { Range } from './core/text';
import { attribute, XmlElement } from './core/xml';
import { escapeMarkdown } from './markdown';
import { Workspace } from './workspace';

/** A place in a scenario file, before it becomes an LSP Location. */
export interface Place {
  ref: SourceRef;
  range: Range;
}

/** The range of offsets in the file a FlatSource was read from (its original text). */
export function placeIn(source: FlatSource, start: number, end: number): Place | undefined {
  const model = source.original ?? source.model;
  return model ? { ref: source.ref, range: model.document.lines.range(start, end) } : undefined;
}

/** Where an element of `source`'s flattened model was written: its name attribute value, or its tag. */
export function elementPlace(source: FlatSource, element: XmlElement, attributeName = 'name'): Place | undefined {
  const origin = originOf(source, element);
  const named = attribute(origin.element, attributeName);
  return named
    ? placeIn(origin.source, named.valueStart, named.valueEnd)
    : placeIn(origin.source, origin.element.start, origin.element.nameEnd);
}

/** Where `name` is listed in the parameterAttributes of an element (of the file the element was read from). */
export function listedPlace(source: FlatSource, element: XmlElement, name: string): Place | undefined {
  const listed = listedName(element, name);
  return listed ? placeIn(source, listed.start, listed.end) : placeIn(source, element.start, element.nameEnd);
}

/** Where an overridable attribute's default is written (the attribute itself, or its name in parameterAttributes). */
export function overridablePlace(source: FlatSource, target: OverridableAttribute): Place | undefined {
  const origin = originOf(source, target.element);
  const own = attribute(origin.element, target.attributeName);
  if (own) return placeIn(origin.source, own.nameStart, own.valueEnd + 1);
  return listedPlace(origin.source, origin.element, target.attributeName);
}

export function linkOf(source: FlatSource, referenceElement: XmlElement): LinkedReference | undefined {
  return source.links.find((link) => link.info.element === referenceElement);
}

export function groupLinkOf(link: LinkedReference, groupReferenceElement: XmlElement): LinkedGroupReference | undefined {
  return link.groups.find((group) => group.info.element === groupReferenceElement);
}

/** The attributes a key sets: those it matches that no more specific key of the same group reference takes. */
export function attributesSetBy(group: LinkedGroupReference, match: KeyMatch): OverridableAttribute[] {
  return match.targets.filter((target) => group.plan?.applied.get(target) === match.parameter);
}

export function resolvedTarget(resolution: Resolution): SourceRef | undefined {
  if (resolution.kind === 'scenario') return resolution.ref;
  if (resolution.kind === 'package') return resolution.main;
  return undefined;
}

/** The referenced file as flattening imports it (rendered), from a name written in `from` (used while typing). */
export async function sourceForFileName(workspace: Workspace, from: SourceRef, fileName: string): Promise<FlatSource | undefined> {
  if (!fileName.trim()) return undefined;
  const resolution = await workspace.store.resolve(fileName, from).catch(() => undefined);
  const target = resolution ? resolvedTarget(resolution) : undefined;
  if (!target) return undefined;
  // Its groups are read from the flattened model, which is rendered on first use.
  const flattener = workspace.flattener();
  return flattener.rendered(await flattener.source(target, []));
}

export function groupOf(source: FlatSource | undefined, name: string): ManeuverGroupInfo | undefined {
  return source?.model ? findGroup(source.model, name) : undefined;
}

/** One line per maneuver and event of a group: what the group does. */
export function describeGroup(group: ManeuverGroupInfo): string[] {
  const lines: string[] = [];
  const visit = (element: XmlElement, depth: number) => {
    for (const child of element.children) {
      if (child.name === 'Maneuver') {
        lines.push(`${'  '.repeat(depth)}- Maneuver **${escapeMarkdown(attribute(child, 'name')?.value ?? '?')}**`);
        visit(child, depth + 1);
      } else if (child.name === 'Event') {
        const actions = child.children
          .filter((action) => action.name === 'Action')
          .map((action) => `${escapeMarkdown(attribute(action, 'name')?.value ?? '?')} (${actionKind(action)})`);
        const start = child.children.find((candidate) => candidate.name === 'StartTrigger');
        const conditions = start ? [...conditionNames(start)] : [];
        lines.push(
          `${'  '.repeat(depth)}- Event **${escapeMarkdown(attribute(child, 'name')?.value ?? '?')}**: ${actions.join(', ') || 'no action'}` +
            (conditions.length ? ` when ${conditions.join(', ')}` : ''),
        );
      } else {
        visit(child, depth);
      }
    }
  };
  visit(group.element, 0);
  return lines;
}

/** Follows the first child whose name ends in `suffix` as deep as it goes: Action › PrivateAction › LongitudinalAction › SpeedAction. */
function deepestKind(element: XmlElement, suffix: string): string {
  let current = element;
  for (;;) {
    const next = current.children.find((child) => child.name.endsWith(suffix));
    if (!next) return current.name;
    current = next;
  }
}

function actionKind(action: XmlElement): string {
  return deepestKind(action, 'Action');
}

function* conditionNames(trigger: XmlElement): Generator<string> {
  for (const group of trigger.children) {
    for (const condition of group.children) {
      if (condition.name === 'Condition') yield deepestKind(condition, 'Condition');
    }
  }
}

/** The shortest positioned key that sets `target` and nothing else of `targets`, if there is one. */
function positionedChoice(target: OverridableAttribute, targets: OverridableAttribute[]): { target: OverridableAttribute; form: string }[] {
  const form = positionedKeyForms(target).find((candidate) => targets.every((other) => other === target || !keyMatches(candidate, other)));
  return form === undefined ? [] : [{ target, form }];
}

/** A key a main file can write: the attributes it sets together, and its forms from shortest to longest. */
export interface KeyChoice {
  targets: OverridableAttribute[];
  /** Every form reaching exactly these attributes, shortest first; `forms[0]` is the one to write. */
  forms: string[];
  /**
   * Where the choice sets several attributes (their paths are equal: two Events of one Maneuver), the key
   * that sets each one alone by position (`Event[2]....value`, the project's addition to SPEC 5), in the
   * targets' order; empty for a choice of one attribute.
   */
  positioned: { target: OverridableAttribute; form: string }[];
}

/**
 * The keys of a group. Attributes whose full paths are equal (two conditions of one kind in one
 * event) are set together by every plain key, so they form one choice instead of none; each one's
 * positioned key sets it alone.
 */
export function keyChoices(targets: OverridableAttribute[]): KeyChoice[] {
  const choices: KeyChoice[] = [];
  const placed = new Set<OverridableAttribute>();
  for (const target of targets) {
    if (placed.has(target)) continue;
    const forms = keyForms(target);
    const together = targets.filter((other) => keyMatches(forms[forms.length - 1], other));
    // A listed name no key can reach (such as the dotted `AbsoluteTargetSpeed.value`) has no choice; its declaration is reported instead.
    if (together.length === 0) continue;
    for (const member of together) placed.add(member);
    const exact = forms.filter((form) => {
      const reached = targets.filter((other) => keyMatches(form, other));
      return reached.length === together.length && reached.every((member) => together.includes(member));
    });
    const positioned = together.length > 1 ? together.flatMap((member) => positionedChoice(member, targets)) : [];
    choices.push({ targets: together, forms: exact, positioned });
  }
  return choices;
}
