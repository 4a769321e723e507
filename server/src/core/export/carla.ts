/**
 * Export for CARLA's ScenarioRunner: one plain OpenSCENARIO 1.0 file that ScenarioRunner loads and builds,
 * and a report of every loss (what cannot be kept, where it was written, what ScenarioRunner does instead).
 *
 * The steps: flatten (modular mains and packages), evaluate every `$name` and `${...}` (ScenarioRunner
 * resolves them in a few places only), inline catalog entries (its catalog file and naming rules), write the
 * 1.0 header, map 1.1-1.3 forms to 1.0 where the meaning is kept (./carlaRules.ts), mark the ego, map
 * entity names to CARLA blueprints, and name the road as a CARLA town or an `.xodr` path from the output's
 * folder. What is left outside the 1.0 schema is dropped at the smallest unit (an attribute, a condition, an
 * action) and reported; a file whose meaning would be lost entirely is refused.
 */
import { expressionMessage } from '../diagnostics/expressionWords';
import * as path from 'node:path';
import type { FlatSource, PackagedFile } from '../flatten/types';
import { geoToRoad, RoadXY } from '../opendrive/geo';
import { MAX_ROAD_FILE_BYTES, parseOpenDrive, RoadNetwork } from '../opendrive/road';
import { formatProblem, Problem } from '../problems';
import { locateRoadFile, logicFileOf } from '../semantics/roadFiles';
import { STORYBOARD_ELEMENT_NAMES, STORYBOARD_ELEMENT_TYPES } from '../semantics/storyboard';
import { schemaFindingWords } from '../diagnostics/schemaFindings';
import { checkSchema } from '../schema/validate';
import { assignmentsOf, CatalogLoader } from '../semantics/catalogs';
import { Evaluator } from '../semantics/evaluator';
import { semanticModelOf } from '../semantics/model';
import type { SemanticContext as DocumentSemantics } from '../semantics/checks/types';
import { formatValue } from '../semantics/values';
import { displayRef, ScenarioStore, SourceError, SourceRef } from '../sources';
import { decodeUtf8 } from '../text';
import { parseXml, XmlDocument, XmlElement } from '../xml';
import {
  CarlaRelease,
  CARLA_TOWNS,
  closestTown,
  DEFAULT_VEHICLE_BLUEPRINTS,
  DEFAULT_WALKER_BLUEPRINT,
  EGO_PROPERTY,
  egoByName,
  isCarlaBlueprint,
  namedAsEgo,
  SR_CONFIGURATION,
  SR_SCHEMA,
  unknownBlueprintProblem,
} from './carlaFacts';
import { movedAlongByScenarioRunner } from './laneOffsets';
import { applyCarlaRules, CarlaLoss, geoPositionDegrees, LossSink, tidyEmptyContainers } from './carlaRules';
import {
  allNodes,
  ancestor,
  appendChild,
  attr,
  child,
  childrenNamed,
  documentOf,
  makeNode,
  named,
  Node,
  nodeFromXml,
  Place,
  removeAttr,
  removeChildren,
  removeNode,
  replaceNode,
  serialize,
  setAttr,
} from './tree';

export type { CarlaLoss } from './carlaRules';
export { CARLA_RELEASES, CARLA_TOWNS, isCarlaRelease } from './carlaFacts';
export type { CarlaRelease } from './carlaFacts';

export interface CarlaExportOptions {
  /** The ScenarioRunner release whose facts apply (0.9.16 by default). */
  release?: CarlaRelease;
  /** Where the export will be written (absolute): the road's path is written relative to its folder (SPEC 11.6). */
  outputPath: string;
  /** Entity names (a Vehicle's `name`, a Pedestrian's `model` or `name`) to CARLA blueprints; wins over the defaults. */
  blueprints?: Readonly<Record<string, string>>;
  /** The road instead of the scenario's LogicFile: a CARLA town name or an `.xodr` path (absolute, or from the working directory of the caller). */
  road?: string;
  /** The entity ScenarioRunner is to take as the ego (a Vehicle); else the one named ego/hero, else the first vehicle. */
  ego?: string;
  /** Folders where a road file is looked for when it is not beside the scenario (as `run --road-path`). */
  roadFolders?: readonly string[];
  /** Flatten past overrides that cannot apply (unknown keys, attributes without default), as the original tool did: each is named as dropped. */
  force?: boolean;
}

/** Wrong options (an unknown blueprint, a town that does not exist): the caller's mistake, not the scenario's. */
export class CarlaExportOptionError extends Error {}

export interface CarlaExport {
  /** The 1.0 scenario to write; undefined when the export is refused. */
  text: string | undefined;
  /** Everything not kept as written, at its source (refusals too, `kind: 'refused'`). */
  losses: CarlaLoss[];
  /** Why nothing is written, in one sentence; undefined when `text` is set. */
  refused: string | undefined;
  /** Errors that stopped flattening the input (a modular main whose references are broken). */
  problems: Problem[];
  /** The road the export names: a CARLA town, or the `.xodr` file on disk (absolute; for a packaged road its copy in `files`). */
  road: { town: string } | { file: string } | undefined;
  /** Files to write beside the export, which names them: the copy of a road packed with the scenario, in `<output name>.files/` as flatten writes it. */
  files?: PackagedFile[];
  /** The entity marked as ScenarioRunner's ego. */
  ego: string | undefined;
  /**
   * Where element N of `text` (in document order) was written in the sources (an element the export added
   * stands at its nearest written ancestor): a message about the export's element N belongs there.
   */
  placeAt?: (index: number) => Place | undefined;
}

/**
 * Exports a scenario file, modular main, unpacked folder or package (`main`, as the flattener takes it) for
 * ScenarioRunner. The store reads the sources (the editor's store sees unsaved text).
 */
