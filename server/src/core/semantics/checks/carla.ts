import * as path from 'node:path';
import type { SimulatorFixData } from '../../problems';
import { carlaFactWording } from '../../diagnostics/simulator';
import { CarlaFactName } from '../../profiles/carla';
import { closestTown, EGO_PROPERTY, egoByName, scenarioRunnerOffsetPlace } from '../../profiles/scenarioRunner';
import { DEFAULT_CARLA_RELEASE } from '../../profiles/simulators';
import { schemaIndex } from '../../schema/index';
import { typeOfElement } from '../../schema/query';
import { checkValue } from '../../schema/values';
import { attribute, descendants, XmlAttribute, XmlElement } from '../../xml';
import type { CarlaCatalogLocation } from '../carlaFiles';
import type { CatalogEntry } from '../catalogs';
import { stopGroupsKeptInActs, XML_SHAPE } from '../storyboardStop';
import { formatValue } from '../values';
import { isCriterion, parametersComparedAsText } from './carlaParameters';
import { at, inCatalogEntry, numberOf, onCatalogReferences } from './support';
import type { Finding, SemanticCheck, SemanticContext } from './types';

/*
 * What CARLA's ScenarioRunner refuses (an error) or runs otherwise than written (a warning) beyond one
 * element or attribute at a time (those are the profile's tables, core/profiles/carla.ts): values it does
 * not evaluate, the catalog and road files it reads, entries it uses, and storyboard rules it ignores. Each
 * finding states the fact's source line in ScenarioRunner.
 */

function carlaFinding(
  name: CarlaFactName,
  element: XmlElement,
  attr: XmlAttribute | undefined,
  detail: string,
  data?: SimulatorFixData,
): Finding {
  return { ...at(element, attr), ...carlaFactWording(name, detail), ...(data ? { data } : {}) };
}

function allElements(context: SemanticContext): XmlElement[] {
  const root = context.model.document.root;
  return root ? [root, ...descendants(root)] : [];
}

/** `${...}` values: the 1.0 schema ScenarioRunner validates with admits them only as text. */
const expressions = (context: SemanticContext, elements: XmlElement[]): Finding[] => {
  const index = schemaIndex('1.0');
  const findings: Finding[] = [];
  for (const element of elements) {
    for (const attr of element.attributes) {
      if (!attr.value.includes('${')) continue;
      const typeName = typeOfElement(index, element);
      const declaration = typeName ? index.attribute(typeName, attr.name) : undefined;
      const type = declaration ? index.simpleType(declaration.type) : undefined;
      // A declaration's value is text to the schema, but ScenarioRunner converts it where the parameter is used.
      const declared = element.name === 'ParameterDeclaration' ? attribute(element, 'parameterType')?.value : undefined;
      const asText = declared !== undefined ? declared === 'string' : type !== undefined && checkValue(type, attr.value).valid;
      const data: SimulatorFixData = { exportMaps: true };
      const whole = /^\s*\$\{[^]*\}\s*$/.test(attr.value);
      const result = context.evaluator.attributeValue(element, attr);
      if (whole && result.ok) data.suggestion = formatValue(result.value);
      const value = data.suggestion !== undefined ? `, which is ${data.suggestion}` : '';
      findings.push(
        carlaFinding(asText ? 'expressionText' : 'expressionNumber', element, attr, `${attr.name}="${attr.value}"${value}`, data),
      );
    }
  }
  return findings;
};

/** Where ScenarioRunner reads a value as written: a `$name` there is the text `$name`. */
const unresolvedParameters = (elements: XmlElement[]): Finding[] => {
  const findings: Finding[] = [];
  for (const element of elements) {
    const written =
      element.name === 'Condition'
        ? attribute(element, 'delay')
        : element.name === 'LogicFile'
          ? attribute(element, 'filepath')
          : element.name === 'CatalogReference'
            ? attribute(element, 'catalogName')
            : undefined;
    if (written && /^\s*\$[A-Za-z_]/.test(written.value))
      findings.push(carlaFinding('parameterNotResolved', element, written, `${written.name}="${written.value}"`, { exportMaps: true }));
  }
  return findings;
};

