import * as fs from 'node:fs';
import * as path from 'node:path';
import { FlatSource, originOf } from '../core/flatten';
import { PARAMETER_ATTRIBUTES } from '../core/model';
import { Evaluator, semanticModelOf } from '../core/semantics';
import { SourceRef } from '../core/sources';
import { Range } from '../core/text';
import { attribute, descendants, XmlAttribute, XmlDocument, XmlElement } from '../core/xml';
import { EsminiLogMessage } from './log';

/** An esmini message placed on the line of the source file it is about. */
export interface EsminiProblem {
  source: SourceRef;
  range: Range;
  severity: 'error' | 'warning';
  /** esmini's own words. */
  message: string;
  /** Simulated time printed with it; undefined while loading. */
  time: number | undefined;
  /** Zero-based line of its first occurrence in the log. */
  logLine: number;
  /** How often esmini printed it. */
  count: number;
  /** False when nothing in the scenario could be matched, so it sits on the main file's first line. */
  located: boolean;
  /** Why it was given a different severity than esmini's, when it was. */
  note?: string;
}

/** Where a message points: an element of the flattened scenario (or, with `file`, of a catalog file a run does not flatten), and one of its attributes when known. */
interface Target {
  element: XmlElement;
  attribute?: string;
  /** The catalog file the element lies in. */
  file?: { ref: SourceRef; document: XmlDocument };
}

/** A catalog entry esmini may read for the scenario (one a reference names, or another of its catalog), in the file it was read from. */
interface UsedEntry {
  entry: XmlElement;
  file: { ref: SourceRef; document: XmlDocument };
}

/** An attribute's value as esmini reads it: `$parameters` and `${...}` evaluated, else as written. */
type ValueOf = (element: XmlElement, name: string) => string | undefined;

/** The Controller an ObjectController's or AssignControllerAction's child stands for: itself inline, or the catalog entry a CatalogReference names. */
type ControllerOf = (element: XmlElement) => XmlElement | undefined;

interface MessageRule {
  pattern: RegExp;
  /** Every element the message can be about, in document order; the n-th message takes the n-th one. */
  targets: (
    root: XmlElement,
    match: RegExpExecArray,
    valueOf: ValueOf,
    controllerOf: ControllerOf,
    entries: readonly UsedEntry[],
  ) => Target[];
  severity?: 'error' | 'warning';
  note?: string;
}

function allElements(root: XmlElement): XmlElement[] {
  return [root, ...descendants(root)];
}

function elementsNamed(root: XmlElement, name: string): XmlElement[] {
  return allElements(root).filter((element) => element.name === name);
}

/** Positions on road `roadId` (LanePosition, RoadPosition, waypoints...): on lane `laneId` when given and any is, else any on that road. */
function positionsOnRoad(root: XmlElement, valueOf: ValueOf, roadId: string, laneId?: string): Target[] {
  const onRoad = allElements(root).filter((element) => valueOf(element, 'roadId') === roadId);
  const onLane = laneId === undefined ? [] : onRoad.filter((element) => Number(valueOf(element, 'laneId')) === Number(laneId));
  return onLane.length > 0
    ? onLane.map((element) => ({ element, attribute: 'laneId' }))
    : onRoad.map((element) => ({ element, attribute: 'roadId' }));
}

function ancestorNamed(element: XmlElement, name: string): XmlElement | undefined {
  for (let current = element.parent; current; current = current.parent) if (current.name === name) return current;
  return undefined;
}

/** Each controller the scenario gives an entity (ObjectController, AssignControllerAction), where it is written and the Controller it stands for. */
function controllersOf(root: XmlElement, controllerOf: ControllerOf): { at: Target; controller: XmlElement | undefined }[] {
  return allElements(root)
    .filter((element) => element.name === 'ObjectController' || element.name === 'AssignControllerAction')
    .flatMap((holder) => holder.children.filter((child) => child.name === 'Controller' || child.name === 'CatalogReference'))
    .map((element) => ({
      at: { element, attribute: element.name === 'CatalogReference' ? 'entryName' : 'name' },
      controller: controllerOf(element),
    }));
}