export async function exportForCarla(store: ScenarioStore, main: SourceRef, options: CarlaExportOptions): Promise<CarlaExport> {
  checkOptions(options);
  // A plain scenario (no ScenarioReference) is exported as written, without a flattening pass that would model it twice.
  if (main.entries.length === 0) {
    let text: string | undefined;
    try {
      text = await store.readText(main);
    } catch (error) {
      if (!(error instanceof SourceError)) throw error;
      return { text: undefined, losses: [], refused: error.message, problems: [], road: undefined, ego: undefined };
    }
    if (!/<ScenarioReference\b/.test(text)) return exportTextForCarla(store, main, text, options);
  }
  // Loaded here: a plain scenario (most exports) needs neither the flattener nor the semantic checks it imports.
  const { Flattener, originOf, OVERRIDE_PROBLEM_CODES } = await import('../flatten');
  const flattened = await new Flattener(store, undefined, { version: 'off' }).flatten(main, { standardOutput: true, force: options.force });
  if (flattened.text === undefined) {
    const errors = flattened.problems.filter((problem) => problem.severity === 'error');
    const first = errors[0] ? formatProblem(errors[0], undefined) : 'the input could not be read';
    return {
      text: undefined,
      losses: errors.map((problem) =>
        problemLoss(problem, 'refused', problem.message, 'nothing can be exported before the input flattens'),
      ),
      refused: `the input cannot be flattened (${errors.length} error${errors.length === 1 ? '' : 's'}; the first: ${first})`,
      problems: errors,
      road: undefined,
      ego: undefined,
    };
  }
  // A plain scenario is exported as written: its relative paths resolve from its folder as esmini and the checks resolve them.
  const source = flattened.source;
  const plain = source.insertions.length === 0 && source.additions.length === 0 && source.original?.document.text;
  const text = plain || flattened.text;
  const exported = await exportTextForCarla(store, main, text, options, plain ? undefined : sourcePlaces(source, originOf));
  // Forced past (--force), an override that cannot apply is one more thing the export does not keep.
  const skipped = flattened.problems.filter((problem) => problem.severity === 'error' && OVERRIDE_PROBLEM_CODES.has(problem.code));
  const skippedLosses = skipped.map((problem) =>
    problemLoss(
      problem,
      'dropped',
      `${problem.message} (skipped: --force)`,
      "the flattened scenario keeps the simple scenario's own value there, as the original Modular2Simple tool did",
    ),
  );
  return { ...exported, losses: [...skippedLosses, ...exported.losses] };
}

/**
 * Exports plain scenario text (a flattened main, one concrete scenario of a distribution) that stands for
 * `ref`: its relative paths start from `ref`'s folder, its losses are placed in `ref` unless `placeOf` knows better.
 */
