/**
 * *Insert into main* with a new entity: a module's role that no entity of the main plays is added to the main as the
 * module's example main declares it (its ScenarioObject, catalog reference as written) and places it in its Init (its
 * TeleportAction and speed), moved so that it stands to the main's ego as it stands to the example's ego
 * (docs/library.md). The edits go with the group's in one workspace edit.
 */
import type { LibraryModule } from './library';
import { moduleRoles, type ModuleRole } from './libraryInsert';
import { parseScenario, type ScenarioModel } from './model';
import { LIBRARY_PREFIX } from './sources';
import { pathsFor } from './paths';
import { attribute, attributeValue, escapeAttributeValue, XmlAttribute, XmlElement } from './xml';

/** The entity the library's example mains name their ego. */
const EGO = 'ego';

/** A change of the main's text: `start`..`end` replaced by `text` (an insertion where they are equal). */
export interface TextChange {
  start: number;
  end: number;
  text: string;
}

/** A role the example main can supply: its entity's name in the example and the fresh name offered in the main. */
export interface EntityOffer {
  role: string;
  name: string;
}

function child(element: XmlElement | undefined, name: string): XmlElement | undefined {
  return element?.children.find((candidate) => candidate.name === name);
}

/** The Init's Private of an entity. */
function privateOf(storyboard: XmlElement | undefined, entity: string): XmlElement | undefined {
  const actions = child(child(storyboard, 'Init'), 'Actions');
  return actions?.children.find((candidate) => candidate.name === 'Private' && attributeValue(candidate, 'entityRef') === entity);
}

/** `base`, or `base2`, `base3`, ...: the first that no name of `taken` equals, case aside (`ego` beside `Ego` would read as one). */
function freshName(base: string, taken: readonly string[]): string {
  const lower = new Set(taken.map((name) => name.toLowerCase()));
  let name = base;
  for (let index = 2; lower.has(name.toLowerCase()); index++) name = `${base}${index}`;
  return name;
}

/** The roles of the module whose entity the example main declares and places in its Init, each with a name free in the main. */
export function entityOffers(module: LibraryModule, exampleText: string, mainEntities: readonly string[]): EntityOffer[] {
  const example = parseScenario(exampleText);
  const storyboard = child(example.document.root, 'Storyboard');
  const taken = [...mainEntities];
  const offers: EntityOffer[] = [];
  for (const role of moduleRoles(module)) {
    if (!example.entities.some((entity) => entity.name === role.name) || !privateOf(storyboard, role.name)) continue;
    const name = freshName(role.name, taken);
    taken.push(name);
    offers.push({ role: role.name, name });
  }
  return offers;
}

function valueOf(element: XmlElement | undefined, name: string): string | undefined {
  return element && attributeValue(element, name);
}

/** A value the main gives, directly or through a parameter its ParameterDeclarations declare. */
function valueIn(root: XmlElement | undefined, value: string | undefined): string | undefined {
  if (value === undefined || !value.trim().startsWith('$')) return value?.trim();
  const name = value.trim().slice(1);
  const declaration = child(root, 'ParameterDeclarations')?.children.find(
    (candidate) => candidate.name === 'ParameterDeclaration' && attributeValue(candidate, 'name') === name,
  );
  return valueOf(declaration, 'value')?.trim();
}

/** A number the main gives, directly or through a parameter its ParameterDeclarations declare. */
function numberIn(root: XmlElement | undefined, value: string | undefined): number | undefined {
  const literal = valueIn(root, value) ?? '';
  if (literal === '' || !/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(literal)) return undefined;
  return Number(literal);
}

interface Placement {
  lanePosition: XmlElement | undefined;
  speedTarget: XmlElement | undefined;
}

/** The LanePosition of a Private's TeleportAction and the AbsoluteTargetSpeed of its SpeedAction (each the first). */
function placementOf(element: XmlElement | undefined): Placement {
  let lanePosition: XmlElement | undefined;
  let speedTarget: XmlElement | undefined;
  for (const action of element?.children.filter((candidate) => candidate.name === 'PrivateAction') ?? []) {
    lanePosition ??= child(child(child(action, 'TeleportAction'), 'Position'), 'LanePosition');
    speedTarget ??= child(child(child(child(action, 'LongitudinalAction'), 'SpeedAction'), 'SpeedActionTarget'), 'AbsoluteTargetSpeed');
  }
  return { lanePosition, speedTarget };
}