/** A Controller's Property of that name, as written. */
function controllerProperty(controller: XmlElement | undefined, name: string): string | undefined {
  const properties = controller?.children.find((child) => child.name === 'Properties');
  const property = properties?.children.find((child) => child.name === 'Property' && attribute(child, 'name')?.value === name);
  return property ? attribute(property, 'value')?.value : undefined;
}

/** The elements of each entry the scenario uses, each entry once, as targets in its catalog file. */
function entryTargets(entries: readonly UsedEntry[], pick: (element: XmlElement) => Target | undefined): Target[] {
  const seen = new Set<XmlElement>();
  const targets: Target[] = [];
  for (const { entry, file } of entries) {
    if (seen.has(entry)) continue;
    seen.add(entry);
    for (const element of allElements(entry)) {
      const target = pick(element);
      if (target) targets.push({ ...target, file });
    }
  }
  return targets;
}

/** The ParameterDeclarations of `name` that come after another of the name: in the scenario, then in the entries it uses (after the scenario's own, or the entry's earlier one), where esmini shadows the earlier value. */
function redeclarations(root: XmlElement, entries: readonly UsedEntry[], name: string): Target[] {
  const named = (element: XmlElement) => element.name === 'ParameterDeclaration' && attribute(element, 'name')?.value === name;
  const inScenario = allElements(root).filter(named);
  const targets: Target[] = inScenario.slice(1).map((element) => ({ element, attribute: 'name' }));
  const global = root.children.find((child) => child.name === 'ParameterDeclarations')?.children.some(named) ?? false;
  const seen = new Set<XmlElement>();
  for (const { entry, file } of entries) {
    if (seen.has(entry)) continue;
    seen.add(entry);
    const declarations = allElements(entry).filter(named);
    for (const element of global ? declarations : declarations.slice(1)) targets.push({ element, attribute: 'name', file });
  }
  return targets;
}