export async function exportTextForCarla(
  store: ScenarioStore,
  ref: SourceRef,
  text: string,
  options: CarlaExportOptions,
  placeOf?: (element: XmlElement) => Place | undefined,
): Promise<CarlaExport> {
  checkOptions(options);
  const losses: CarlaLoss[] = [];
  const result = (refused: string | undefined, out?: string, extra: Partial<CarlaExport> = {}): CarlaExport => ({
    text: refused === undefined ? out : undefined,
    losses,
    refused,
    problems: [],
    road: undefined,
    ego: undefined,
    ...extra,
  });
  const document = parseXml(text);
  const root = document.root;
  const wellFormed = document.problems.every((problem) => problem.severity !== 'error');
  if (!root || !wellFormed) {
    const first = document.problems[0];
    return result(
      `the file is not well-formed XML${first ? ` (line ${document.lines.positionAt(first.start).line + 1}: ${first.message})` : ''}`,
    );
  }
  const ownPlace = (element: XmlElement): Place => placeIn(ref, document, element);
  const place = (element: XmlElement): Place => placeOf?.(element) ?? ownPlace(element);
  if (root.name !== 'OpenSCENARIO') return result(`the root element is <${root.name}>, not <OpenSCENARIO>`);
  if (root.children.some((each) => each.name === 'ParameterValueDistribution'))
    return result('the file is a ParameterValueDistribution: export one concrete scenario of it (modular2simple export FILE --index I)');
  if (root.children.some((each) => each.name === 'Catalog')) return result('the file is a catalog, not a scenario');
  if (!root.children.some((each) => each.name === 'Storyboard')) return result('the file has no Storyboard');

  // The model, values and catalogs alone: the road rules' signal reading (analyzeDocument parses the road file) has nothing to tell an export.
  const model = semanticModelOf(document);
  const evaluator = new Evaluator(model);
  const semantics: DocumentSemantics = {
    ref,
    model,
    evaluator,
    catalogs: await new CatalogLoader(store).resolve(ref, model, evaluator),
    modular: false,
  };
  const sink = lossSink(losses, (node) => node.place ?? ownPlace(root));
  const unevaluated: { element: XmlElement; name: string; message: string }[] = [];
  const elementNodes = new Map<XmlElement, Node>();
  const fallbacks: { element: XmlElement; name: string; how: string }[] = [];
  const tree = nodeFromXml(document, root, place, (element, index) =>
    evaluatedValue(
      semantics.evaluator,
      element,
      index,
      (message) => unevaluated.push({ element, name: element.attributes[index].name, message }),
      (how) => fallbacks.push({ element, name: element.attributes[index].name, how }),
    ),
  );
  mapElements(root, tree, elementNodes);
  for (const failure of unevaluated) {
    const node = elementNodes.get(failure.element) as Node;
    sink.refuse(
      node,
      `@${failure.name}`,
      `its value cannot be computed (${failure.message})`,
      'ScenarioRunner would fail on it while loading',
    );
  }

  for (const fallback of fallbacks)
    sink.approximated(
      elementNodes.get(fallback.element) as Node,
      `${fallback.element.name}/@${fallback.name}`,
      fallback.how,
      'ScenarioRunner reads the value written',
    );

  inlineCatalogs(semantics, elementNodes, sink);
  await rebasePropertyFiles(tree, ref, options.outputPath, store);
  const catalogLocations = child(tree, 'CatalogLocations');
  if (catalogLocations) removeChildren(catalogLocations);
  for (const leftover of named(tree, 'CatalogReference')) {
    if (ancestor(leftover, 'Entities') && leftover.parent?.name !== 'ScenarioObject') {
      // A catalog entry's own reference (a trailer of a truck): a detail ScenarioRunner has no use for.
      sink.dropped(
        leftover,
        `${leftover.parent?.name ?? ''}/CatalogReference`,
        `the ${leftover.parent?.name ?? 'part'} '${attr(leftover, 'entryName')}' of an inlined entity is dropped`,
        'ScenarioRunner spawns one actor per ScenarioObject and nothing attached to it',
      );
      removeNode(leftover.parent?.name === 'Trailer' ? (leftover.parent as Node) : leftover);
      continue;
    }
    sink.refuse(
      leftover,
      'CatalogReference',
      `catalog '${attr(leftover, 'catalogName')}' entry '${attr(leftover, 'entryName')}' is not found`,
      `ScenarioRunner stops loading at an unknown catalog entry; name the folder of the catalog file that declares '${attr(leftover, 'catalogName')}' in the scenario's CatalogLocations (a Directory of its type's catalog, such as VehicleCatalog), or write the entry inline`,
    );
  }

  const eventsBefore = named(tree, 'Event').length;
  const placedBefore = placedEntities(tree);
  rewriteHeader(tree, ref);
  // A simple scenario exported as it is: `parameterAttributes` marks what a main may override (SPEC), its values are
  // the defaults; ScenarioRunner's 1.0 schema refuses the attribute, and flattening removes it the same way.
  for (const node of allNodes(tree)) removeAttr(node, 'parameterAttributes');
  const { road, copy, townFile } = (await rewriteRoad(store, tree, ref, document, semantics, options, sink)) ?? {};
  const files = copy ? [copy] : [];
  const ego = markEgo(tree, options, sink);
  mapBlueprints(tree, options, sink);
  // Route positions are placed on the road they name: only then is the road file read.
  // Route positions need road lengths, sampled trajectories the heading of a lane an actor starts on, trajectory positions and an Init trajectory's offset (the only one init-starts places) the road their vertices are on, lane changes by time or rate the lanes' widths.
  const needsRoads =
    named(tree, new Set(['RoutePosition', 'GeoPosition', 'Clothoid', 'ClothoidSpline', 'Nurbs', 'TrajectoryPosition'])).length > 0 ||
    named(tree, 'FollowTrajectoryAction').some(
      (action) => Number(attr(action, 'initialDistanceOffset') ?? 0) !== 0 && ancestor(action, 'Init') !== undefined,
    ) ||
    // How far a lane change moves across (laneChanges.ts): a rate needs it, a time is exact with it.
    named(tree, 'LaneChangeActionDynamics').some((dynamics) => ['time', 'rate'].includes(attr(dynamics, 'dynamicsDimension') ?? '')) ||
    // Which way is left for an absolute target lane: the road's traffic rule.
    named(tree, 'AbsoluteTargetLane').length > 0 ||
    // A steady state's target moved back along its lane: the road's length and traffic rule.
    named(tree, new Set(['TargetDistanceSteadyState', 'TargetTimeSteadyState'])).length > 0 ||
    // A LanePosition ScenarioRunner would move along the road, written as the WorldPosition esmini gives it (laneOffsets.ts).
    named(tree, 'LanePosition').some(movedAlongByScenarioRunner) ||
    // The lanes a route drives, written as a trajectory where 0.9.16 crashes on the route (routeTrajectories.ts).
    ((options.release ?? '0.9.16') === '0.9.16' && named(tree, new Set(['AssignRouteAction', 'AcquirePositionAction'])).length > 0);
  const roadFile = road && 'file' in road ? (copy?.bytes ?? road.file) : townFile;
  const roads = roadFile !== undefined && needsRoads ? await readRoads(roadFile, store) : undefined;
  const geoPlaces = new Map<Node, RoadXY | string>();
  for (const position of named(tree, 'GeoPosition')) {
    const degrees = geoPositionDegrees(position);
    if (roads && degrees) geoPlaces.set(position, await geoToRoad(roads, degrees.latitude, degrees.longitude));
  }
  const elementsBefore = storyboardElementKeys(tree);
  const sampledPolylines = new Set<Node>();
  const town = road && 'town' in road ? road.town : undefined;
  applyCarlaRules(tree, { release: options.release ?? '0.9.16', sink, roads, town, geoPlaces, sampledPolylines });
  // Nothing changes the tree after the last schema check.
  const valid = dropOutsideSchema(tree, sink, sampledPolylines);
  reportStatesOfDroppedElements(tree, elementsBefore, sink);

  const placedAfter = placedEntities(tree);
  for (const [entity, privateNode] of placedBefore)
    if (!placedAfter.has(entity))
      sink.refuse(
        privateNode,
        'Init/Private',
        `'${entity}' has no start position left after the drops above`,
        `ScenarioRunner would spawn it at (0, 0, 0) ("was not assigned an initial position", ${SR_CONFIGURATION}:373-377)`,
      );
  if (eventsBefore > 0 && named(tree, 'Event').length === 0)
    sink.refuse(
      child(tree, 'Storyboard') ?? tree,
      'Storyboard',
      `none of its ${eventsBefore} events is left after the drops above`,
      'ScenarioRunner would run nothing of the story',
    );
  const refusals = losses.filter((loss) => loss.kind === 'refused');
  if (refusals.length > 0) return result(refusalSentence(refusals), undefined, { road, ego, files });
  const out = serialize(tree);
  // What is written must be 1.0 as ScenarioRunner's bundled schema reads it; anything left is a bug of a rule, not the user's.
  const schemaErrors = valid
    ? []
    : checkSchema(parseXml(out), { modular: false, version: '1.0' }).findings.filter((finding) => finding.severity === 'error');
  if (schemaErrors.length > 0) {
    const outDocument = parseXml(out);
    const first = schemaErrors[0];
    const line = outDocument.lines.positionAt(first.element.start).line + 1;
    return result(
      `the export would not be valid OpenSCENARIO 1.0 (${SR_SCHEMA}): line ${line} of the export, <${first.element.name}>: ${schemaFindingWords(first).message}`,
      undefined,
      { road, ego, files },
    );
  }
  return result(undefined, out, { road, ego, files, placeAt: placeInDocument(tree) });
}

