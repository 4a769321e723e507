/**
 * *Insert into main*: a library module's group written into a main file's Act as a `ManeuverGroup` holding its
 * `ScenarioReference`, with every documented key at its default and the module's entities played by the main's
 * (docs/library.md). The entities a module names are its *roles*: its actor and each entity an entity-valued key
 * names by default (`ego` in the cut-in's `RelativeDistanceCondition.entityRef`).
 */
import type { LibraryModule } from './library';
import { parseScenario } from './model';
import { LIBRARY_PREFIX } from './sources';
import { attributeValue, elementAt, endTagStart, escapeAttributeValue, XmlDocument, XmlElement } from './xml';

/** An entity the module names, which an entity of the main plays. */
export interface ModuleRole {
  /** The entity's name in the module (the default of the keys that name it). */
  name: string;
  about: string;
  /** Whether it is the group's actor (in `Actors`). */
  actor: boolean;
  /** The keys whose value names it. */
  keys: string[];
}

/** An `Act` of the main the group may go into. */
export interface ActChoice {
  /** `Story/Act`, what a caller names to choose it. */
  path: string;
  story: string;
  act: string;
  /** The names of the ManeuverGroups the Act holds. */
  groups: string[];
}

export interface MainShape {
  acts: ActChoice[];
  entities: string[];
  /** The entities an Actors of one of the main's ManeuverGroups names: each has a behaviour already. */
  actors: string[];
  /** Given an offset: whether a group can go there (insertionPointAt). */
  insertsAt?: boolean;
}

export interface InsertedGroup {
  /** Where the text goes (an offset of the main's text); nothing is replaced. */
  offset: number;
  text: string;
  groupName: string;
  act: string;
}

/** Whether a key's attribute names an entity (`entityRef`, `masterEntityRef`, ...): its value is one of the main's entities. */
export function isEntityKey(key: string): boolean {
  const attribute = key.split('.').pop() ?? key;
  return /entityref$/i.test(attribute);
}

/**
 * The module's roles: its actor first, then each other entity its entity-valued keys name by default; such an entity
 * that the group's Actors also names (traffic-jam-end's `jam2`, set by the key `Actors.EntityRef[2].entityRef`) is an actor.
 */
export function moduleRoles(module: LibraryModule): ModuleRole[] {
  const roles: ModuleRole[] = [{ name: module.actor.name, about: module.actor.about, actor: true, keys: [] }];
  for (const parameter of module.parameters) {
    if (!isEntityKey(parameter.key) || parameter.defaultValue === undefined) continue;
    let role = roles.find((known) => known.name === parameter.defaultValue);
    if (!role) {
      role = { name: parameter.defaultValue, about: parameter.about, actor: module.actors.includes(parameter.defaultValue), keys: [] };
      roles.push(role);
    }
    role.keys.push(parameter.key);
  }
  return roles;
}

function storyboardActs(root: XmlElement | undefined): { story: XmlElement; act: XmlElement }[] {
  const storyboard = root?.children.find((child) => child.name === 'Storyboard');
  const acts: { story: XmlElement; act: XmlElement }[] = [];
  for (const story of storyboard?.children.filter((child) => child.name === 'Story') ?? [])
    for (const act of story.children.filter((child) => child.name === 'Act')) acts.push({ story, act });
  return acts;
}

/** The Acts and entities of a main's text, for the questions *Insert into main* asks; given `at`, whether a group can go there. */
export function mainShape(text: string, at?: number): MainShape {
  const model = parseScenario(text);
  return {
    ...(at !== undefined ? { insertsAt: insertionPointAt(model.document, at) !== undefined } : {}),
    acts: storyboardActs(model.document.root).map(({ story, act }) => {
      const storyName = attributeValue(story, 'name') ?? '';
      const actName = attributeValue(act, 'name') ?? '';
      return {
        path: `${storyName}/${actName}`,
        story: storyName,
        act: actName,
        groups: act.children.filter((child) => child.name === 'ManeuverGroup').map((group) => attributeValue(group, 'name') ?? ''),
      };
    }),
    entities: model.entities.map((entity) => entity.name).filter((name) => name.length > 0),
    actors: [
      ...new Set(
        model.groups.flatMap((group) =>
          (group.element.children.find((child) => child.name === 'Actors')?.children ?? [])
            .filter((child) => child.name === 'EntityRef')
            .map((entityRef) => attributeValue(entityRef, 'entityRef') ?? ''),
        ),
      ),
    ].filter((name) => name.length > 0),
  };
}

/**
 * The main's scripted actors: the entities an Actors of its ManeuverGroups names, but for one a group importing a library
 * module names by an entity key while not acting in it (the ego a cut-in cuts in ahead of: the driver under test).
 */