/** Messages of esmini 3.6 that name no element, with what they are about (from its ScenarioReader.cpp and OSCPrivateAction.cpp). */
const RULES: MessageRule[] = [
  {
    // ScenarioReader.cpp parseOSCController: a controller's Properties File found neither from the working folder nor the scenario's.
    pattern: /^Failed to localize controller file /,
    targets: (root, _match, _valueOf, controllerOf) =>
      controllersOf(root, controllerOf)
        .filter(({ controller }) =>
          controller?.children.some((child) => child.name === 'Properties' && child.children.some((each) => each.name === 'File')),
        )
        .map(({ at }) => at),
  },
  {
    // ScenarioReader.cpp parseOSCController: the controller's esminiController (else its name) is no controller this esmini has.
    pattern: /^Unsupported controller type: (.+?)\. Falling back/,
    targets: (root, match, _valueOf, controllerOf) =>
      controllersOf(root, controllerOf)
        .filter(
          ({ controller }) =>
            controller !== undefined &&
            (controllerProperty(controller, 'esminiController') ?? attribute(controller, 'name')?.value) === match[1],
        )
        .map(({ at }) => at),
  },
  {
    // Printed for each Event whose StartTrigger has such a condition, in document order.
    pattern: /simulationTime = 0 condition used with edge "(\w+)"/,
    targets: (root, match) =>
      elementsNamed(root, 'SimulationTimeCondition')
        .filter((element) => Math.abs(Number(attribute(element, 'value')?.value)) < 1e-9)
        .map((element) => ancestorNamed(element, 'Condition'))
        .filter((condition): condition is XmlElement =>
          Boolean(condition && attribute(condition, 'conditionEdge')?.value === match[1] && ancestorNamed(condition, 'Event')),
        )
        .map((condition) => ({ element: condition, attribute: 'conditionEdge' })),
  },
  {
    // ScenarioEngine.cpp: no road file named (esmini runs on without roads): an empty LogicFile, else the RoadNetwork. Before the next rule, which would take 'specified' for a file's name.
    pattern: /^No OpenDRIVE file specified/,
    targets: (root) => {
      const logicFiles = elementsNamed(root, 'LogicFile').map((element): Target => ({ element, attribute: 'filepath' }));
      return logicFiles.length > 0 ? logicFiles : elementsNamed(root, 'RoadNetwork').map((element) => ({ element }));
    },
  },
  {
    pattern: /OpenDRIVE file (\S+)/,
    targets: (root) => elementsNamed(root, 'LogicFile').map((element) => ({ element, attribute: 'filepath' })),
  },
  {
    // ScenarioReader.cpp CheckAndAdjustRoadSValue: a position's s past its road's end (or below 0), which esmini clamps; the positions on that road with that s, else any on it.
    pattern: /^Invalid s value (\S+) for road (\S+) of length/,
    targets: (root, match, valueOf) => {
      const onRoad = allElements(root).filter((element) => valueOf(element, 'roadId') === match[2] && valueOf(element, 's') !== undefined);
      const atS = onRoad.filter((element) => Math.abs(Number(valueOf(element, 's')) - Number(match[1])) < 1e-4);
      return (atS.length > 0 ? atS : onRoad).map((element) => ({ element, attribute: 's' }));
    },
  },
  {
    // ScenarioReader.cpp and RoadManager.cpp: a position on a road the road file does not have.
    pattern:
      /^(?:Error: )?(?:Failed to find road|No matching road with ID|Failed to resolve road id|Position::Set Error: track|OpenDrive::GetTrackIdxById Error: Road id|Failed to lookup road id|Invalid waypoint roadId|Invalid (?:startpos|targetpos) road ID:) (\S+)/,
    targets: (root, match, valueOf) => positionsOnRoad(root, valueOf, match[1]),
  },
  {
    // RoadManager.cpp (Position::SetLanePos and kin): a lane the road does not have where the position is.
    pattern:
      /^(?:Lane id (-?\d+) does not exist on road (\S+)|GetLaneMaterialByS: No valid lane (-?\d+) at road (\S+)|Lane section idx \d+ does not exist on road (\S+))/,
    targets: (root, match, valueOf) =>
      match[5] !== undefined
        ? positionsOnRoad(root, valueOf, match[5])
        : positionsOnRoad(root, valueOf, match[2] ?? match[4], match[1] ?? match[3]),
  },
  {
    // ScenarioReader.cpp, printed when Init places no entity (or its actions depend on each other).
    pattern: /to reorder \d+ init actions/,
    targets: (root) => elementsNamed(root, 'Init').map((element) => ({ element })),
  },
  {
    // Storyboard.cpp: "Stopping object <entity> <action> on conflicting <domain> domain(s)".
    pattern: /^Stopping object \S+ (.+) on conflicting/,
    targets: (root, match) =>
      elementsNamed(root, 'Action')
        .filter((element) => attribute(element, 'name')?.value === match[1])
        .map((element) => ({ element, attribute: 'name' })),
  },
  {
    // "cloudState is deprecated in v1.2 ...", "In Precipitation, intensity is deprecated in v1.1 ...".
    pattern: /^(?:In (\w+), )?(\w+) is deprecated/,
    targets: (root, match) =>
      allElements(root)
        .filter((element) => (!match[1] || element.name === match[1]) && attribute(element, match[2]))
        .map((element) => ({ element, attribute: match[2] })),
  },
  {
    pattern: /^Property: color format invalid/,
    targets: (root) =>
      elementsNamed(root, 'Property')
        .filter(
          (element) => attribute(element, 'name')?.value === 'color' && !/^#[0-9a-fA-F]{6}$/.test(attribute(element, 'value')?.value ?? ''),
        )
        .map((element) => ({ element, attribute: 'value' })),
    // esmini skips the property and runs on; CARLA reads this "R,G,B" form, so it is no error of the scenario.
    severity: 'warning',
    note: 'esmini ignores the colour; CARLA accepts the "R,G,B" form',
  },
  {
    // ScenarioReader.cpp parseOrientation: an Orientation with no type (or one esmini does not know), read as the file's version's default.
    pattern: /^(No|Invalid) orientation type specified/,
    targets: (root, match, valueOf) =>
      elementsNamed(root, 'Orientation')
        .filter((element) => {
          const type = valueOf(element, 'type');
          return match[1] === 'No' ? type === undefined || type === '' : type !== 'relative' && type !== 'absolute' && type !== undefined;
        })
        .map((element) => (match[1] === 'No' ? { element } : { element, attribute: 'type' })),
  },
  {
    pattern: /^(?:Invalid Dynamics shape: (\S+)|Dynamics shape (\S+) unexpected)/,
    targets: (root, match) =>
      allElements(root)
        .filter((element) => attribute(element, 'dynamicsShape')?.value === (match[1] ?? match[2]))
        .map((element) => ({ element, attribute: 'dynamicsShape' })),
  },
  {
    // ScenarioReader.cpp parseOSCPrivateAction / parseOSCControllerAction: an ActivateControllerAction where the file's version does not put it.
    pattern: /^In OSC 1\.\d ActivateControllerAction should be placed under (ControllerAction|PrivateAction)/,
    targets: (root, match) =>
      elementsNamed(root, 'ActivateControllerAction')
        .filter((element) => element.parent !== undefined && element.parent.name !== match[1])
        .map((element) => ({ element })),
  },
  {
    // ScenarioReader.cpp (TimeHeadwayCondition, TimeToCollisionCondition...): esmini's own spelling.
    pattern: /^(\w+) attribute is depricated/,
    targets: (root, match) =>
      allElements(root)
        .filter((element) => attribute(element, match[1]))
        .map((element) => ({ element, attribute: match[1] })),
  },
  {
    // ScenarioReader.cpp parseDynamicConstraints: a limit beyond the vehicle's Performance (or below a small number), which esmini replaces; the constraints with that value, else any with the attribute.
    pattern:
      /^parseDynamicConstraints: (?:(\w+) value (\S+) exceeds object performance value|Unexpected small (\w+) value: (\S+),|Ignoring unexpected attribute (\w+))/,
    targets: (root, match, valueOf) => {
      const name = match[1] ?? match[3] ?? match[5];
      const written = elementsNamed(root, 'DynamicConstraints').filter((element) => attribute(element, name));
      const value = match[2] ?? match[4];
      const atValue =
        value === undefined ? [] : written.filter((element) => Math.abs(Number(valueOf(element, name)) - Number(value)) < 0.01);
      return (atValue.length > 0 ? atValue : written).map((element) => ({ element, attribute: name }));
    },
  },
  {
    // ScenarioReader.cpp: a LongitudinalDistanceAction (trailing) or LateralDistanceAction ('any') of a 1.1+ file without displacement.
    pattern: /^displacement attribute missing, setting default (trailingReferencedEntity|'any')/,
    targets: (root, match) =>
      elementsNamed(root, match[1] === 'trailingReferencedEntity' ? 'LongitudinalDistanceAction' : 'LateralDistanceAction')
        .filter((element) => !attribute(element, 'displacement'))
        .map((element) => ({ element })),
  },
  {
    // OSCEnvironment.cpp SetAtmosphericPressure: a Weather's pressure outside esmini's range, inline or in an Environment entry the scenario uses.
    pattern: /^Atmospheric pressure clamped between/,
    targets: (root, _match, valueOf, _controllerOf, entries) => {
      const outside = (value: string | undefined) => value !== undefined && !(Number(value) >= 80000 && Number(value) <= 120000);
      return [
        ...elementsNamed(root, 'Weather')
          .filter((element) => outside(valueOf(element, 'atmosphericPressure')))
          .map((element) => ({ element, attribute: 'atmosphericPressure' })),
        ...entryTargets(entries, (element) =>
          element.name === 'Weather' && outside(attribute(element, 'atmosphericPressure')?.value)
            ? { element, attribute: 'atmosphericPressure' }
            : undefined,
        ),
      ];
    },
  },
  {
    // Parameters.cpp parseParameterDeclarations: a declaration of a name already declared (a catalog entry's of a scenario's parameter, or twice), whose value now shadows the earlier one.
    pattern: /^Parameter (?:(\S+) redefined\. Previous value|value (\S+) updated from)/,
    targets: (root, match, _valueOf, _controllerOf, entries) => redeclarations(root, entries, match[1] ?? match[2]),
  },
  {
    // ScenarioReader.cpp (storyboard element triggers): a StoryboardElementStateCondition's name that several elements have (a catalog Maneuver used twice), resolved to the first.
    pattern: /^Non unique element name: (.+), picking first occurrence/,
    targets: (root, match, _valueOf, _controllerOf, entries) => {
      const naming = (element: XmlElement) => attribute(element, 'storyboardElementRef')?.value === match[1];
      const inScenario = allElements(root).filter(naming);
      return inScenario.length > 0
        ? inScenario.map((element) => ({ element, attribute: 'storyboardElementRef' }))
        : entryTargets(entries, (element) => (naming(element) ? { element, attribute: 'storyboardElementRef' } : undefined));
    },
  },
  {
    // Parameters.cpp getParameter: a $name no declaration in scope gives, in the scenario or in a catalog entry it uses.
    pattern: /^Failed to resolve parameter \$?(\S+)/,
    targets: (root, match, _valueOf, _controllerOf, entries) => {
      const use = new RegExp(`\\$${match[1].replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}(?!\\w)`);
      const using = (element: XmlElement) => element.attributes.find((each) => use.test(each.value))?.name;
      const inScenario = allElements(root).flatMap((element) => {
        const name = using(element);
        return name ? [{ element, attribute: name }] : [];
      });
      return inScenario.length > 0
        ? inScenario
        : entryTargets(entries, (element) => {
            const name = using(element);
            return name ? { element, attribute: name } : undefined;
          });
    },
  },
  {
    pattern:
      /^(?:Unexpected XML element|Unsupported element type|Unexpected child element|Unsupported global action|Unsupported EnvironmentAction|Unexpected property element): (\w+)/,
    targets: (root, match) => elementsNamed(root, match[1]).map((element) => ({ element })),
  },
];