/** The road ScenarioRunner loads: a CARLA map by name, or an .xodr beside the scenario. */
const road = (context: SemanticContext): Finding[] => {
  const files = context.carlaFiles;
  if (!files) return [];
  const found = files.road;
  if (!found) {
    const root = context.model.document.root;
    const network = root?.children.find((child) => child.name === 'RoadNetwork') ?? root;
    return network ? [carlaFinding('noRoadNetwork', network, undefined, 'this scenario names no LogicFile')] : [];
  }
  // A $parameter is reported where its value is read as written.
  if (found.attribute.value.trim().startsWith('$')) return [];
  if (found.xodr && !found.xodr.exists)
    return [carlaFinding('roadFileMissing', found.element, found.attribute, `${found.xodr.file} is not a file`, { exportMaps: true })];
  if (found.town && !found.town.known) {
    const town = closestTown(found.attribute.value);
    return [
      carlaFinding(
        'unknownTown',
        found.element,
        found.attribute,
        `'${found.attribute.value}' is neither a CARLA town nor an .xodr path${town ? `; did you mean '${town}'?` : ''}`,
        town ? { suggestion: town } : undefined,
      ),
    ];
  }
  return [];
};

/** The catalog of a name as ScenarioRunner keeps it: one table by name, a later type's catalog replacing an earlier one. */
function loadedCatalogs(locations: CarlaCatalogLocation[]): Map<string, CarlaCatalogLocation> {
  const byName = new Map<string, CarlaCatalogLocation>();
  for (const location of locations) if (location.catalog) byName.set(location.catalog.name, location);
  return byName;
}

/** Catalogs: read only as `<Type>Catalog.xosc`, validated against 1.0, one table by name; a reference to what it did not read fails. */
const catalogs = (context: SemanticContext): Finding[] => {
  const files = context.carlaFiles;
  if (!files) return [];
  const findings: Finding[] = [];
  const byName = loadedCatalogs(files.catalogs);
  for (const location of files.catalogs) {
    if (location.schemaErrors.length > 0)
      findings.push(
        carlaFinding('catalogSchema', location.location, location.pathAttribute, `${location.file}, ${location.schemaErrors.join('; ')}`, {
          exportMaps: true,
        }),
      );
    const name = location.catalog?.name;
    const winner = name === undefined ? undefined : byName.get(name);
    if (name !== undefined && winner && winner !== location)
      findings.push(
        carlaFinding(
          'catalogNameShared',
          location.location,
          location.pathAttribute,
          `the ${location.type} catalog '${name}' is replaced by the ${winner.type} catalog of the same name`,
          { exportMaps: true },
        ),
      );
  }
  for (const resolution of context.catalogs.references) {
    const reference = resolution.reference;
    const catalogName = reference.catalogNameAttribute?.value.trim();
    const entryName = resolution.entryName;
    // A $parameter catalog name is reported where it is read as written; an unknown name by the standard's check.
    if (!catalogName || catalogName.startsWith('$') || entryName === undefined) continue;
    const loaded = byName.get(catalogName);
    if (loaded?.catalog?.entries.some((entry) => entry.name === entryName)) {
      if (loaded.schemaErrors.length > 0)
        findings.push(
          carlaFinding(
            'catalogSchema',
            reference.element,
            reference.catalogNameAttribute,
            `${loaded.file} holds '${entryName}' but fails that schema`,
            {
              exportMaps: true,
            },
          ),
        );
      continue;
    }
    const holder = resolution.catalogs.at(0);
    if (!holder) {
      const read = files.catalogs
        .filter((location) => location.catalog)
        .map((location) => `'${location.catalog?.name}' (${location.file})`);
      const why = `catalog '${catalogName}' is not among those it reads: ${read.length > 0 ? read.join(', ') : 'none'}`;
      findings.push(carlaFinding('catalogNotLoaded', reference.element, reference.catalogNameAttribute, why, { exportMaps: true }));
      continue;
    }
    const type = holder.catalog.children[0]?.name;
    const location = files.catalogs.find((candidate) => candidate.type === type);
    const expected = type ? `${type}Catalog.xosc` : undefined;
    const data: SimulatorFixData = { exportMaps: true };
    let why: string;
    if (!location) why = `the scenario lists no ${type ?? 'such'}Catalog location, so catalog '${catalogName}' is not read`;
    else if (loaded && loaded !== location)
      why = `catalog '${catalogName}' names the ${loaded.type} catalog it reads, which has no entry '${entryName}'`;
    else if (location.catalog)
      why = `it reads the ${location.type} catalog from ${location.file}, which is catalog '${location.catalog.name}', not '${catalogName}'`;
    else {
      why = `it reads the ${location.type} catalog only from ${location.file}, which does not exist; '${catalogName}' is in ${holder.ref.disk}`;
      // One rename does it when the catalog lies in the directory ScenarioRunner reads, under another name.
      if (expected && holder.ref.entries.length === 0 && path.dirname(holder.ref.disk) === path.dirname(location.file))
        data.rename = { from: holder.ref.disk, to: location.file };
    }
    findings.push(carlaFinding('catalogNotLoaded', reference.element, reference.catalogNameAttribute, why, data));
  }
  return findings;
};

