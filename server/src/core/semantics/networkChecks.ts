import { chooseVersion } from '../schema/version';
import { NO_ACTOR_ACTION_NOTE, noActorWording } from '../diagnostics/noActor';
import { esminiFactWording } from '../diagnostics/simulator';
import { negativeTransitionTimeWording } from '../diagnostics/negativeTransitionTime';
import { nonPositivePhaseDurationWording } from '../diagnostics/nonPositivePhaseDuration';
import { outOfRangeWording } from '../diagnostics/outOfRange';
import { roadFileWording } from '../diagnostics/roadFile';
import { unknownTrafficSignalWording } from '../diagnostics/unknownTrafficSignal';
import { unknownTrafficSignalControllerWording } from '../diagnostics/unknownTrafficSignalController';
import { attribute, descendants, firstDescendant, XmlAttribute, XmlElement } from '../xml';
import { at, numberOf } from './checks/support';
import type { Finding, SemanticCheck, SemanticContext } from './checks/types';
import { inRange, rangeText, readingsOf, ValueRange, valueRangesOf } from './ranges';
import { SemanticModel } from './types';
import { elementsNamed } from './elementIndex';
import { coreMemo } from '../memos';

/**
 * The rules about traffic signals, actors and value ranges (ASAM Quality Checker rules
 * `reference_control.resolvable_signal_id_in_traffic_signal_state_action`,
 * `..._traffic_signal_controller_by_traffic_signal_controller_ref`, `valid_actor_reference_in_private_actions`,
 * `data_type.non_negative_transition_time_in_light_state_action`, `data_type.positive_duration_in_phase`,
 * and the ranges the standard gives). Each is one SemanticCheck registered in SEMANTIC_CHECKS.
 */

function textOf(context: SemanticContext, element: XmlElement, name: string): { attr: XmlAttribute; text: string } | undefined {
  const attr = attribute(element, name);
  const text = context.evaluator.textOf(element, attr);
  return attr && text !== undefined ? { attr, text } : undefined;
}

/** The scenario's own `RoadNetwork/TrafficSignals/TrafficSignalController`s; undefined when the file has no RoadNetwork (a catalog, a group's source). */
function signalControllers(model: SemanticModel): XmlElement[] | undefined {
  const network = model.document.root?.children.find((child) => child.name === 'RoadNetwork');
  if (!network) return undefined;
  const signals = network.children.find((child) => child.name === 'TrafficSignals');
  return signals ? signals.children.filter((child) => child.name === 'TrafficSignalController') : [];
}

/**
 * The road file a LogicFile names is found where a run has esmini look for it (SemanticContext.roadFile). Said
 * nothing of with simulator carla (its profile's own road rule), nor of a CARLA map's name unless esmini is the simulator.
 */
export const roadFileFound: SemanticCheck = ({ roadFile, simulator, model }) => {
  if (!roadFile || roadFile.resolved || roadFile.packaged || simulator === 'carla') return [];
  if (roadFile.carlaTown && simulator !== 'esmini') return [];
  const { element } = roadFile.logic;
  return [
    {
      ...at(element, roadFile.attribute),
      ...roadFileWording(
        roadFile.logic.filepath,
        roadFile.folders,
        simulator === 'esmini' ? 'error' : 'warning',
        roadFile.carlaTown,
        (roadFile.heldByReferencedPackages ?? []).map(({ held, referencedEntries }) => ({
          packageFile: held.disk,
          entries: held.entries,
          referencedEntries,
        })),
        (roadFile.unreadReferencedPackages ?? []).map((unread) => ({
          packageFile: unread.packageFile,
          line: model.document.lines.positionAt(unread.reference.start).line + 1,
          reason: unread.reason,
        })),
      ),
    },
  ];
};

/** A `TrafficSignalStateAction name` is a signal of the road file or of one of the scenario's controller phases. Skipped when the road file cannot be read. */
export const trafficSignalIds: SemanticCheck = (context) => {
  const { road, model } = context;
  if (!road) return [];
  const known = new Set(road.signalIds);
  for (const state of elementsNamed(model, 'TrafficSignalState')) {
    const id = textOf(context, state, 'trafficSignalId');
    if (id) known.add(id.text);
  }
  const findings: Finding[] = [];
  for (const action of elementsNamed(model, 'TrafficSignalStateAction')) {
    const id = textOf(context, action, 'name');
    if (!id || known.has(id.text)) continue;
    findings.push({
      ...at(action, id.attr),
      ...unknownTrafficSignalWording(id.text, road.file),
    });
  }
  return findings;
};