const PLACING: ReadonlySet<string> = new Set(['Position', 'PositionStart']);

/** The entities whose Init Privates place them (a Position, or a ClothoidSpline's PositionStart), with the first such Private. */
function placedEntities(tree: Node): Map<string, Node> {
  const placed = new Map<string, Node>();
  const init = named(tree, 'Init')[0];
  for (const privateNode of init ? named(init, 'Private') : []) {
    const entity = attr(privateNode, 'entityRef') ?? '';
    if (!placed.has(entity) && named(privateNode, PLACING).length > 0) placed.set(entity, privateNode);
  }
  return placed;
}

/**
 * The place of the node N in document order, which is the order `serialize` writes them in; an added node takes
 * its ancestor's. Worked out when asked (the editor asks for the few elements ScenarioRunner names).
 */
function placeInDocument(tree: Node): (index: number) => Place | undefined {
  const nodes = allNodes(tree);
  return (index) => {
    let at: Node | undefined = nodes[index];
    while (at && !at.place) at = at.parent;
    return at?.place;
  };
}

/** The road file's roads (from disk, or the bytes of a packaged road's copy), or undefined when it cannot be read (the rules then name why a route position stays unconverted). */
async function readRoads(road: string | Uint8Array, store: ScenarioStore): Promise<RoadNetwork | undefined> {
  const bytes = typeof road === 'string' ? await store.host.readFile(road, MAX_ROAD_FILE_BYTES + 1).catch(() => undefined) : road;
  if (!bytes || bytes.byteLength > MAX_ROAD_FILE_BYTES) return undefined;
  const network = parseOpenDrive(decodeUtf8(bytes));
  return network.roads.length > 0 ? network : undefined;
}

function problemLoss(problem: Problem, kind: CarlaLoss['kind'], what: string, carla: string): CarlaLoss {
  return {
    kind,
    file: displayRef(problem.source, undefined),
    line: problem.range.start.line + 1,
    element: problem.subject?.element ?? (problem.code === 'unknown-key' || problem.code === 'no-default' ? 'ParameterReference' : 'input'),
    what,
    carla,
    source: problem.source,
    range: problem.range,
  };
}

/** The path of an element by name and index among same-named siblings: the same in the rendered output and the flattener's model of it. */
function pathOf(element: XmlElement): string {
  const parts: string[] = [];
  for (let at: XmlElement | undefined = element; at; at = at.parent) {
    const siblings = at.parent ? at.parent.children.filter((each) => each.name === at?.name) : [at];
    parts.push(`${at.name}[${siblings.indexOf(at)}]`);
  }
  return parts.reverse().join('/');
}

/** Where each element of a rendered flattened text was written: its counterpart in the flattener's model, followed to the file it was copied from (originOf). */
function sourcePlaces(source: FlatSource, originOf: typeof import('../flatten').originOf): (element: XmlElement) => Place | undefined {
  let byPath: Map<string, XmlElement> | undefined;
  return (element) => {
    if (!source.model) return undefined;
    if (!byPath) {
      byPath = new Map();
      const stack = source.model.document.root ? [source.model.document.root] : [];
      while (stack.length > 0) {
        const next = stack.pop() as XmlElement;
        byPath.set(pathOf(next), next);
        stack.push(...next.children);
      }
    }
    const counterpart = byPath.get(pathOf(element));
    if (!counterpart) return undefined;
    const origin = originOf(source, counterpart);
    const originDocument = (origin.source.original ?? origin.source.model)?.document;
    return originDocument ? placeIn(origin.source.ref, originDocument, origin.element) : undefined;
  };
}

/** What to do about a road the export cannot name, for the command line and the editor alike (the editor has no --road). */
const ROAD_REMEDY =
  `write a CARLA town (${CARLA_TOWNS[0]} ... ${CARLA_TOWNS.at(-1)}) or the path of an .xodr file in the LogicFile, or add the folder ` +
  'that holds the .xodr to the road path (--road-path DIR, the modular2simple.esmini.roadPath setting); on the command line, ' +
  '--road TOWN|FILE.xodr replaces the road';

function checkOptions(options: CarlaExportOptions): void {
  for (const [name, blueprint] of Object.entries(options.blueprints ?? {})) {
    const problem = unknownBlueprintProblem(name, blueprint);
    if (problem) throw new CarlaExportOptionError(problem);
  }
  if (options.road !== undefined && !options.road.toLowerCase().endsWith('.xodr') && !CARLA_TOWNS.includes(options.road)) {
    const town = closestTown(options.road);
    throw new CarlaExportOptionError(
      `--road '${options.road}' is neither a CARLA town (${CARLA_TOWNS.join(', ')}) nor an .xodr file` +
        (town ? `; did you mean '${town}'?` : ''),
    );
  }
}

function placeIn(ref: SourceRef, document: XmlDocument, element: XmlElement): Place {
  return { source: ref, range: { start: document.lines.positionAt(element.start), end: document.lines.positionAt(element.startTagEnd) } };
}

function mapElements(element: XmlElement, node: Node, into: Map<XmlElement, Node>): void {
  into.set(element, node);
  element.children.forEach((each, index) => mapElements(each, node.children[index], into));
}