/** An entityRef of a used catalog entry that stays a `$name` after ScenarioRunner's substitution (esmini's `$owner`). */
const entryEntityRefs = (context: SemanticContext): Finding[] => {
  if (!context.carlaFiles) return [];
  const findings: Finding[] = [];
  for (const resolution of context.catalogs.references) {
    const entry = resolution.entry;
    if (!entry) continue;
    const known = new Set<string>();
    for (const declaration of entry.file.model.declarations)
      if (entry.element.start <= declaration.element.start && declaration.element.end <= entry.element.end) known.add(declaration.name);
    for (const assignment of resolution.reference.assignments) {
      const name = assignment.parameterRef?.value.replace(/^\$/, '');
      if (name) known.add(name);
    }
    for (const element of descendants(entry.element)) {
      const ref = attribute(element, 'entityRef');
      const name = ref?.value.trim();
      if (!ref || !name?.startsWith('$') || known.has(name.slice(1))) continue;
      findings.push(
        carlaFinding(
          'catalogEntityRef',
          resolution.reference.element,
          resolution.reference.entryNameAttribute,
          `entry '${entry.name}' (${path.basename(entry.file.ref.disk)}) has entityRef="${name}" in ${element.name}`,
          { exportMaps: true },
        ),
      );
      break;
    }
  }
  return findings;
};

/** The boolean attributes ScenarioRunner reads with strtobool, which fails on the default it passes when one is absent. */
const REQUIRED_FLAGS: Readonly<Record<string, readonly string[]>> = {
  TimeHeadwayCondition: ['freespace'],
  TimeToCollisionCondition: ['freespace'],
  DistanceCondition: ['freespace', 'alongRoute'],
};

/** Elements whose parts ScenarioRunner reads without looking first. */
const missingParts = (elements: XmlElement[]): Finding[] => {
  const findings: Finding[] = [];
  for (const element of elements) {
    if (element.name === 'ControllerAction') {
      const missing = ['AssignControllerAction', 'OverrideControllerValueAction'].filter(
        (part) => !element.children.some((child) => child.name === part),
      );
      if (missing.length > 0)
        findings.push(carlaFinding('controllerActionParts', element, undefined, `this one has no ${missing.join(' and no ')}`));
    }
    const required = REQUIRED_FLAGS[element.name]?.filter((name) => !attribute(element, name)) ?? [];
    if (required.length > 0)
      findings.push(carlaFinding('freespaceRequired', element, undefined, `this ${element.name} has no ${required.join(' and no ')}`));
  }
  return findings;
};