/** A `trafficSignalControllerRef` names a TrafficSignalController of the scenario's RoadNetwork. */
export const trafficSignalControllerRefs: SemanticCheck = (context) => {
  const controllers = signalControllers(context.model);
  if (!controllers) return [];
  const names = new Set(
    controllers.map((controller) => textOf(context, controller, 'name')?.text).filter((name): name is string => name !== undefined),
  );
  const findings: Finding[] = [];
  for (const elementName of ['TrafficSignalControllerAction', 'TrafficSignalControllerCondition']) {
    for (const element of elementsNamed(context.model, elementName)) {
      const ref = textOf(context, element, 'trafficSignalControllerRef');
      if (!ref || names.has(ref.text)) continue;
      findings.push({
        ...at(element, ref.attr),
        ...unknownTrafficSignalControllerWording(ref.text, [...names]),
      });
    }
  }
  return findings;
};

/**
 * A ManeuverGroup whose maneuvers hold private actions has actors to act on: an EntityRef, or
 * `selectTriggeringEntities="true"` where its Act's StartTrigger has an entity condition to take the
 * triggering entities from (ASAM's Quality Checker counts only EntityRefs, so it reports that case too:
 * here it is left alone, but for esmini, which never reads selectTriggeringEntities and refuses it: ESMINI_FACTS).
 * Without either it is an error, as ASAM's checker says: esmini 3.6 quits on it ("PrivateAction ... missing
 * actor(s)", ScenarioReader.cpp:5304-5310).
 */
export const privateActionActors: SemanticCheck = (context) => {
  const findings: Finding[] = [];
  for (const group of elementsNamed(context.model, 'ManeuverGroup')) {
    const privateAction = firstPrivateAction(group);
    if (!privateAction) continue;
    const actors = group.children.find((child) => child.name === 'Actors');
    if (actors?.children.some((child) => child.name === 'EntityRef')) continue;
    const selects = actors && textOf(context, actors, 'selectTriggeringEntities');
    const selectsTriggering = selects !== undefined && selects.text.trim() === 'true';
    const related = [
      {
        source: context.ref,
        range: context.model.document.lines.range(privateAction.start, privateAction.nameEnd),
        message: NO_ACTOR_ACTION_NOTE,
      },
    ];
    const name = attribute(group, 'name')?.value ?? '';
    if (selectsTriggering && actStartTriggeringEntities(group)) {
      if (context.simulator === 'esmini' && actors && selects)
        findings.push(esminiTriggeringActors(group, name, actors, selects.attr, related));
      continue;
    }
    findings.push({
      ...at(actors ?? group, actors ? undefined : attribute(group, 'name')),
      ...noActorWording(name, selectsTriggering),
      related,
    });
  }
  return findings;
};

/** A group the standard gives the triggering entities as actors, which esmini refuses: its fix names the Act's one triggering entity, where there is one. */
function esminiTriggeringActors(
  group: XmlElement,
  name: string,
  actors: XmlElement,
  selects: XmlAttribute,
  related: Finding['related'],
): Finding {
  const trigger = group.parent?.name === 'Act' ? group.parent.children.find((child) => child.name === 'StartTrigger') : undefined;
  const triggering = new Set(
    (trigger ? descendants(trigger) : [])
      .filter((element) => element.name === 'EntityRef' && element.parent?.name === 'TriggeringEntities')
      .map((element) => attribute(element, 'entityRef')?.value)
      .filter((entity): entity is string => entity !== undefined && entity !== ''),
  );
  const [actor] = triggering.size === 1 ? triggering : [];
  return {
    ...at(actors, selects),
    ...esminiFactWording(
      'triggeringActors',
      `ManeuverGroup '${name}' holds private actions and takes its actors only from the triggering entities of its Act`,
    ),
    hint: `add <EntityRef entityRef="${actor ?? '...'}"/> to its <Actors>${actor ? ", the Act's triggering entity" : ''}`,
    related,
    ...(actor ? { data: { actor } } : {}),
  };
}

/** Whether the StartTrigger of the Act holding `group` has an entity condition (its TriggeringEntities are what selectTriggeringEntities takes). */
function actStartTriggeringEntities(group: XmlElement): boolean {
  const act = group.parent?.name === 'Act' ? group.parent : undefined;
  // A group outside an Act (a simple scenario's, composed into a main's Act): the Act it lands in is not known here.
  if (!act) return true;
  const trigger = act.children.find((child) => child.name === 'StartTrigger');
  return trigger !== undefined && firstDescendant(trigger, 'TriggeringEntities') !== undefined;
}