/** An actor of the main that enters its ego's lane ahead of it (a cut-in's car), or drives slower ahead in it: how far ahead it starts, and how fast. */
interface QueueMember {
  name: string;
  distance: number;
  speed: number;
  /** Whether it starts in the ego's lane (a LanePosition on its lane, or a RelativeLanePosition of dLane 0). */
  inLane: boolean;
  /** Its Init's distance (a LanePosition's s, `sense` per metre ahead, from `base`; a RelativeLanePosition's ds) and speed, where each is a number. */
  place?: { attribute: XmlAttribute; base: number; sense: number };
  speedAttribute?: XmlAttribute;
  /** Its group's ScenarioReference, and the library module it imports. */
  reference: XmlElement | undefined;
  module: string;
}

/**
 * The actors of the main's groups that import a module of `modules` (by name: those whose actor enters the lane of
 * `player` ahead of it, or those whose actor drives slower ahead in it; the group's keys name `player` where `named`), placed in its
 * Init ahead of `player`: by a LanePosition on its road (the distance counted as `player` drives, `sense`) or a
 * RelativeLanePosition from it, at a known speed.
 */
function queueMembers(
  main: ScenarioModel,
  storyboard: XmlElement | undefined,
  player: string,
  modules: { has(name: string): boolean },
  sense: number,
  named = true,
): QueueMember[] {
  const root = main.document.root;
  const playerPosition = placementOf(privateOf(storyboard, player)).lanePosition;
  const members: QueueMember[] = [];
  for (const group of main.groups) {
    const reference = child(group.element, 'ScenarioReference');
    const file = valueOf(reference, 'scenarioFileName') ?? '';
    const moduleName = file.slice(LIBRARY_PREFIX.length).replace(/\.xosc$/i, '');
    if (!file.startsWith(LIBRARY_PREFIX) || !modules.has(moduleName)) continue;
    const values = child(reference, 'ManeuverGroupReference')?.children.map((parameter) => valueOf(parameter, 'value')) ?? [];
    const name = valueOf(child(child(group.element, 'Actors'), 'EntityRef'), 'entityRef');
    // A slower car's group may name no ego (a slow target): its place in the lane of `player` is what counts.
    if (!name || (named && !values.includes(player))) continue;
    const placed = privateOf(storyboard, name);
    const { lanePosition, speedTarget } = placementOf(placed);
    const relative = placed?.children
      .map((action) => child(child(child(action, 'TeleportAction'), 'Position'), 'RelativeLanePosition'))
      .find((position) => position !== undefined);
    let distance: number | undefined;
    let inLane = false;
    let place: QueueMember['place'];
    const literal = (found: XmlAttribute | undefined) => (found && !found.value.trim().startsWith('$') ? found : undefined);
    if (
      lanePosition &&
      playerPosition &&
      valueIn(root, valueOf(lanePosition, 'roadId')) === valueIn(root, valueOf(playerPosition, 'roadId'))
    ) {
      const [s, playerS] = [numberIn(root, valueOf(lanePosition, 's')), numberIn(root, valueOf(playerPosition, 's'))];
      if (s !== undefined && playerS !== undefined) distance = sense * (s - playerS);
      inLane = numberIn(root, valueOf(lanePosition, 'laneId')) === numberIn(root, valueOf(playerPosition, 'laneId'));
      const sAttribute = literal(attribute(lanePosition, 's'));
      if (sAttribute && playerS !== undefined) place = { attribute: sAttribute, base: playerS, sense };
    } else if (relative && valueOf(relative, 'entityRef') === player) {
      distance = numberIn(root, valueOf(relative, 'ds'));
      inLane = (numberIn(root, valueOf(relative, 'dLane')) ?? 0) === 0;
      const dsAttribute = literal(attribute(relative, 'ds'));
      if (dsAttribute) place = { attribute: dsAttribute, base: 0, sense: 1 };
    }
    const speed = numberIn(root, valueOf(speedTarget, 'value'));
    const speedAttribute = literal(speedTarget && attribute(speedTarget, 'value'));
    if (distance !== undefined && distance > 0 && speed !== undefined)
      members.push({ name, distance, speed, inLane, place, speedAttribute, reference, module: moduleName });
  }
  return members;
}

/** The change of an attribute's value in the main's text. */
function attributeChange(found: XmlAttribute, value: string): TextChange {
  return { start: found.valueStart, end: found.valueEnd, text: escapeAttributeValue(value, found.quote) };
}

/**
 * How much slower than its follower (the example's ego) a module's actor drives in its example main: for a car that drives
 * slower ahead in the ego's lane, the difference a car entering the lane ahead of it leaves it (lead-brake: 2 m/s).
 */