/** How a value that the standard cannot compute was computed after all, for the loss report. */
type Fallback = (how: string) => void;

/**
 * An attribute's value to write: itself when literal, else its `$name` or `${...}` evaluated by the standard;
 * where the standard gives none, a catalog entry's `$name` from the scenario's own parameters, else esmini's
 * reading (the files were written for esmini), each named by `fellBack`; `failed` when nothing gives one.
 */
function evaluatedValue(
  evaluator: Evaluator,
  element: XmlElement,
  index: number,
  failed: (message: string) => void,
  fellBack: Fallback,
  scenario?: DocumentSemantics,
): string {
  const attribute = element.attributes[index];
  const site = evaluator.model.siteOf.get(attribute);
  if (!site || site.element !== element) return attribute.value;
  const value = evaluator.standardValue(site);
  if (value.ok) return formatValue(value.value);
  const global = scenario && site.form.kind === 'parameter' ? scenario.model.root?.byName.get(site.form.name) : undefined;
  if (scenario && global) {
    const globalValue = scenario.evaluator.declarationValue(global);
    if (globalValue.ok) {
      fellBack(
        `$${global.name} is not declared in the catalog entry: the scenario's own ${global.name} = ${formatValue(globalValue.value)} is used, as esmini does`,
      );
      return formatValue(globalValue.value);
    }
  }
  const esmini = evaluator.esminiSiteText(site);
  if (esmini.ok) {
    fellBack(
      `${attribute.value} is written as esmini computes it, '${esmini.text}' (the standard gives no value: ${value.errors[0] ? expressionMessage(value.errors[0]) : 'an error'})`,
    );
    return esmini.text;
  }
  failed(value.errors[0] ? expressionMessage(value.errors[0]) : 'unknown error');
  return attribute.value;
}

function lossSink(losses: CarlaLoss[], placeOf: (node: Node) => Place): LossSink {
  // A catalog entry used twice is inlined twice: its losses are named once.
  const seen = new Set<string>();
  const add = (kind: CarlaLoss['kind'], node: Node, element: string, what: string, carla: string): void => {
    const place = placeOf(node);
    const key = [kind, displayRef(place.source, undefined), place.range.start.line, place.range.start.character, element, what].join('\0');
    if (seen.has(key)) return;
    seen.add(key);
    losses.push({
      kind,
      file: displayRef(place.source, undefined),
      line: place.range.start.line + 1,
      element,
      what,
      carla,
      source: place.source,
      range: place.range,
    });
  };
  return {
    dropped: (node, element, what, carla) => add('dropped', node, element, what, carla),
    approximated: (node, element, what, carla) => add('approximated', node, element, what, carla),
    refuse: (node, element, what, carla) => add('refused', node, element, what, carla),
  };
}

function refusalSentence(refusals: CarlaLoss[]): string {
  const first = refusals[0];
  const more = refusals.length > 1 ? ` (and ${refusals.length - 1} more)` : '';
  return `${first.file}:${first.line}: <${first.element}> ${first.what}: ${first.carla}${more}`;
}

/** Each CatalogReference replaced by its entry, the entry's parameters evaluated with the reference's values (SR_CONFIGURATION `_load_catalogs` names catalogs by file and type). */
function inlineCatalogs(semantics: DocumentSemantics, nodes: Map<XmlElement, Node>, sink: LossSink): void {
  for (const resolution of semantics.catalogs.references) {
    const node = nodes.get(resolution.reference.element);
    const entry = resolution.entry;
    if (!node || !entry) continue;
    const entryEvaluator = new Evaluator(entry.file.model, assignmentsOf(resolution.reference, semantics.evaluator));
    const entryDocument = entry.file.model.document;
    const inlined = nodeFromXml(
      entryDocument,
      entry.element,
      (element) => placeIn(entry.file.ref, entryDocument, element),
      (element, index) =>
        evaluatedValue(
          entryEvaluator,
          element,
          index,
          (message) =>
            sink.refuse(
              node,
              'CatalogReference',
              `the value of ${element.name}/@${element.attributes[index].name} in catalog entry '${entry.name}' cannot be computed (${message})`,
              'ScenarioRunner would fail on it while loading',
            ),
          (how) =>
            sink.approximated(
              node,
              `${element.name}/@${element.attributes[index].name}`,
              `in catalog entry '${entry.name}': ${how}`,
              'ScenarioRunner reads the value written',
            ),
          semantics,
        ),
    );
    for (const declarations of childrenNamed(inlined, 'ParameterDeclarations')) removeNode(declarations);
    replaceNode(node, inlined);
  }
}

/**
 * Each relative `Properties/File` path (a controller's configuration, a model), an inlined catalog entry's too, written from
 * the output's folder (SPEC 11.6). esmini reads one from the folder of the scenario it runs, a catalog entry's too, never the
 * catalog's (ScenarioReader.cpp parseOSCObjectController): here `ref`'s. Only a path that names a file from there is rebased.
 */
async function rebasePropertyFiles(tree: Node, ref: SourceRef, outputPath: string, store: ScenarioStore): Promise<void> {
  const from = path.dirname(ref.disk);
  const to = path.dirname(path.resolve(outputPath));
  if (from === to) return;
  for (const file of named(tree, 'File')) {
    const value = attr(file, 'filepath')?.trim();
    if (file.parent?.name !== 'Properties' || !value || path.isAbsolute(value) || value.includes('$')) continue;
    const disk = path.resolve(from, value);
    if ((await store.host.kind(disk)) === 'file') setAttr(file, 'filepath', path.relative(to, disk).split(path.sep).join('/'));
  }
}

