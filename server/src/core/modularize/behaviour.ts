import { keyForms, keyMatches, overridableAttributes, OverridableAttribute, positionedKeyForms } from '../keys';
import { parseScenario } from '../model';
import { applyEdits, reindent, TextEdit } from '../flatten/edits';
import { indentationAt } from '../text';
import { attribute, escapeAttributeValue, selfAndDescendants } from '../xml';
import { copyName, parameterConflicts, readingCopy } from './parameterCopies';
import { GroupOccurrence, Slot } from './shape';
import { simpleScenarioText } from './simpleScenario';
import { Behaviour, Override, ParsedInput, RebasePaths, Use } from './types';

/** The name a ParameterDeclaration declares (a `$` before it is the lenient form check and flatten accept). */
const DECLARED_NAME = /<ParameterDeclaration\b[^>]*?\bname\s*=\s*["']\$?([^"']+)["']/g;

/** The most common value, the earliest written on a tie. */
function mostCommon(values: string[]): string {
  const counts = new Map<string, number>();
  for (const value of values) counts.set(value, (counts.get(value) ?? 0) + 1);
  let best = values[0];
  for (const value of values) if ((counts.get(value) as number) > (counts.get(best) as number)) best = value;
  return best;
}

/**
 * The name the group takes in the simple scenario. A flattened group is named `OUTER.INNER`, so
 * groups named `X.INNER` are reproduced by the outer name alone; any other name is set by a key.
 */
function innerName(names: string[]): string {
  const suffixes = names.filter((name) => /.\../.test(name)).map((name) => name.slice(name.lastIndexOf('.') + 1));
  return suffixes.length > 0 ? mostCommon(suffixes) : mostCommon(names);
}

export interface BehaviourPlan {
  behaviour?: Behaviour;
  /** Why the group stays inline, when it does. */
  reason?: string;
  /** Attributes (slot indices) that one key reaches together although their values differ: uses that agree on them may still share a behaviour. */
  conflict?: number[];
}

/** The text of the group as the simple scenario holds it: defaults written, overridable attributes listed. */
function simpleGroupText(
  representative: GroupOccurrence,
  slots: Slot[],
  targets: string[],
  listed: Set<number>,
  indent: string,
  eol: string,
): string {
  const text = representative.document.text;
  const edits: TextEdit[] = [];
  const listedByElement = new Map<number, string[]>();
  slots.forEach((slot, index) => {
    const element = representative.elements[slot.element];
    if (representative.values[index] !== targets[index]) {
      const written = attribute(element, slot.name);
      if (written)
        edits.push({ start: written.valueStart, end: written.valueEnd, text: escapeAttributeValue(targets[index], written.quote) });
    }
    if (listed.has(index)) listedByElement.set(slot.element, [...(listedByElement.get(slot.element) ?? []), slot.name]);
  });
  for (const [index, names] of listedByElement) {
    const element = representative.elements[index];
    edits.push({ start: element.nameEnd, end: element.nameEnd, text: ` parameterAttributes="${names.join(',')}"` });
  }
  const group = representative.group.element;
  const copied = applyEdits(text, edits, group.start, group.end);
  return reindent(copied, indentationAt(text, group.start), indent, eol);
}

/**
 * Plans one recurring group: its defaults (the most common value of each attribute), the attributes
 * a main must be able to set (those whose values differ between uses), the simple scenario that holds
 * it, and each use's overrides under the shortest unambiguous key (SPEC 5).
 */