export function exampleSpeedDifference(module: LibraryModule, exampleText: string): number | undefined {
  const example = parseScenario(exampleText);
  const storyboard = child(example.document.root, 'Storyboard');
  const roles = moduleRoles(module);
  const actor = roles.find((role) => role.actor);
  const follower = roles.find((role) => !role.actor && privateOf(storyboard, role.name))?.name ?? EGO;
  const speedOf = (name: string | undefined) =>
    name === undefined
      ? undefined
      : numberIn(example.document.root, valueOf(placementOf(privateOf(storyboard, name)).speedTarget, 'value'));
  const [own, followed] = [speedOf(actor?.name), speedOf(follower)];
  return own === undefined || followed === undefined ? undefined : followed - own;
}

/**
 * A slower car ahead in the ego's lane (`member`) behind a car that enters the lane `distance` ahead of the ego at
 * `speed`: no further ahead than it (level at most), and `difference` (its example's to its follower) slower than it, as
 * a slower car inserted after an entering one is placed; never moved forward or made faster. Its group's speed key that
 * holds its Init speed moves with it, else the group would set the old speed again at once.
 */
function queueBehind(
  member: QueueMember,
  player: string,
  distance: number,
  speed: number,
  difference: number,
): { changes: TextChange[]; said?: string } {
  const changes: TextChange[] = [];
  const told: string[] = [];
  if (member.place && distance < member.distance) {
    changes.push(attributeChange(member.place.attribute, rounded(member.place.base + member.place.sense * distance)));
    told.push(`${rounded(distance)} m ahead of ${player}, was ${rounded(member.distance)}`);
  }
  const slowed = Math.max(0, Math.min(speed, speed - difference));
  if (member.speedAttribute && slowed < member.speed) {
    changes.push(attributeChange(member.speedAttribute, rounded(slowed)));
    for (const parameter of member.reference?.children.find((candidate) => candidate.name === 'ManeuverGroupReference')?.children ?? [])
      if (
        /(^|\.)AbsoluteTargetSpeed\.value$/.test(valueOf(parameter, 'key') ?? '') &&
        numberIn(undefined, valueOf(parameter, 'value')) === member.speed
      ) {
        const value = attribute(parameter, 'value');
        if (value) changes.push(attributeChange(value, rounded(slowed)));
      }
    told.push(`${rounded(slowed)} m/s, was ${rounded(member.speed)}`);
  }
  return { changes, ...(told.length > 0 ? { said: `${member.name} moved behind it: ${told.join(', ')}` } : {}) };
}

/** Keys of an offset from a lane's centre line that esmini takes along the road's t, not the entity's left (swerving-lead's, arrive-leave-site's, oncoming-vehicle's). */
const LATERAL_OFFSET_KEY = /(^|\.)(AbsoluteTargetLaneOffset\.value|LaneChangeAction\.targetLaneOffset|targetLaneOffset)$/;

/** Keys of a lane change's side, counted from the heading of the entity they name (+1 its left): swapped on a road of the other traffic rule. */
const SIDE_KEY = /(^|\.)RelativeTargetLane\.value$/;

/** The roads of the main's and of the example's road file that are of left-hand traffic (none known: right-hand, OpenDRIVE's default). */
export interface TrafficRules {
  main?: ReadonlySet<string>;
  example?: ReadonlySet<string>;
}

/** +1 where a lane is driven along s (right-hand traffic: the negative lanes; left-hand: the positive ones), -1 against it. */
const drivingSense = (laneId: number, leftHand: boolean) => ((leftHand ? laneId > 0 : laneId < 0) ? 1 : -1);

/**
 * How the main's ego stands to the example's, as its driver sees the road: `along` -1 where one drives against s and the
 * other along it (the placement turned half round), `mirrored` where one road is of left-hand traffic and the other not
 * (left and right swapped, as a driver there expects), `lateral` -1 where the road's t runs the other way from the driver's left.
 */
interface Frame {
  along: number;
  lateral: number;
  mirrored: boolean;
  mainLeftHand: boolean;
  exampleLeftHand: boolean;
}