export function scriptedActors(text: string): Set<string> {
  const model = parseScenario(text);
  const actors = new Set(mainShape(text).actors);
  for (const group of model.groups) {
    const reference = group.element.children.find((child) => child.name === 'ScenarioReference');
    if (!(attributeValue(reference ?? group.element, 'scenarioFileName') ?? '').startsWith(LIBRARY_PREFIX)) continue;
    const acting = new Set(
      (group.element.children.find((child) => child.name === 'Actors')?.children ?? []).map((entityRef) =>
        attributeValue(entityRef, 'entityRef'),
      ),
    );
    for (const parameter of reference?.children.find((child) => child.name === 'ManeuverGroupReference')?.children ?? []) {
      const value = attributeValue(parameter, 'value');
      if (value && isEntityKey(attributeValue(parameter, 'key') ?? '') && !acting.has(value)) actors.delete(value);
    }
  }
  return actors;
}

/** Each entity's kind (`Vehicle`, `Pedestrian`, `MiscObject`) where its ScenarioObject says it; a catalog entry's is not known here. */
export function entityKinds(text: string): Map<string, string> {
  const kinds = new Map<string, string>();
  for (const entity of parseScenario(text).entities) {
    const kind = entity.element.children.find((child) => ['Vehicle', 'Pedestrian', 'MiscObject'].includes(child.name))?.name;
    if (entity.name && kind) kinds.set(entity.name, kind);
  }
  return kinds;
}

/** The entity of the main with the role's very name, else the same name ignoring case. */
function namedPlayer(role: ModuleRole, entities: readonly string[]): string | undefined {
  return entities.find((entity) => entity === role.name) ?? entities.find((entity) => entity.toLowerCase() === role.name.toLowerCase());
}

/**
 * The entity of the main that most likely plays a role: the same name, else the same name ignoring case; else, given
 * the kinds of the module's and of the main's entities, the one entity of the role's kind (a Pedestrian for a
 * pedestrian) that no role of the module names and, for a role the module drives (an actor), that is no actor of a
 * group of the main (`busy`: a car that cuts in already is no likely lead vehicle; the ego its own group drives still
 * is the ego a key names); else none (the user is asked).
 */
export function guessPlayer(
  role: ModuleRole,
  entities: readonly string[],
  kinds?: {
    roles: readonly ModuleRole[];
    module: ReadonlyMap<string, string>;
    main: ReadonlyMap<string, string>;
    busy?: readonly string[];
  },
): string | undefined {
  const named = namedPlayer(role, entities);
  if (named || !kinds) return named;
  const kind = kinds.module.get(role.name);
  if (!kind) return undefined;
  const candidates = freeEntities(entities, kinds.roles, role.actor ? (kinds.busy ?? []) : []).filter(
    (entity) => kinds.main.get(entity) === kind,
  );
  return candidates.length === 1 ? candidates[0] : undefined;
}

/** The main's entities that no role of the module names and that no group of the main has as an actor. */
export function freeEntities(entities: readonly string[], roles: readonly ModuleRole[], busy: readonly string[]): string[] {
  const playingByName = new Set(roles.map((other) => namedPlayer(other, entities)));
  return entities.filter((entity) => !playingByName.has(entity) && !busy.includes(entity));
}

/** `base`, or `base2`, `base3`, ... : the first not among `taken`. */
export function uniqueName(base: string, taken: readonly string[]): string {
  if (!taken.includes(base)) return base;
  for (let index = 2; ; index++) if (!taken.includes(`${base}${index}`)) return `${base}${index}`;
}

/** Where *Insert library module here…* puts a group: an Act, and the ManeuverGroup of it the new one follows (none: first). */
export interface InsertionPoint {
  story: XmlElement;
  act: XmlElement;
  after: XmlElement | undefined;
}

/**
 * The insertion point for a cursor at `offset`: on a ManeuverGroup of an Act (its tags or the space directly in it),
 * after that group; in the space directly in an Act (between its groups, on its tags), after the group that ends
 * before the cursor. Undefined anywhere else (inside an Actors, a Maneuver, a trigger, outside the Storyboard).
 */
export function insertionPointAt(document: XmlDocument, offset: number): InsertionPoint | undefined {
  const element = elementAt(document, offset);
  const group = element?.name === 'ManeuverGroup' && element.parent?.name === 'Act' ? element : undefined;
  const act = group ? group.parent : element?.name === 'Act' ? element : undefined;
  const story = act?.parent;
  if (!act || story?.name !== 'Story' || story.parent?.name !== 'Storyboard') return undefined;
  const after = group ?? act.children.filter((child) => child.name === 'ManeuverGroup' && child.end <= offset).pop();
  return { story, act, after };
}

function lineStart(text: string, offset: number): number {
  return text.lastIndexOf('\n', offset - 1) + 1;
}

function indentationAt(text: string, offset: number): string {
  return /^[ \t]*/.exec(text.slice(lineStart(text, offset)))?.[0] ?? '';
}