export async function planBehaviour(
  shapeKey: string,
  slots: Slot[],
  occurrences: GroupOccurrence[],
  inputs: ParsedInput[],
  file: string,
  rebase: RebasePaths,
  /** Attributes (slot indices) listed whatever their values: an editor's *Extract to a simple scenario* lets the user choose. */
  chosen: ReadonlySet<number> = new Set(),
  /** The group's name in the simple scenario, where the one its uses suggest is taken in a shared file. */
  wantedGroupName?: string,
  /** Parameters the group reads through copies of its own, each use passing its own reading (their values differ between its scenarios). */
  copied: ReadonlySet<string> = new Set(),
): Promise<BehaviourPlan> {
  const representative = occurrences[0];
  const nameSlot = slots.findIndex((slot) => slot.element === 0 && slot.name === 'name');
  const actorSlot = slots.findIndex((slot) => slot.element === representative.actorElement && slot.name === 'entityRef');
  const groupName = wantedGroupName ?? innerName(occurrences.map((occurrence) => occurrence.values[nameSlot]));
  const defaults = slots.map((_, index) => mostCommon(occurrences.map((occurrence) => occurrence.values[index])));
  defaults[nameSlot] = groupName;
  const copies = new Map<string, string>();
  const taken = new Set(
    [...new Set(occurrences.map((occurrence) => inputs[occurrence.input].text))].flatMap((text) =>
      [...text.matchAll(DECLARED_NAME)].map((match) => match[1].toLowerCase()),
    ),
  );
  for (const name of [...copied].sort()) {
    const copy = copyName(name, groupName, taken);
    for (const index of slots.keys()) {
      const reading = readingCopy(defaults[index], name, copy);
      if (reading === defaults[index]) continue;
      // The reference sets the actor (SPEC 4.2), so it may read the copy; the group's name is no place for a parameter.
      if (index === nameSlot) return { reason: `its name reads '${name}', whose value differs between its scenarios` };
      defaults[index] = reading;
      copies.set(copy, name);
    }
    taken.add(copy.toLowerCase());
  }
  const outerNames = occurrences.map((occurrence) => {
    const name = occurrence.values[nameSlot];
    return name.endsWith(`.${groupName}`) && name.length > groupName.length + 1 ? name.slice(0, -groupName.length - 1) : undefined;
  });
  const listed = new Set<number>();
  slots.forEach((_, index) => {
    if (index === actorSlot) return;
    if (index === nameSlot) {
      if (outerNames.some((outer) => outer === undefined)) listed.add(index);
      return;
    }
    if (chosen.has(index) || occurrences.some((occurrence) => occurrence.values[index] !== defaults[index])) listed.add(index);
  });

  const representativeInput = inputs[representative.input];
  const eol = representativeInput.text.includes('\r\n') ? '\r\n' : '\n';
  const unit = indentUnit(representativeInput.text, representativeInput.document.root?.children[0]?.start);
  const groupText = simpleGroupText(representative, slots, defaults, listed, unit.repeat(4), eol);
  const text = await simpleScenarioText({ groupText, groupName, file, occurrences, inputs, defaults, copies, unit, eol, rebase });
  // A parameter whose value differs between the group's scenarios (or from the one declared here): the group reads a copy of its own.
  const differing = [...(parameterConflicts(text, [{ groupText, groupName, occurrences, defaults, copies }], inputs).get(0) ?? [])];
  if (differing.some((name) => !copied.has(name))) {
    const own = await planBehaviour(
      shapeKey,
      slots,
      occurrences,
      inputs,
      file,
      rebase,
      chosen,
      wantedGroupName,
      new Set([...copied, ...differing]),
    );
    // One that cannot (its name reads it) is planned as before; modularize's flatten-back check decides.
    if (own.behaviour) return own;
  }

  // Keys are computed on the simple scenario as written, so they are what the flattener will match.
  const model = parseScenario(text);
  const group = model.groups[0];
  if (!group || group.name !== groupName) return { reason: 'the simple scenario would not hold the group' };
  const targets = overridableAttributes(model, group);
  const elements = selfAndDescendants(group.element);
  const slotOf = (target: OverridableAttribute): number =>
    slots.findIndex((slot) => elements[slot.element] === target.element && slot.name === target.attributeName);
  const keys = new Map<number, string>();
  for (const target of targets) {
    const index = slotOf(target);
    if (index < 0) return { reason: `'${target.attributeName}' is listed on an element the group does not have` };
    // The shortest key whose attributes take this one's value in every use: a key reaching several
    // attributes sets them all, which is right exactly where they always agree.
    const agrees = (key: string) =>
      targets
        .filter((other) => keyMatches(key, other))
        .map(slotOf)
        .every((other) => occurrences.every((occurrence) => occurrence.values[other] === occurrence.values[index]));
    const key = keyForms(target).find(agrees) ?? positionedKeyForms(target).find(agrees);
    if (key === undefined) {
      const longest = keyForms(target).at(-1) as string;
      return {
        reason: `no key tells its attributes '${longest}' apart`,
        conflict: targets.filter((other) => keyMatches(longest, other)).map(slotOf),
      };
    }
    keys.set(index, key);
  }
  const uses: Use[] = occurrences.map((occurrence, position) => {
    const overrides: Override[] = [];
    const written = new Set<string>();
    for (const index of [...keys.keys()].sort((a, b) => a - b)) {
      const key = keys.get(index) as string;
      const needed = index === nameSlot ? outerNames[position] === undefined : occurrence.values[index] !== defaults[index];
      if (!needed || written.has(key)) continue;
      written.add(key);
      overrides.push({ key, value: occurrence.values[index] });
    }
    return { occurrence, outerName: outerNames[position] ?? occurrence.values[nameSlot], overrides };
  });
  const parameters = [...keys.keys()].sort((a, b) => a - b).map((index) => `${elements[slots[index].element].name}.${slots[index].name}`);
  const part = { groupText, groupName, occurrences, defaults, copies };
  return { behaviour: { shapeKey, file, groupName, slots, defaults, parameters: [...new Set(parameters)], uses, text, part } };
}

/** The indentation of one level: that of the root's first child, else two spaces. */
export function indentUnit(text: string, firstChildStart: number | undefined): string {
  const indent = firstChildStart === undefined ? '' : indentationAt(text, firstChildStart);
  return indent.length > 0 ? indent : '  ';
}