function rewriteHeader(tree: Node, ref: SourceRef): void {
  const header = child(tree, 'FileHeader');
  if (!header) return;
  // ScenarioRunner names the scenario by the description and stops without one (SR_CONFIGURATION _validate_result).
  if (!attr(header, 'description')?.trim())
    setAttr(header, 'description', path.basename(ref.entries.at(-1) ?? ref.disk).replace(/\.xosc$/i, ''));
  setAttr(header, 'revMajor', '1');
  setAttr(header, 'revMinor', '0');
  // The 1.1+ License and Properties of a header carry no behaviour.
  removeChildren(header);
}

async function rewriteRoad(
  store: ScenarioStore,
  tree: Node,
  ref: SourceRef,
  document: XmlDocument,
  semantics: DocumentSemantics,
  options: CarlaExportOptions,
  sink: LossSink,
): Promise<{ road: CarlaExport['road']; copy?: PackagedFile; townFile?: string } | undefined> {
  const network = child(tree, 'RoadNetwork');
  const logic = network ? child(network, 'LogicFile') : undefined;
  const header = child(tree, 'FileHeader');
  let road: CarlaExport['road'];
  let copy: PackagedFile | undefined;
  let townFile: string | undefined;
  if (options.road !== undefined) {
    if (CARLA_TOWNS.includes(options.road)) road = { town: options.road };
    else {
      const file = path.resolve(options.road);
      if ((await store.host.kind(file)) !== 'file') throw new CarlaExportOptionError(`--road ${options.road}: no such .xodr file`);
      road = { file };
    }
  } else {
    const written = logicFileOf(document, semantics.evaluator);
    if (!written || !logic) {
      sink.refuse(
        network ?? tree,
        'RoadNetwork',
        'names no road (no LogicFile)',
        `ScenarioRunner stops with "CARLA level not defined" (${SR_CONFIGURATION} _validate_result); ${ROAD_REMEDY}`,
      );
      return undefined;
    }
    if (CARLA_TOWNS.includes(written.filepath)) {
      road = { town: written.filepath };
      // The town's OpenDRIVE where esmini finds it (a file of the town's name in the road path): its lanes, for the rules that plan on them.
      const folders = [...(options.roadFolders ?? []), ...(semantics.roadFile?.folders ?? [])];
      const located = await locateRoadFile(store, ref, document, semantics.evaluator, folders, store.host);
      if (located?.resolved) townFile = located.resolved;
    } else {
      // Where run and check look (core/semantics/roadFiles.ts locateRoadFile): the road folders, then those the check searched (its catalog folders).
      const folders = [...(options.roadFolders ?? []), ...(semantics.roadFile?.folders ?? [])];
      const located = await locateRoadFile(store, ref, document, semantics.evaluator, folders, store.host);
      const found = located ?? { resolved: undefined, packaged: undefined, candidates: [] };
      const name = found.resolved ?? found.packaged?.entries.at(-1);
      if (!name || !name.toLowerCase().endsWith('.xodr')) {
        const town = written.filepath.toLowerCase().endsWith('.xodr') ? undefined : closestTown(written.filepath);
        sink.refuse(
          logic,
          'LogicFile',
          `names the road '${written.filepath}', which is neither a CARLA town nor a readable .xodr file (looked for at ${found.candidates.join(', ')})` +
            (town ? `; did you mean the town '${town}'?` : ''),
          `ScenarioRunner loads it as a CARLA map and fails (${SR_CONFIGURATION} _set_carla_town); ${ROAD_REMEDY}`,
        );
        return undefined;
      }
      if (found.packaged) {
        // A road packed with the scenario: its copy goes beside the export, where flatten puts it (flatten/rebase.ts).
        const { packagedFilesFolder } = await import('../flatten/rebase');
        const bytes = await store.readBytes(found.packaged);
        const file = path.join(path.dirname(options.outputPath), packagedFilesFolder(options.outputPath), ...name.split('/'));
        copy = { path: file, bytes };
        road = { file };
      } else road = { file: name };
    }
  }
  if (!network || !logic) {
    const roadNetwork = network ?? appendChild(tree, makeNode('RoadNetwork'), child(tree, 'Entities'));
    appendChild(roadNetwork, makeNode('LogicFile', [['filepath', '']]), roadNetwork.children[0]);
  }
  const logicNode = child(child(tree, 'RoadNetwork') as Node, 'LogicFile') as Node;
  if ('town' in road) setAttr(logicNode, 'filepath', road.town);
  else {
    const relative = path.relative(path.dirname(options.outputPath), road.file).split(path.sep).join('/');
    setAttr(logicNode, 'filepath', relative || path.basename(road.file));
  }
  const networkNode = child(tree, 'RoadNetwork') as Node;
  const sceneGraph = child(networkNode, 'SceneGraphFile');
  // ScenarioRunner ignores the scene graph (it draws CARLA's own map); its path would not resolve from the output's folder.
  if (sceneGraph) removeNode(sceneGraph);
  // An empty path (ScenarioRunner's own examples write one) names nothing to lose.
  if (sceneGraph && attr(sceneGraph, 'filepath')) {
    sink.dropped(
      sceneGraph,
      'SceneGraphFile',
      'is dropped',
      `ScenarioRunner never reads it: it takes the road from RoadNetwork/LogicFile only (${SR_CONFIGURATION}:164-165) and draws CARLA's own map`,
    );
  }
  const description = header ? attr(header, 'description') : undefined;
  if (header && description?.startsWith('CARLA:') && 'file' in road) {
    setAttr(header, 'description', description.slice('CARLA:'.length).trimStart() || 'scenario');
    sink.approximated(
      header,
      'FileHeader',
      "the description's 'CARLA:' prefix is removed: the road is an .xodr file in OpenDRIVE coordinates",
      `with the prefix ScenarioRunner would read positions in CARLA's left-handed coordinates (${SR_CONFIGURATION} _set_scenario_name)`,
    );
  }
  return { road, copy, townFile };
}

function egoProperty(properties: Node): boolean {
  return childrenNamed(properties, 'Property').some(
    (property) => attr(property, 'name') === EGO_PROPERTY.name && attr(property, 'value') === EGO_PROPERTY.value,
  );
}