const firstPrivateActions = coreMemo<XmlElement, XmlElement | null>('firstPrivateActions');

/** The first PrivateAction below a group: its subtree never changes, and a value edit shares the groups it does not hold with the previous tree. */
function firstPrivateAction(group: XmlElement): XmlElement | undefined {
  let found = firstPrivateActions.get(group);
  if (found === undefined) firstPrivateActions.set(group, (found = firstDescendant(group, 'PrivateAction') ?? null));
  return found ?? undefined;
}

/** `LightStateAction transitionTime` is not negative. */
export const lightTransitionTimes: SemanticCheck = (context) =>
  elementsNamed(context.model, 'LightStateAction').flatMap((action): Finding[] => {
    const time = numberOf(context, action, 'transitionTime');
    if (!time || time.value >= 0) return [];
    return [
      {
        ...at(action, time.attr),
        ...negativeTransitionTimeWording(time.value),
      },
    ];
  });

/**
 * A traffic-signal `Phase duration` is positive. A negative one is an error by both the standard and
 * ASAM's checker; zero is within the standard's range [0..inf[, but ASAM's checker reports it: a warning.
 */
export const phaseDurations: SemanticCheck = (context) =>
  elementsNamed(context.model, 'Phase').flatMap((phase): Finding[] => {
    const duration = numberOf(context, phase, 'duration');
    if (!duration || duration.value > 0) return [];
    return [
      {
        ...at(phase, duration.attr),
        ...nonPositivePhaseDurationWording(duration.value),
      },
    ];
  });

const DOLLAR = 36;

/** Lists of elements of one name (`elementsNamed`: a value edit elsewhere keeps the list) whose values are literals within these ranges. */
const withinRanges = coreMemo<readonly XmlElement[], readonly ValueRange[]>('listsWithinRanges');

/**
 * Values within the ranges the standard gives for the file's version (core/semantics/ranges.ts),
 * evaluated after `$parameter`/`${...}` resolution: an error, as in RA Consulting's checker. Where esmini
 * reads such a value with one clear meaning (a negative rate as its magnitude), it is a warning that says
 * both (SPEC 12: what a mainstream simulator runs with one meaning). A range that a rule of its own checks is left to it.
 */
export const valueRanges: SemanticCheck = (context) => {
  const findings: Finding[] = [];
  const { version } = chooseVersion(context.model.document);
  for (const [elementName, ranges] of valueRangesOf(version)) {
    const elements = elementsNamed(context.model, elementName);
    if (withinRanges.get(elements) === ranges) continue;
    let within = true;
    for (const element of elements) {
      for (const range of ranges) {
        if (range.checkedBy) continue;
        // A `$` value is evaluated with the file's parameters, which an edit may change: the list is checked again next time.
        if (attribute(element, range.attribute)?.value.charCodeAt(0) === DOLLAR) within = false;
        const value = numberOf(context, element, range.attribute);
        if (!value || inRange(value.value, range)) continue;
        within = false;
        const written = value.attr.value.trim() === String(value.value) ? undefined : value.attr.value.trim();
        // Said for the simulator checked: ScenarioRunner's reading with carla where one is recorded, esmini's otherwise (named as such).
        const carla = context.simulator === 'carla';
        const carlaReadings = carla ? readingsOf(range.carla) : [];
        const known = (carlaReadings.length > 0 ? carlaReadings : readingsOf(range.esmini)).find(
          (reading) =>
            (!reading.versions || reading.versions.includes(version)) &&
            (!reading.when || textOf(context, element, reading.when.attribute)?.text.trim() === reading.when.value),
        );
        const isCarla = known !== undefined && carlaReadings.includes(known);
        findings.push({
          ...at(element, value.attr),
          ...outOfRangeWording({
            element: range.element,
            attribute: range.attribute,
            value: value.value,
            written,
            range: rangeText(range),
            modelClass: range.modelClass,
            ...(known
              ? {
                  reading: { by: isCarla ? 'CARLA ScenarioRunner' : 'esmini', text: known.reading },
                  ...(carla && !isCarla ? { notRecordedFor: 'CARLA ScenarioRunner' } : {}),
                }
              : {}),
          }),
        });
      }
    }
    if (within && elements.length > 0) withinRanges.set(elements, ranges);
  }
  return findings;
};