/** Storyboard rules ScenarioRunner does not follow: warnings where the scenario depends on them. */
const storyboard = (elements: XmlElement[]): Finding[] => {
  const findings: Finding[] = [];
  const keptStopGroups = new Map<XmlElement, Set<XmlElement>>();
  const keptInActs = (group: XmlElement, storyboard: XmlElement): boolean => {
    let kept = keptStopGroups.get(storyboard);
    if (!kept) keptStopGroups.set(storyboard, (kept = stopGroupsKeptInActs(storyboard, XML_SHAPE)));
    return kept.has(group);
  };
  for (const element of elements) {
    if (element.name === 'Event') {
      const priority = attribute(element, 'priority');
      const siblings = element.parent?.children.filter((child) => child.name === 'Event').length ?? 0;
      if (priority && siblings > 1 && priority.value !== 'parallel' && !priority.value.startsWith('$'))
        findings.push(carlaFinding('eventPriority', element, priority, `priority="${priority.value}" among ${siblings} events`));
      const count = attribute(element, 'maximumExecutionCount');
      if (count && Number(count.value) > 1)
        findings.push(carlaFinding('eventRepetition', element, count, `maximumExecutionCount="${count.value}"`));
    }
    if (element.name === 'TriggeringEntities') {
      const rule = attribute(element, 'triggeringEntitiesRule');
      const entities = element.children.filter((child) => child.name === 'EntityRef').length;
      if (rule?.value === 'all' && entities > 1)
        findings.push(carlaFinding('triggeringEntitiesRule', element, rule, `triggeringEntitiesRule="all" over ${entities} entities`));
    }
    if (element.name === 'ConditionGroup' && element.parent?.name === 'StopTrigger') {
      const holder = element.parent.parent;
      const owner = holder?.name;
      const conditions = element.children.filter((child) => child.name === 'Condition');
      if (owner === 'Act' && conditions.length > 1)
        findings.push(carlaFinding('actStopTrigger', element, undefined, `${conditions.length} conditions in one group`));
      // A group every Act's StopTrigger holds too (as the export writes it) still stops the scenario in ScenarioRunner.
      if (holder && owner === 'Storyboard' && !keptInActs(element, holder))
        for (const condition of conditions) {
          if (!isCriterion(condition))
            findings.push(
              carlaFinding(
                'storyboardStopTrigger',
                condition,
                attribute(condition, 'name'),
                `condition '${attribute(condition, 'name')?.value ?? ''}'`,
              ),
            );
        }
    }
  }
  return findings;
};

/** A negative AbsoluteTargetSpeed in the Init: ScenarioRunner reads it as the actor's start speed and refuses it. */
const negativeStartSpeeds = (context: SemanticContext, elements: XmlElement[]): Finding[] => {
  const findings: Finding[] = [];
  for (const element of elements) {
    if (element.name !== 'AbsoluteTargetSpeed') continue;
    const owner = element.parent?.parent?.parent?.parent?.parent;
    const init = owner?.parent?.parent;
    const value = attribute(element, 'value');
    if (!value || owner?.name !== 'Private' || init?.name !== 'Init') continue;
    const result = context.evaluator.attributeValue(element, value);
    if (!result.ok || typeof result.value !== 'number' || !(result.value < 0)) continue;
    const entity = attribute(owner, 'entityRef')?.value ?? 'an actor';
    findings.push(
      carlaFinding('negativeStartSpeed', element, value, `the start speed ${formatValue(result.value)} of ${entity} is negative`),
    );
  }
  return findings;
};

/** A LanePosition's offset, which ScenarioRunner moves to the right of the lane's heading in CARLA (CARLA_FACTS.laneOffsetSide): where that is not to the left of the road's reference line. */
const laneOffsets = (context: SemanticContext, elements: XmlElement[]): Finding[] => {
  const findings: Finding[] = [];
  for (const element of elements) {
    if (element.name !== 'LanePosition') continue;
    // Absent: an offset and h of 0; written but no number: none of this check's (other rules report it).
    const offset = numberOf(context, element, 'offset')?.value ?? 0;
    const laneId = numberOf(context, element, 'laneId')?.value ?? NaN;
    const orientation = element.children.find((child) => child.name === 'Orientation');
    const h = orientation && attribute(orientation, 'h') ? (numberOf(context, orientation, 'h')?.value ?? NaN) : 0;
    if (offset === 0 || !Number.isFinite(offset) || !Number.isInteger(laneId) || laneId === 0 || !Number.isFinite(h)) continue;
    const { along, across, place } = scenarioRunnerOffsetPlace(laneId, h, offset);
    if (place === 'as-written') continue;
    const metres = (value: number) => `${Number(Math.abs(value).toFixed(2))} m`;
    const side = (value: number) => `${metres(value)} to the ${value > 0 ? 'left' : 'right'}`;
    const alongWords = place === 'along' ? ` and ${metres(along)} ${along > 0 ? 'on' : 'back'} along the road` : '';
    findings.push(
      carlaFinding(
        'laneOffsetSide',
        element,
        attribute(element, 'offset'),
        `this one lands ${Math.abs(across) < 0.005 ? 'on' : side(across) + ' of'} lane ${laneId}'s centre${alongWords}, where OpenSCENARIO puts it ${side(offset)}`,
        { exportMaps: true },
      ),
    );
  }
  return findings;
};