/** The frame of the main's ego placed by `mainPosition` against the example's by `examplePosition` (LanePositions); undefined when either is no LanePosition. */
function frameOf(
  mainRoot: XmlElement | undefined,
  mainPosition: XmlElement | undefined,
  exampleRoot: XmlElement | undefined,
  examplePosition: XmlElement | undefined,
  rules: TrafficRules | undefined,
): Frame | undefined {
  const mainLane = numberIn(mainRoot, valueOf(mainPosition, 'laneId'));
  const exampleLane = numberIn(exampleRoot, valueOf(examplePosition, 'laneId'));
  if (mainLane === undefined || exampleLane === undefined) return undefined;
  const mainLeftHand = rules?.main?.has(valueIn(mainRoot, valueOf(mainPosition, 'roadId')) ?? '') ?? false;
  const exampleLeftHand = rules?.example?.has(valueIn(exampleRoot, valueOf(examplePosition, 'roadId')) ?? '') ?? false;
  const mirrored = mainLeftHand !== exampleLeftHand;
  const along = drivingSense(mainLane, mainLeftHand) * drivingSense(exampleLane, exampleLeftHand);
  return { along, lateral: mirrored ? -along : along, mirrored, mainLeftHand, exampleLeftHand };
}

/**
 * The module's keys whose default means a side, written for the frame: an absolute lane offset an action moves to, which
 * esmini takes along the road's t (OSCPrivateAction.cpp:1078, 920), negated where t runs the other way from the driver's
 * left; a lane change's side, which esmini counts from the heading (OSCPrivateAction.cpp:895), negated where mirrored.
 */
function sideValues(module: LibraryModule, frame: Frame): Record<string, string> {
  const values: Record<string, string> = {};
  for (const parameter of module.parameters) {
    const value = numberIn(undefined, parameter.defaultValue);
    if (value === undefined || value === 0) continue;
    if ((LATERAL_OFFSET_KEY.test(parameter.key) && frame.lateral < 0) || (SIDE_KEY.test(parameter.key) && frame.mirrored))
      values[parameter.key] = rounded(-value);
  }
  return values;
}

/** Lane ids skip 0: as a count from the centre (…, -2, -1 | 0, 1, …), a lane further right is one less. */
const laneIndex = (laneId: number) => (laneId > 0 ? laneId - 1 : laneId);
const laneOfIndex = (index: number) => (index >= 0 ? index + 1 : index);
const rounded = (value: number) => String(Math.round(value * 1000) / 1000);

function lineStart(text: string, offset: number): number {
  return text.lastIndexOf('\n', offset - 1) + 1;
}

function indentUnit(text: string): string {
  return /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ';
}

/** A part of the example's text replaced: an attribute's value (escaped), or a range of the text (as given). */
type Replacement = { attribute: XmlAttribute; value: string } | { start: number; end: number; text: string };

/**
 * The element's text from the example with `replacements` made, re-indented from the example's indentation and unit
 * to `indent` and the main's unit.
 */
function transplant(exampleText: string, element: XmlElement, replacements: Replacement[], indent: string, unit: string): string {
  let text = exampleText.slice(element.start, element.end);
  const ranges = replacements.map((replacement) =>
    'attribute' in replacement
      ? {
          start: replacement.attribute.valueStart,
          end: replacement.attribute.valueEnd,
          text: escapeAttributeValue(replacement.value, replacement.attribute.quote),
        }
      : replacement,
  );
  for (const range of ranges.sort((a, b) => b.start - a.start))
    text = text.slice(0, range.start - element.start) + range.text + text.slice(range.end - element.start);
  const exampleUnit = indentUnit(exampleText);
  const base = exampleText.slice(lineStart(exampleText, element.start), element.start);
  return text
    .split('\n')
    .map((line, index) => {
      if (index === 0) return indent + line;
      const rest = line.startsWith(base) ? line.slice(base.length) : line.trimStart();
      const leading = /^[ \t]*/.exec(rest)?.[0] ?? '';
      const depth = Math.round(leading.replace(/\t/g, exampleUnit).length / exampleUnit.length);
      return indent + unit.repeat(depth) + rest.slice(leading.length);
    })
    .join('\n');
}

/** Text that appends `block` (already indented) as the last child of `parent`, which may be self-closing. */
function appendChild(text: string, parent: XmlElement, block: string): TextChange {
  const parentIndent = /^[ \t]*/.exec(text.slice(lineStart(text, parent.start)))?.[0] ?? '';
  if (parent.selfClosing) {
    const open = text.slice(parent.start, parent.end).replace(/\s*\/>$/, '>');
    return { start: parent.start, end: parent.end, text: `${open}\n${block}\n${parentIndent}</${parent.name}>` };
  }
  const last = parent.children[parent.children.length - 1];
  if (last) return { start: last.end, end: last.end, text: `\n${block}` };
  const closing = text.lastIndexOf('</', parent.end);
  const before = lineStart(text, closing);
  if (text.slice(before, closing).trim() === '') return { start: before, end: before, text: `${block}\n` };
  return { start: closing, end: closing, text: `\n${block}\n${parentIndent}` };
}

