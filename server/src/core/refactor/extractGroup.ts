import * as path from 'node:path';
import { TextEdit } from '../flatten/edits';
import { ManeuverGroupInfo } from '../model';
import { planBehaviour } from '../modularize/behaviour';
import { mainText } from '../modularize/mainText';
import { pathRebaser } from '../modularize/rebase';
import { readOccurrence } from '../modularize/shape';
import { ParsedInput } from '../modularize/types';
import { enumerationValues } from '../schema/values';
import { indexFor, typeOfElement } from '../schema/query';
import { XmlDocument } from '../xml';
import { RefactoringRefusal } from './refusal';

/** One attribute of a group that the simple scenario may list in `parameterAttributes`. */
export interface TunableAttribute {
  /** Stable for one text: the element's place in the group (document order) and the attribute's name. */
  id: string;
  /** `Element.attribute`, the key a user would write. */
  label: string;
  value: string;
  /** Whether it is proposed by default: a number, an entity reference or an enumeration. */
  suggested: boolean;
}

const NUMBER = /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/;

function attributeId(element: number, name: string): string {
  return `${element}:${name}`;
}

/**
 * The attributes of a group a user could make overridable, in document order: all but the group's
 * name and the actor's `entityRef` (the outer group sets both); numbers, entity references and
 * enumeration values are suggested. Undefined when the group cannot be extracted (no name, no actor,
 * already importing or declaring overridable attributes).
 */
export function tunableAttributes(
  document: XmlDocument,
  group: ManeuverGroupInfo,
  entityNames: ReadonlySet<string>,
): TunableAttribute[] | undefined {
  const read = readOccurrence(0, document, group);
  if (!read) return undefined;
  const { shape, occurrence } = read;
  const schema = indexFor(document, 'auto');
  const result: TunableAttribute[] = [];
  shape.slots.forEach((slot, index) => {
    if (slot.element === 0 && slot.name === 'name') return;
    if (slot.element === occurrence.actorElement && slot.name === 'entityRef') return;
    const element = occurrence.elements[slot.element];
    const value = occurrence.values[index];
    let suggested = NUMBER.test(value.trim()) || entityNames.has(value);
    if (!suggested && schema && !value.startsWith('$')) {
      const typeName = typeOfElement(schema, element);
      const declaration = typeName ? schema.attribute(typeName, slot.name) : undefined;
      const simple = declaration ? schema.simpleType(declaration.type) : undefined;
      suggested = simple !== undefined && enumerationValues(simple).includes(value);
    }
    result.push({ id: attributeId(slot.element, slot.name), label: `${element.name}.${slot.name}`, value, suggested });
  });
  return result;
}

/** A file stem from a group's name: letters, digits, `_` and `-` kept. */
export function fileStem(groupName: string): string {
  const stem = groupName.replace(/[^A-Za-z0-9_-]+/g, '_').replace(/^_+|_+$/g, '');
  return stem.length > 0 ? stem : 'group';
}

export interface ExtractGroupRequest {
  /** Absolute path of the scenario the group is in. */
  file: string;
  text: string;
  document: XmlDocument;
  group: ManeuverGroupInfo;
  /** Ids (`TunableAttribute.id`) of the attributes to list; the suggested ones when undefined. */
  chosen?: readonly string[];
  entityNames: ReadonlySet<string>;
  /** Whether a path is taken already (on disk or open in the editor). */
  exists(file: string): Promise<boolean>;
  /** The parameters each CatalogReference's entry reads from the scenario (ModularizeInput.catalogParameters): declared in the simple scenario too. */
  catalogParameters?: ReadonlyMap<number, readonly string[]>;
}

export interface ExtractedGroup {
  /** The new simple scenario (absolute path) and its text. */
  file: string;
  text: string;
  /** The edit of the scenario: the group replaced by a group that imports it. */
  replacement: TextEdit;
  /** The attributes listed, as `Element.attribute`. */
  parameters: string[];
}

/** A free `<stem>.xosc` beside `file`: `stem_2.xosc`, ... when taken. */
async function freeFile(directory: string, stem: string, exists: (file: string) => Promise<boolean>): Promise<string> {
  for (let n = 1; ; n++) {
    const candidate = path.join(directory, n === 1 ? `${stem}.xosc` : `${stem}_${n}.xosc`);
    if (!(await exists(candidate))) return candidate;
  }
}

/**
 * Extracts one group into a simple scenario beside its file, as `modularize` does for a recurring
 * one (the same writer): the chosen attributes listed with their current values as defaults, and the
 * group replaced by a ScenarioReference that reproduces it (setting its name when the outer name alone
 * cannot). Throws with the reason when the group cannot be extracted.
 */
export async function extractGroup(request: ExtractGroupRequest): Promise<ExtractedGroup> {
  const { file, text, document, group } = request;
  const read = readOccurrence(0, document, group);
  if (!read)
    throw new RefactoringRefusal(
      'only a named ManeuverGroup with an actor, no ScenarioReference and no parameterAttributes can be extracted',
    );
  const { shape, occurrence } = read;
  const tunable = tunableAttributes(document, group, request.entityNames) ?? [];
  const wanted = new Set(request.chosen ?? tunable.filter((candidate) => candidate.suggested).map((candidate) => candidate.id));
  const chosen = new Set<number>();
  shape.slots.forEach((slot, index) => {
    if (wanted.has(attributeId(slot.element, slot.name))) chosen.add(index);
  });
  const simpleFile = await freeFile(path.dirname(file), fileStem(group.name), request.exists);
  const input: ParsedInput = { path: file, output: file, text, document, pathEdits: [], catalogParameters: request.catalogParameters };
  const rebase = pathRebaser();
  let planned = await planBehaviour(shape.key, shape.slots, [occurrence], [input], simpleFile, rebase, chosen);
  // Attributes that no key tells apart with different values cannot all be listed: those are left out.
  while (!planned.behaviour && planned.conflict?.some((index) => chosen.has(index))) {
    for (const index of planned.conflict) chosen.delete(index);
    planned = await planBehaviour(shape.key, shape.slots, [occurrence], [input], simpleFile, rebase, chosen);
  }
  const behaviour = planned.behaviour;
  if (!behaviour) throw new RefactoringRefusal(`the group cannot be extracted: ${planned.reason ?? 'no simple scenario holds it'}`);
  const main = mainText(input, [{ behaviour, use: behaviour.uses[0] }]);
  // mainText rewrites the whole input; only the group's span differs.
  const start = group.element.start;
  const tail = text.length - group.element.end;
  return {
    file: simpleFile,
    text: behaviour.text,
    replacement: { start, end: group.element.end, text: main.slice(start, main.length - tail) },
    parameters: behaviour.parameters,
  };
}