function marksEgo(holder: XmlElement): boolean {
  return descendants(holder).some(
    (property) =>
      property.name === 'Property' &&
      attribute(property, 'name')?.value === EGO_PROPERTY.name &&
      attribute(property, 'value')?.value === EGO_PROPERTY.value,
  );
}

/**
 * Entities: blueprint names and the ego ScenarioRunner looks for (marked here or in a catalog entry a ScenarioObject
 * uses). With none marked, the fix marks the vehicle the export marks (egoByName), where its Vehicle is in this file.
 */
const entities = (context: SemanticContext): Finding[] => {
  const root = context.model.document.root;
  const entitiesElement = root?.children.find((child) => child.name === 'Entities');
  if (!entitiesElement || context.model.catalog) return [];
  const findings: Finding[] = [];
  let ego = false;
  /** The vehicles in order, with their Vehicle element where it is written in this file (not a catalog's). */
  const vehicles: { name: string; inFile: XmlElement | undefined }[] = [];
  const objects = entitiesElement.children.filter((child) => child.name === 'ScenarioObject');
  for (const object of objects) {
    const reference = object.children.find((child) => child.name === 'CatalogReference');
    const entry = reference
      ? context.catalogs.references.find((resolution) => resolution.reference.element === reference)?.entry
      : undefined;
    const catalogVehicle = entry?.element.name === 'Vehicle' ? entry.element : undefined;
    if (marksEgo(object) || (catalogVehicle && marksEgo(catalogVehicle))) ego = true;
    const vehicle = object.children.find((child) => child.name === 'Vehicle');
    if (vehicle || catalogVehicle) vehicles.push({ name: attribute(object, 'name')?.value ?? '', inFile: vehicle });
    for (const entity of object.children) {
      const named =
        entity.name === 'Vehicle' ? attribute(entity, 'name') : entity.name === 'Pedestrian' ? attribute(entity, 'model') : undefined;
      const value = named?.value.trim();
      if (named && value && !value.startsWith('$') && !value.includes('.'))
        findings.push(
          carlaFinding(
            'blueprint',
            entity,
            named,
            `'${value}' is not a blueprint name (such as vehicle.tesla.model3 or walker.pedestrian.0001)`,
            { exportMaps: true },
          ),
        );
    }
  }
  if (!ego && objects.length > 0) {
    const chosen = egoByName(vehicles.map((vehicle) => vehicle.name));
    const fixable = chosen !== undefined && vehicles.find((vehicle) => vehicle.name === chosen)?.inFile !== undefined;
    const property = `<Property name="${EGO_PROPERTY.name}" value="${EGO_PROPERTY.value}"/>`;
    findings.push(
      carlaFinding(
        'noEgo',
        entitiesElement,
        undefined,
        chosen !== undefined
          ? `add ${property} to the Properties of the ego ('${chosen}' is the vehicle Export for CARLA marks)`
          : `add ${property} to the ego's Properties`,
        { exportMaps: true, ...(fixable ? { ego: chosen } : {}) },
      ),
    );
  }
  return findings;
};

/** Every CARLA finding of a document, with `simulator` = `carla`. */
export const carlaScenario: SemanticCheck = (context) => {
  if (context.simulator !== 'carla') return [];
  const elements = allElements(context);
  // ScenarioRunner validates a whole catalog file against its schema (expressions), but runs an entry only where a scenario references it.
  const run = context.model.catalog ? elements.filter((element) => !inCatalogEntry(context, element)) : elements;
  const inEntry = (entry: CatalogEntry) => {
    const entryElements = [entry.element, ...descendants(entry.element)];
    return [...unresolvedParameters(entryElements), ...missingParts(entryElements), ...storyboard(entryElements)];
  };
  return [
    ...expressions(context, elements),
    ...unresolvedParameters(run),
    ...road(context),
    ...catalogs(context),
    ...entryEntityRefs(context),
    ...missingParts(run),
    ...storyboard(run),
    ...onCatalogReferences(context, inEntry),
    ...parametersComparedAsText(context, elements),
    ...negativeStartSpeeds(context, elements),
    ...laneOffsets(context, run),
    ...entities(context),
  ];
};

/** The release a context's CARLA facts are checked for. */
export function carlaReleaseOf(context: SemanticContext) {
  return context.carlaRelease ?? DEFAULT_CARLA_RELEASE;
}