/**
 * The ManeuverGroup that imports the module's group, written into the chosen Act after its last ManeuverGroup
 * (before its StartTrigger when it holds none), or, given `at` (an offset of the text), at that insertion point
 * (insertionPointAt). `players` maps each role to the main's entity; a role left out keeps the module's name,
 * which `check` then reports as an entity the main does not declare.
 */
export function insertModuleGroup(
  text: string,
  module: LibraryModule,
  choice: { act?: string; at?: number; players: Readonly<Record<string, string>>; values?: Readonly<Record<string, string>> },
): InsertedGroup {
  const model = parseScenario(text);
  if (!model.document.root || model.document.problems.some((problem) => problem.severity === 'error'))
    throw new Error('the main is not well-formed XML: fix it first (the Problems panel says where)');
  const acts = storyboardActs(model.document.root);
  if (acts.length === 0) throw new Error('the main has no Story with an Act to put the group in');
  const point = choice.at === undefined ? undefined : insertionPointAt(model.document, choice.at);
  if (choice.at !== undefined && !point)
    throw new Error('the position is not on an Act or on a ManeuverGroup of an Act (the text changed since it was asked?)');
  const found =
    point ??
    (choice.act
      ? acts.find(({ story, act }) => `${attributeValue(story, 'name') ?? ''}/${attributeValue(act, 'name') ?? ''}` === choice.act)
      : acts[0]);
  if (!found) throw new Error(`the main has no Act '${choice.act}' (Story/Act)`);
  const { act } = found;
  const unit = /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ';
  const actIndent = indentationAt(text, act.start);
  const groupIndent = actIndent + unit;
  const groupName = uniqueName(
    module.maneuverGroup,
    model.groups.map((group) => group.name),
  );
  const player = (role: string) => choice.players[role] ?? role;
  const attributeText = (value: string) => escapeAttributeValue(value);
  // Every entity of the module's Actors (only the first if it names none); flattening sets only the first from the
  // outer group (SPEC 4 step 2), the others through their keys, so the main reads as it runs.
  const actorPlayers = (module.actors.length > 0 ? module.actors : [module.actor.name]).map(player);
  const roleOfDefault = new Map(moduleRoles(module).map((role) => [role.name, role]));
  const parameterLines = module.parameters
    .filter((parameter) => parameter.defaultValue !== undefined)
    .map((parameter) => {
      const value =
        isEntityKey(parameter.key) && roleOfDefault.has(parameter.defaultValue ?? '')
          ? player(parameter.defaultValue ?? '')
          : (choice.values?.[parameter.key] ?? parameter.defaultValue ?? '');
      return `${groupIndent}${unit.repeat(3)}<ParameterReference key="${attributeText(parameter.key)}" value="${attributeText(value)}"/>`;
    });
  const lines = [
    `${groupIndent}<ManeuverGroup name="${attributeText(groupName)}" maximumExecutionCount="1">`,
    `${groupIndent}${unit}<Actors selectTriggeringEntities="false">`,
    ...actorPlayers.map((actor) => `${groupIndent}${unit.repeat(2)}<EntityRef entityRef="${attributeText(actor)}"/>`),
    `${groupIndent}${unit}</Actors>`,
    `${groupIndent}${unit}<ScenarioReference scenarioFileName="${attributeText(`${LIBRARY_PREFIX}${module.name}`)}">`,
    `${groupIndent}${unit.repeat(2)}<ManeuverGroupReference maneuverGroupName="${attributeText(module.maneuverGroup)}">`,
    ...parameterLines,
    `${groupIndent}${unit.repeat(2)}</ManeuverGroupReference>`,
    `${groupIndent}${unit}</ScenarioReference>`,
    `${groupIndent}</ManeuverGroup>`,
  ];
  const groups = act.children.filter((child) => child.name === 'ManeuverGroup');
  const last = point ? point.after : groups[groups.length - 1];
  const block = lines.join('\n');
  if (last) return { offset: last.end, text: `\n${block}`, groupName, act: attributeValue(act, 'name') ?? '' };
  if (act.selfClosing) throw new Error(`the Act '${attributeValue(act, 'name') ?? ''}' is empty (<Act/>): give it a StartTrigger first`);
  const next = act.children[0];
  // Before the Act's first child (its StartTrigger), at the start of that child's line; else before its end tag
  // (which may hold whitespace: `</Act >`, `</Act\n>`).
  const at = next ? next.start : endTagStart(text, act);
  const before = lineStart(text, at);
  if (text.slice(before, at).trim() === '')
    return { offset: before, text: `${block}\n`, groupName, act: attributeValue(act, 'name') ?? '' };
  return { offset: at, text: `\n${block}\n${actIndent}`, groupName, act: attributeValue(act, 'name') ?? '' };
}