/** What an unplaced message says of its place: esmini's words name no element or file of the scenario, so it stands at the file's start. */
export const UNPLACED_NOTE = "esmini's message names no element or file of the scenario; shown at the start of the file run";

/** Attributes whose values name things: a message quoting such a value is about that element. */
const NAMING_ATTRIBUTES = ['name', 'entityRef', 'storyboardElementRef', 'masterEntityRef', 'catalogName', 'entryName'];

/** Targets for a message that quotes a name or a value: elements whose naming attribute, then any attribute, equals a word of it. */
function targetsByWords(root: XmlElement, text: string): Target[] {
  const words = [
    ...new Set(text.split(/[\s,;:()'"{}[\]]+|\.(?=\s|$)/).filter((word) => word.length > 1 && !/^[-+]?\d+(\.\d+)?$/.test(word))),
  ];
  const wordSet = new Set(words);
  // Storyboard elements first: an entity's name also appears in messages about its actions.
  const storyboard = root.children.find((element) => element.name === 'Storyboard');
  const elements = storyboard
    ? [
        ...descendants(storyboard),
        root,
        ...descendants(root).filter((element) => element.start < storyboard.start || element.start >= storyboard.end),
      ]
    : allElements(root);
  for (const naming of NAMING_ATTRIBUTES) {
    const found = elements
      .filter((element) => wordSet.has(attribute(element, naming)?.value ?? ''))
      .map((element) => ({ element, attribute: naming }));
    if (found.length > 0) return found;
  }
  // Else the first word of the message that is some attribute's value ("Invalid priority: sometimes").
  for (const word of words) {
    const found: Target[] = [];
    for (const element of elements) {
      const match = element.attributes.find(
        (candidate: XmlAttribute) => candidate.value === word && candidate.name !== PARAMETER_ATTRIBUTES,
      );
      if (match) found.push({ element, attribute: match.name });
    }
    if (found.length > 0) return found;
  }
  return [];
}

/**
 * Where the value of a flattened element's attribute was written: the ParameterReference that
 * overrode it on the way in, else the attribute in the file the element was copied from.
 */
function valueOrigin(
  source: FlatSource,
  element: XmlElement,
  name: string | undefined,
): { source: FlatSource; element: XmlElement; attribute: XmlAttribute | undefined } {
  const insertion =
    source.model !== source.original
      ? source.insertions.find((candidate) => element.start >= candidate.start && element.end <= candidate.end)
      : undefined;
  const copy = insertion ? source.model?.groups.find((group) => group.element.start === insertion.start)?.element : undefined;
  const original = insertion?.group.target?.element;
  const counterpart = copy && original ? [original, ...descendants(original)][[copy, ...descendants(copy)].indexOf(element)] : undefined;
  if (!insertion?.link.source || !counterpart || name === undefined) {
    const origin = originOf(source, element);
    return { ...origin, attribute: name === undefined ? undefined : attribute(origin.element, name) };
  }
  for (const [target, parameter] of insertion.group.plan?.applied ?? []) {
    if (target.element === counterpart && target.attributeName === name)
      return { source, element: parameter.element, attribute: parameter.valueAttribute };
  }
  return valueOrigin(insertion.link.source, counterpart, name);
}

function rangeOf(source: FlatSource, target: Target): { source: SourceRef; range: Range } | undefined {
  if (target.file) {
    const found = target.attribute ? attribute(target.element, target.attribute) : undefined;
    const [start, end] = found ? [found.valueStart, found.valueEnd] : [target.element.start + 1, target.element.nameEnd];
    return { source: target.file.ref, range: target.file.document.lines.range(start, end) };
  }
  const origin = valueOrigin(source, target.element, target.attribute);
  const model = origin.source.original ?? origin.source.model;
  if (!model) return undefined;
  // An attribute added by flattening (no such attribute in the source) falls back to the tag.
  const [start, end] = origin.attribute
    ? [origin.attribute.valueStart, origin.attribute.valueEnd]
    : [origin.element.start + 1, origin.element.nameEnd];
  if (end > model.document.text.length) return undefined;
  return { source: origin.source.ref, range: model.document.lines.range(start, end) };
}

/**
 * esmini's words with the run's private folder (`runFolder`, where the run's copy of the scenario lies, removed after the
 * run) named as what it stands for: a file `copies` names (the scenario's copy, a package file's copy) as that file, any other
 * path in it as from `scenarioFolder`, the folder the scenario's own relative paths start from, where esmini run on the
 * original would have looked.
 */
export function withoutRunFolder(
  text: string,
  runFolder: string,
  scenarioFolder: string,
  copies: ReadonlyMap<string, string>,
  exists: (file: string) => boolean = fs.existsSync,
  /** The folder inside `runFolder` that stands for `scenarioFolder` (a worker's job lays the scenario's folder out deeper); `runFolder` itself by default. */
  standsFor: string = runFolder,
): string {
  if (!text.includes(runFolder)) return text;
  const escaped = runFolder.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
  const reached: string[] = [];
  const said = text.replace(new RegExp(`${escaped}(?=$|[\\/\\s,;'"()])([\\/][^\\s,;'"()]*)?`, 'g'), (_found, rest: string | undefined) => {
    const inside = path.resolve(runFolder, (rest ?? '').replace(/^[\\/]/, ''));
    const copy = copies.get(inside);
    if (copy !== undefined) return copy;
    const original = path.resolve(scenarioFolder, path.relative(standsFor, inside));
    if (inside !== path.resolve(runFolder) && exists(original)) reached.push(original);
    return original;
  });
  // The run's copy lies elsewhere: a path esmini missed from there may be there beside the scenario itself.
  return reached.length === 0
    ? said
    : `${said} [${reached.join(', ')} exists: esmini ran a copy of the scenario in a private folder and looked from there; esmini run on the scenario itself finds it]`;
}

/**
 * Places esmini's messages on the source lines they come from: the flattened element they are
 * about (by a rule for messages that name nothing, else by a name or value they quote), followed
 * back through the flattener's provenance. Repeats of one message are counted once per place.
 */
/**
 * How a message of esmini's log counts: its rule's severity where one is set (esmini logs a colour it skips as an error,
 * and runs on), else esmini's own level. One answer for `run`, which places the message, and for a batch's rows, which do not.
 */
export function esminiMessageSeverity(message: Pick<EsminiLogMessage, 'level' | 'text'>): 'error' | 'warning' {
  const rule = RULES.find((candidate) => candidate.pattern.test(message.text));
  return rule?.severity ?? (message.level === 'error' ? 'error' : 'warning');
}

export function mapEsminiMessages(messages: EsminiLogMessage[], source: FlatSource, main: SourceRef): EsminiProblem[] {
  const document = (source.model ?? source.original)?.document;
  const root = document?.root;
  const evaluator = document ? new Evaluator(semanticModelOf(document)) : undefined;
  const valueOf: ValueOf = (element, name) => {
    const found = attribute(element, name);
    return found ? (evaluator?.textOf(element, found) ?? found.value) : undefined;
  };
  // A CatalogReference's entry, where the file's semantics were read from this document (a plain scenario's).
  const references = source.semantics?.model.document === document ? (source.semantics?.catalogs.references ?? []) : [];
  const controllerOf: ControllerOf = (element) =>
    element.name === 'Controller' ? element : references.find((reference) => reference.reference.element === element)?.entry?.element;
  // The entries the references use, then the other entries of their catalogs (a TrafficSwarmAction reads every vehicle).
  const entries: UsedEntry[] = [
    ...references.flatMap(({ entry }) => (entry ? [entry] : [])),
    ...references.flatMap(({ catalogs }) => catalogs[0]?.entries ?? []),
  ].map((entry) => ({ entry: entry.element, file: { ref: entry.file.ref, document: entry.file.model.document } }));
  const seenText = new Map<string, number>();
  const problems = new Map<string, EsminiProblem>();
  for (const message of messages) {
    const occurrence = seenText.get(message.text) ?? 0;
    seenText.set(message.text, occurrence + 1);
    let targets: Target[] = [];
    let rule: MessageRule | undefined;
    if (root) {
      for (const candidate of RULES) {
        const match = candidate.pattern.exec(message.text);
        if (match) {
          rule = candidate;
          targets = candidate.targets(root, match, valueOf, controllerOf, entries);
          break;
        }
      }
      if (targets.length === 0) targets = targetsByWords(root, message.text);
    }
    const target = targets.length > 0 ? targets[Math.min(occurrence, targets.length - 1)] : undefined;
    const place = target ? rangeOf(source, target) : undefined;
    const severity = esminiMessageSeverity(message);
    const problem: EsminiProblem = {
      source: place?.source ?? main,
      range: place?.range ?? { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } },
      severity,
      message: message.text,
      time: message.time,
      logLine: message.logLine,
      count: 1,
      located: place !== undefined,
      ...(rule?.note ? { note: rule.note } : place === undefined ? { note: UNPLACED_NOTE } : {}),
    };
    const key = `${problem.source.disk}|${problem.source.entries.join('/')}|${problem.range.start.line}|${problem.range.start.character}|${problem.message}`;
    const known = problems.get(key);
    if (known) known.count++;
    else problems.set(key, problem);
  }
  return [...problems.values()];
}