/** Marks one vehicle with `<Property name="type" value="ego_vehicle"/>` as ScenarioRunner reads it (SR_CONFIGURATION `_extract_vehicle_information`). */
function markEgo(tree: Node, options: CarlaExportOptions, sink: LossSink): string | undefined {
  const entities = child(tree, 'Entities');
  const objects = entities ? childrenNamed(entities, 'ScenarioObject') : [];
  const vehicleOf = (object: Node): Node | undefined => allNodes(object).find((each) => each.name === 'Vehicle');
  const vehicles = objects.filter((object) => vehicleOf(object));
  if (options.ego !== undefined) {
    const chosen = objects.find((object) => attr(object, 'name') === options.ego);
    if (!chosen)
      throw new CarlaExportOptionError(
        `--ego ${options.ego}: the scenario has no entity of that name (it has ${objects.map((object) => attr(object, 'name')).join(', ') || 'none'})`,
      );
    if (!vehicleOf(chosen)) throw new CarlaExportOptionError(`--ego ${options.ego}: ScenarioRunner takes only a Vehicle as the ego`);
  }
  const already = vehicles.filter((object) => allNodes(object).some((each) => each.name === 'Properties' && egoProperty(each)));
  const byName = egoByName(vehicles.map((object) => attr(object, 'name') ?? ''));
  const chosen =
    (options.ego !== undefined ? vehicles.find((object) => attr(object, 'name') === options.ego) : undefined) ??
    (already.length > 0 ? already[0] : undefined) ??
    vehicles.find((object) => (attr(object, 'name') ?? '') === byName);
  if (!chosen) {
    sink.approximated(
      entities ?? tree,
      'Entities',
      'no vehicle to mark as the ego',
      'ScenarioRunner runs it without an ego vehicle ("No ego vehicles defined in scenario")',
    );
    return undefined;
  }
  const name = attr(chosen, 'name') as string;
  if (already.length === 0 && !namedAsEgo(name) && options.ego === undefined)
    sink.approximated(
      chosen,
      'ScenarioObject',
      `'${name}' is taken as the ego (the first vehicle; none is named ego or hero)`,
      'ScenarioRunner spawns it as the ego vehicle (choose another with --ego NAME)',
    );
  for (const object of vehicles) {
    const vehicle = vehicleOf(object) as Node;
    const properties = child(vehicle, 'Properties') ?? appendChild(vehicle, makeNode('Properties'));
    for (const property of childrenNamed(properties, 'Property'))
      if (attr(property, 'name') === EGO_PROPERTY.name && attr(property, 'value') === EGO_PROPERTY.value && object !== chosen)
        removeNode(property);
    if (object === chosen && !egoProperty(properties))
      appendChild(
        properties,
        makeNode('Property', [
          ['name', EGO_PROPERTY.name],
          ['value', EGO_PROPERTY.value],
        ]),
        properties.children.find((each) => each.name === 'File'),
      );
  }
  return name;
}

/** A vehicle's BoundingBox, Performance and Axles are never read: named once per export, at the first vehicle, not once per vehicle. */
function vehicleShapesUnused(vehicles: readonly Node[], sink: LossSink): void {
  if (vehicles.length === 0) return;
  const names = vehicles.map((vehicle) => `'${attr(vehicle, 'name') ?? ''}'`);
  sink.approximated(
    vehicles[0],
    'Vehicle/BoundingBox',
    `the BoundingBox, Performance and Axles of ${vehicles.length === 1 ? `the vehicle ${names[0]}` : `the ${vehicles.length} vehicles (${names.join(', ')})`} are kept as written, but not used`,
    `ScenarioRunner reads a Vehicle's name, vehicleCategory and its type and color Properties only: CARLA spawns the blueprint with its own size, axles and performance (${SR_CONFIGURATION}:294-316)`,
  );
}

/** Vehicle `name`s and Pedestrian `model`s as CARLA blueprints: the user's table, else kept when a blueprint, else by category. */
function mapBlueprints(tree: Node, options: CarlaExportOptions, sink: LossSink): void {
  const table = options.blueprints ?? {};
  const chosen = (written: string | undefined): string | undefined =>
    written !== undefined && Object.hasOwn(table, written) ? table[written] : undefined;
  vehicleShapesUnused(named(tree, 'Vehicle'), sink);
  for (const vehicle of named(tree, 'Vehicle')) {
    const name = attr(vehicle, 'name') ?? '';
    const category = attr(vehicle, 'vehicleCategory') ?? 'car';
    const blueprint =
      chosen(name) ?? (isCarlaBlueprint(name) ? name : (DEFAULT_VEHICLE_BLUEPRINTS[category] ?? DEFAULT_VEHICLE_BLUEPRINTS.car));
    if (blueprint === name) continue;
    setAttr(vehicle, 'name', blueprint);
    if (chosen(name) === undefined)
      sink.approximated(
        vehicle,
        'Vehicle',
        `'${name}' is no CARLA blueprint: spawned as ${blueprint} (its category ${category})`,
        'ScenarioRunner spawns the vehicle named by the blueprint (to spawn another, name the Vehicle after a CARLA blueprint, such as vehicle.audi.tt; on the command line, a table given with --blueprints FILE.json maps names to blueprints)',
      );
  }
  for (const pedestrian of named(tree, 'Pedestrian')) {
    const model = attr(pedestrian, 'model') ?? '';
    const name = attr(pedestrian, 'name') ?? '';
    // 1.2 deprecates `model` for `model3d`; a walker blueprint written there or as the name is the walker meant.
    const model3d = attr(pedestrian, 'model3d') ?? '';
    const walker = [model, model3d, name].find((each) => isCarlaBlueprint(each) && each.startsWith('walker.'));
    const blueprint = chosen(model) ?? chosen(name) ?? (isCarlaBlueprint(model) ? model : (walker ?? DEFAULT_WALKER_BLUEPRINT));
    if (blueprint === model) continue;
    setAttr(pedestrian, 'model', blueprint);
    if (chosen(model) === undefined && chosen(name) === undefined && blueprint !== walker)
      sink.approximated(
        pedestrian,
        'Pedestrian',
        `'${model || name}' is no CARLA walker: spawned as ${blueprint}`,
        'ScenarioRunner spawns the walker its model names (to spawn another, write a CARLA walker, such as walker.pedestrian.0001, as its model; on the command line, a table given with --blueprints FILE.json maps names to blueprints)',
      );
  }
  for (const misc of named(tree, 'MiscObject')) {
    const name = attr(misc, 'name') ?? '';
    const category = attr(misc, 'miscObjectCategory');
    const blueprint = chosen(name);
    if (blueprint) setAttr(misc, 'name', blueprint);
    else if (category !== 'barrier' && category !== 'guardRail' && !isCarlaBlueprint(name))
      sink.approximated(
        misc,
        'MiscObject',
        `'${name}' is no CARLA prop`,
        'ScenarioRunner asks CARLA for a blueprint of that name, which spawns nothing (map it with --blueprints FILE.json)',
      );
  }
}