export interface NewEntities {
  changes: TextChange[];
  /** Key values of the group other than the module's defaults (a speed key moved with the actor's Init speed). */
  values: Record<string, string>;
  /** What was added, for the user: `adversary (Vehicle, 35 m ahead of Ego, lane -2, 7 m/s)`. */
  added: string[];
}

/**
 * The changes that add, for each role in `create` (role → the new entity's name, free in the main), the example's
 * ScenarioObject and Init Private. Where the example places the role's entity and a reference role (the first other
 * role the main already has a player for, `ego`) by LanePositions on one road, and the main places that player by a
 * LanePosition on a lane of the same side, the new entity keeps the example's lane difference and distance along the
 * road to it (turned half round where that player drives against s as the example's does not: ahead against s; mirrored
 * where the main's road is of the other traffic rule than the example's (`rules`): lanes and sides swapped), and its speed keeps the example's difference to the reference's (a standing entity stays standing);
 * a speed key whose default is that speed moves with it. Else the example's placement is written as it is.
 * Throws with what to do where the main cannot take the entity.
 */
export function newEntityChanges(
  mainText: string,
  module: LibraryModule,
  exampleText: string,
  create: Readonly<Record<string, string>>,
  players: Readonly<Record<string, string>>,
  files?: { main: string; example: string },
  rules?: TrafficRules,
  entering?: ReadonlySet<string>,
  slower?: ReadonlyMap<string, number>,
): NewEntities {
  const result: NewEntities = { changes: [], values: {}, added: [] };
  const roles = moduleRoles(module).filter((role) => create[role.name] !== undefined);
  const main = parseScenario(mainText);
  const root = main.document.root;
  const wellFormed = root !== undefined && !main.document.problems.some((problem) => problem.severity === 'error');
  const storyboard = child(root, 'Storyboard');
  const example = parseScenario(exampleText);
  const exampleRoot = example.document.root;
  const exampleStoryboard = child(exampleRoot, 'Storyboard');
  const roleReference = moduleRoles(module).find(
    (role: ModuleRole) => create[role.name] === undefined && players[role.name] !== undefined && privateOf(exampleStoryboard, role.name),
  );
  // A module whose keys name no ego (a lead that swerves at a set time) still stands to the example's `ego` somewhere:
  // the main's entity of that name, case aside, is the one it stands to.
  const mainEgo = main.entities.find((entity) => entity.name.toLowerCase() === EGO);
  const reference: { name: string; player: string } | undefined = roleReference
    ? { name: roleReference.name, player: players[roleReference.name] }
    : mainEgo && !Object.values(create).includes(mainEgo.name) && privateOf(exampleStoryboard, EGO)
      ? { name: EGO, player: mainEgo.name }
      : undefined;
  // The ego's frame against the example's, for the keys whose default means a side, whoever plays the actor.
  const frame =
    wellFormed && reference
      ? frameOf(
          root,
          placementOf(privateOf(storyboard, reference.player)).lanePosition,
          exampleRoot,
          placementOf(privateOf(exampleStoryboard, reference.name)).lanePosition,
          rules,
        )
      : undefined;
  if (frame) Object.assign(result.values, sideValues(module, frame));
  if (roles.length === 0) return result;
  if (!root || !wellFormed) throw new Error('the main is not well-formed XML: fix it first (the Problems panel says where)');
  const entities = child(root, 'Entities');
  if (!entities) throw new Error('the main has no Entities to add a new entity to: add <Entities/> after its RoadNetwork');
  if (!storyboard) throw new Error('the main has no Storyboard (with an Init) to place a new entity in');
  const actions = child(child(storyboard, 'Init'), 'Actions');
  if (!actions)
    throw new Error(
      "the main's Storyboard has no Init with Actions to place a new entity in: add <Init><Actions/></Init> as its first element",
    );
  const mainNames = main.entities.map((entity) => entity.name.toLowerCase());
  const unit = indentUnit(mainText);
  const entitiesIndent = /^[ \t]*/.exec(mainText.slice(lineStart(mainText, entities.start)))?.[0] ?? '';
  const actionsIndent = /^[ \t]*/.exec(mainText.slice(lineStart(mainText, actions.start)))?.[0] ?? '';
  const objects: string[] = [];
  const privates: string[] = [];
  // A slower car in the ego's lane goes behind the cars that enter that lane ahead of the ego, no faster than they: a
  // scripted car neither brakes nor steers for another, so one ahead that slows down would be run into (docs/library.md).
  const mainReferencePosition = reference && placementOf(privateOf(storyboard, reference.player)).lanePosition;
  const referenceLane = numberIn(root, valueOf(mainReferencePosition, 'laneId'));
  const sense = referenceLane === undefined ? 1 : drivingSense(referenceLane, frame?.mainLeftHand ?? false);
  const members =
    module.queue === 'slower' && reference && entering && entering.size > 0
      ? queueMembers(main, storyboard, reference.player, entering, sense)
      : [];
  const nearest = members.reduce<QueueMember | undefined>(
    (found, member) => (found && found.distance <= member.distance ? found : member),
    undefined,
  );
  // The other order: a car that enters the lane inserted after slower cars in it ahead of the same ego moves them behind it.
  const slowerAhead =
    module.queue === 'enters' && reference && slower && slower.size > 0
      ? queueMembers(main, storyboard, reference.player, slower, sense, false).filter((member) => member.inLane)
      : [];
  for (const role of roles) {
    const name = create[role.name];
    if (!/\S/.test(name)) throw new Error(`the new entity for '${role.name}' has no name`);
    if (mainNames.includes(name.toLowerCase()))
      throw new Error(
        `the main already declares an entity '${name}': name the new one otherwise (${freshName(
          name,
          main.entities.map((entity) => entity.name),
        )})`,
      );
    const object = example.entities.find((entity) => entity.name === role.name);
    const placed = privateOf(exampleStoryboard, role.name);
    if (!object || !placed)
      throw new Error(
        `the example main of ${module.name} declares and places no entity '${role.name}' to copy: pick an entity of the main to play it`,
      );
    objects.push(
      transplant(
        exampleText,
        object.element,
        object.nameAttribute ? [{ attribute: object.nameAttribute, value: name }] : [],
        entitiesIndent + unit,
        unit,
      ),
    );
    const replacements: Replacement[] = [];
    const entityRef = attribute(placed, 'entityRef');
    if (entityRef) replacements.push({ attribute: entityRef, value: name });
    const own = placementOf(placed);
    let where = 'placed as in the example';
    /** How far ahead of the reference player the new entity starts, where it is placed relative to it. */
    let placedDistance: number | undefined;
    if (reference) {
      const exampleReference = placementOf(privateOf(exampleStoryboard, reference.name));
      const player = reference.player;
      const mainReference = placementOf(privateOf(storyboard, player));
      const [ownLane, ownS, refLane, refS] = [
        numberIn(exampleRoot, valueOf(own.lanePosition, 'laneId')),
        numberIn(exampleRoot, valueOf(own.lanePosition, 's')),
        numberIn(exampleRoot, valueOf(exampleReference.lanePosition, 'laneId')),
        numberIn(exampleRoot, valueOf(exampleReference.lanePosition, 's')),
      ];
      const sameRoad =
        own.lanePosition &&
        exampleReference.lanePosition &&
        valueOf(own.lanePosition, 'roadId') === valueOf(exampleReference.lanePosition, 'roadId');
      const mainPosition = mainReference.lanePosition;
      const mainLane = numberIn(root, valueOf(mainPosition, 'laneId'));
      const mainS = numberIn(root, valueOf(mainPosition, 's'));
      const mainRoad = valueOf(mainPosition, 'roadId');
      if (sameRoad && own.lanePosition && ownLane !== undefined && ownS !== undefined && refLane !== undefined && refS !== undefined) {
        if (!privateOf(storyboard, player))
          throw new Error(
            `the main's Init does not place ${player}: '${name}' is placed relative to it as in the example of ${module.name}; place ${player} first, or pick an entity of the main to play '${role.name}'`,
          );
        const dLane = laneIndex(ownLane) - laneIndex(refLane);
        // Behind the nearest car that enters the lane (level with it at most), as it cuts in ahead of this one.
        const queued = role.actor && nearest !== undefined && dLane === 0 && ownS - refS > nearest.distance;
        const distance = queued && nearest ? nearest.distance : ownS - refS;
        placedDistance = distance;
        if (!mainPosition || mainLane === undefined || mainS === undefined || mainRoad === undefined) {
          // The ego stands where its route, world or road position puts it: the entity is placed relative to it, in
          // the lanes as counted from the ego's (right-hand side, as the example's), ds along the road.
          const offset = valueOf(own.lanePosition, 'offset');
          const open = `<RelativeLanePosition entityRef="${escapeAttributeValue(player)}" dLane="${dLane}" ds="${rounded(distance)}"${offset !== undefined ? ` offset="${escapeAttributeValue(offset)}"` : ''}`;
          const inner = own.lanePosition.selfClosing
            ? ''
            : exampleText.slice(own.lanePosition.startTagEnd, exampleText.lastIndexOf('</', own.lanePosition.end));
          replacements.push({
            start: own.lanePosition.start,
            end: own.lanePosition.end,
            text: own.lanePosition.selfClosing ? `${open}/>` : `${open}>${inner}</RelativeLanePosition>`,
          });
          where = `${rounded(Math.abs(distance))} m ${distance >= 0 ? 'ahead of' : 'behind'} ${player}, ${dLane === 0 ? 'in its lane' : `${Math.abs(dLane)} lane${Math.abs(dLane) > 1 ? 's' : ''} ${dLane < 0 ? 'right' : 'left'} of it`} (RelativeLanePosition)`;
        } else if (frame) {
          // The example's placement as its ego's driver sees it (ahead, to the left), turned half round where the main's ego
          // drives against s as the example's does not, and mirrored where one road is of left-hand traffic and the other
          // not (a driver there expects the other lanes, the overtaking and cutting in, on the other side): esmini drives a
          // lane by its side and the road's rule (RoadManager.cpp:11158) and reads lane changes and offsets relative to the
          // entity's heading (OSCPrivateAction.cpp:895, 1087), a LanePosition's offset along the road's t (RoadManager.cpp:9746).
          const { along, lateral, mirrored, mainLeftHand, exampleLeftHand } = frame;
          const turned = along < 0;
          const laneId = laneOfIndex(laneIndex(mainLane) + lateral * dLane);
          const s = mainS + along * distance;
          if (s < 0)
            throw new Error(
              `'${name}' would stand at s ${rounded(s)}, before the start of road ${mainRoad} (${rounded(Math.abs(distance))} m ${distance >= 0 ? 'ahead of' : 'behind'} ${player} as in the example${turned ? `, ${player} driving against the road's s on lane ${mainLane}` : ''}): move ${player} further ${turned ? "from the road's start" : 'along the road'} first`,
            );
          const roadAttribute = attribute(own.lanePosition, 'roadId');
          const laneAttribute = attribute(own.lanePosition, 'laneId');
          const sAttribute = attribute(own.lanePosition, 's');
          if (roadAttribute) replacements.push({ attribute: roadAttribute, value: mainRoad });
          if (laneAttribute) replacements.push({ attribute: laneAttribute, value: String(laneId) });
          if (sAttribute) replacements.push({ attribute: sAttribute, value: rounded(s) });
          const offsetAttribute = attribute(own.lanePosition, 'offset');
          const offset = numberIn(exampleRoot, offsetAttribute?.value);
          if (lateral < 0 && offsetAttribute && offset !== undefined && offset !== 0)
            replacements.push({ attribute: offsetAttribute, value: rounded(-offset) });
          // A heading relative to the lane's driving direction (a pedestrian facing the road) mirrored: its left is the other's right.
          const orientation = child(own.lanePosition, 'Orientation');
          const heading = orientation && attribute(orientation, 'h');
          const headingValue = numberIn(exampleRoot, heading?.value);
          if (mirrored && heading && headingValue !== undefined && headingValue !== 0 && valueOf(orientation, 'type') === 'relative')
            replacements.push({ attribute: heading, value: rounded(-headingValue) });
          const how = [
            ...(turned ? [`turned round: ${player} drives against the road's s, the example's ${reference.name} along it`] : []),
            ...(mirrored
              ? [
                  `mirrored: road ${mainRoad} is of ${mainLeftHand ? 'left' : 'right'}-hand traffic, the example's of ${exampleLeftHand ? 'left' : 'right'}-hand`,
                ]
              : []),
          ];
          where = `${rounded(Math.abs(distance))} m ${distance >= 0 ? 'ahead of' : 'behind'} ${player}, lane ${laneId}${how.length > 0 ? ` (the example's placement ${how.join(', and ')})` : ''}`;
        }
      }
      const speedAttribute = own.speedTarget && attribute(own.speedTarget, 'value');
      const ownSpeed = numberIn(exampleRoot, speedAttribute?.value);
      const refSpeed = numberIn(exampleRoot, valueOf(exampleReference.speedTarget, 'value'));
      const mainSpeed = numberIn(root, valueOf(mainReference.speedTarget, 'value'));
      if (speedAttribute && ownSpeed !== undefined && ownSpeed > 0 && refSpeed !== undefined && mainSpeed !== undefined) {
        // Behind a car that enters the lane: the example's difference to its follower taken from that car, and no faster than any.
        const followed = role.actor && nearest ? nearest.speed : mainSpeed;
        const fastest = role.actor && nearest ? Math.min(...members.map((member) => member.speed)) : Infinity;
        const speed = rounded(Math.max(0, Math.min(fastest, ownSpeed + followed - refSpeed)));
        replacements.push({ attribute: speedAttribute, value: speed });
        where += `, ${speed} m/s`;
        if (role.actor && nearest)
          where += ` (behind ${nearest.name}, which enters the lane of ${player} ahead of it: ${rounded(Math.max(0, nearest.speed - Number(speed)))} m/s slower, so that ${nearest.name} cuts in ahead of it and never runs into it)`;
        // Standing where the example's drives: the closing speed of the example is out of reach.
        if (!(role.actor && nearest) && ownSpeed + mainSpeed - refSpeed <= 0)
          where += ` (standing: the example's ${reference.name} drives ${rounded(refSpeed)} m/s, ${player} ${rounded(mainSpeed)}; a faster ${player} gives the example's closing speed)`;
        if (role.actor)
          for (const parameter of module.parameters)
            if (
              /(^|\.)AbsoluteTargetSpeed\.value$/.test(parameter.key) &&
              numberIn(undefined, parameter.defaultValue) === ownSpeed &&
              result.values[parameter.key] === undefined
            )
              result.values[parameter.key] = speed;
        if (role.actor && placedDistance !== undefined && placedDistance > 0)
          for (const member of slowerAhead) {
            const moved = queueBehind(
              member,
              player,
              placedDistance,
              Number(speed),
              slower?.get(member.module) ?? mainSpeed - member.speed,
            );
            result.changes.push(...moved.changes);
            if (moved.said) where += ` (${moved.said}, so that ${name} cuts in ahead of it and ${member.name} never runs into it)`;
          }
      }
    }
    privates.push(transplant(exampleText, placed, replacements, actionsIndent + unit, unit));
    const kind = object.element.children.find((candidate) =>
      ['Vehicle', 'Pedestrian', 'MiscObject', 'CatalogReference'].includes(candidate.name),
    );
    result.added.push(`${name} (${kind?.name ?? 'entity'}, ${where})`);
  }
  const catalogs = catalogLocationsNeeded(root, example.document.root, roles, create, files);
  if (catalogs.length > 0) {
    const locations = child(root, 'CatalogLocations');
    if (!locations)
      throw new Error(
        `the new entities are catalog references (as the example of ${module.name} writes them) and the main has no CatalogLocations to say where their catalogs are: add <CatalogLocations/> after its ParameterDeclarations`,
      );
    const indent = /^[ \t]*/.exec(mainText.slice(lineStart(mainText, locations.start)))?.[0] ?? '';
    const block = catalogs.map(
      (catalog) =>
        `${indent}${unit}<${catalog.kind}>\n${indent}${unit}${unit}<Directory path="${escapeAttributeValue(catalog.path)}"/>\n${indent}${unit}</${catalog.kind}>`,
    );
    result.changes.push(appendChild(mainText, locations, block.join('\n')));
  }
  result.changes.push(appendChild(mainText, entities, objects.join('\n')));
  result.changes.push(appendChild(mainText, actions, privates.join('\n')));
  return result;
}

/**
 * The example's catalog locations the main lacks, where a new entity is a catalog reference: each kind of catalog the
 * example locates and the main does not, its directory rebased from the example's folder to the main's (`files`; as
 * written when they are not known or the path holds a parameter). A kind the main locates elsewhere is left to it.
 */
function catalogLocationsNeeded(
  mainRoot: XmlElement,
  exampleRoot: XmlElement | undefined,
  roles: readonly ModuleRole[],
  create: Readonly<Record<string, string>>,
  files: { main: string; example: string } | undefined,
): { kind: string; path: string }[] {
  const references = roles.some((role) =>
    child(exampleRoot, 'Entities')?.children.some(
      (object) => attributeValue(object, 'name') === role.name && create[role.name] !== undefined && child(object, 'CatalogReference'),
    ),
  );
  if (!references) return [];
  const located = new Set(child(mainRoot, 'CatalogLocations')?.children.map((catalog) => catalog.name) ?? []);
  const needed: { kind: string; path: string }[] = [];
  for (const catalog of child(exampleRoot, 'CatalogLocations')?.children ?? []) {
    const written = valueOf(child(catalog, 'Directory'), 'path');
    if (located.has(catalog.name) || written === undefined) continue;
    let rebased = written;
    if (files && !written.includes('$')) {
      const paths = pathsFor(files.main);
      const absolute = paths.resolve(paths.dirname(files.example), written);
      rebased = paths.relative(paths.dirname(files.main), absolute).split(paths.sep).join('/') || '.';
    }
    needed.push({ kind: catalog.name, path: rebased });
  }
  return needed;
}