/**
 * What the project's 1.0 schema still rejects after the rules: an unknown attribute is dropped, an unknown
 * element drops the smallest unit holding it (a condition, an action, an init action); anything else (a
 * missing part) is refused, never written.
 */
function dropOutsideSchema(tree: Node, sink: LossSink, sampledPolylines: ReadonlySet<Node>): boolean {
  for (let round = 0; round < 8; round++) {
    // A sampled Polyline's vertices are all of one make (vertexNode): its first two stand for the rest, as many as 1.0 requires.
    const { document, nodeOf: nodeAt } = documentOf(tree, sampledPolylines);
    const findings = checkSchema(document, { modular: false, version: '1.0' }).findings.filter((finding) => finding.severity === 'error');
    if (findings.length === 0) return true;
    let changed = false;
    for (const finding of findings) {
      const node = nodeAt.get(finding.element);
      if (!node || (!node.parent && node !== tree)) continue;
      if (finding.attribute && finding.code === 'schema-unknown-attribute') {
        if (removeAttr(node, finding.attribute.name)) {
          sink.dropped(
            node,
            `${node.name}/@${finding.attribute.name}`,
            'is not in OpenSCENARIO 1.0: dropped',
            `ScenarioRunner's 1.0 schema (${SR_SCHEMA}) refuses it; nothing in ScenarioRunner reads it`,
          );
          changed = true;
        }
        continue;
      }
      if (finding.code === 'schema-unknown-element') {
        const unit = droppableUnit(node);
        if (unit && unit.parent) {
          sink.dropped(
            unit,
            unit === node ? node.name : `${unit.name} holding <${node.name}>`,
            `<${node.name}> is not in OpenSCENARIO 1.0: the ${unit.name} is dropped`,
            `ScenarioRunner's 1.0 schema (${SR_SCHEMA}) refuses it`,
          );
          removeNode(unit);
          changed = true;
          continue;
        }
      }
      sink.refuse(
        node,
        node.name,
        `cannot be written as OpenSCENARIO 1.0 (${schemaFindingWords(finding).message})`,
        `ScenarioRunner's 1.0 schema (${SR_SCHEMA}) refuses the file`,
      );
      return false;
    }
    if (!changed) return false;
    tidyEmptyContainers(tree);
  }
  return false;
}

function storyboardElementKeys(tree: Node): Set<string> {
  const keys = new Set<string>();
  for (const node of named(tree, STORYBOARD_ELEMENT_NAMES))
    if (ancestor(node, 'Storyboard')) keys.add(`${node.name}:${attr(node, 'name') ?? ''}`);
  return keys;
}

/**
 * A StoryboardElementStateCondition waiting for an element the drops removed is kept (ScenarioRunner builds
 * it) and named: it never becomes true there, so what waits for it never starts.
 */
function reportStatesOfDroppedElements(tree: Node, before: ReadonlySet<string>, sink: LossSink): void {
  const after = storyboardElementKeys(tree);
  for (const condition of named(tree, 'StoryboardElementStateCondition')) {
    const type = STORYBOARD_ELEMENT_TYPES[attr(condition, 'storyboardElementType') ?? ''];
    if (!type) continue;
    const name = attr(condition, 'storyboardElementRef') ?? '';
    const key = `${type}:${name}`;
    if (!before.has(key) || after.has(key)) continue;
    sink.approximated(
      condition,
      'StoryboardElementStateCondition',
      `waits for the ${type} '${name}', which the export dropped: it never becomes true, and what waits for it never starts`,
      `ScenarioRunner waits for the blackboard entry the element writes when it starts or ends (srunner/scenariomanager/scenarioatomics/atomic_trigger_conditions.py OSCStartEndCondition); esmini refuses the file ("StoryboardElement ${name} not found")`,
    );
  }
}

const DROPPABLE = new Set([
  'Condition',
  'Action',
  'PrivateAction',
  'GlobalAction',
  'UserDefinedAction',
  'ParameterDeclaration',
  'Property',
  'AdditionalAxle',
]);

function droppableUnit(node: Node): Node | undefined {
  // Entity and road details past 1.0 (trailers, 3D models) carry nothing ScenarioRunner spawns or drives by.
  for (let at = node.parent; at; at = at.parent) if (at.name === 'Entities' || at.name === 'RoadNetwork') return node;
  for (let at: Node | undefined = node; at; at = at.parent) {
    if (DROPPABLE.has(at.name)) return at;
    // Init's PrivateAction children hold the actions directly.
    if (at.parent?.name === 'Private' || at.parent?.name === 'Actions') return at;
  }
  return undefined;
}
