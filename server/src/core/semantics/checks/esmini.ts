import { esminiFactWording } from '../../diagnostics/simulator';
import { ESMINI_SMALL_NUMBER } from '../../profiles/esmini';
import { attribute, descendants, XmlAttribute, XmlElement } from '../../xml';
import { assignmentsOf } from '../catalogs';
import { Evaluator } from '../model';
import { at, inCatalogEntry, onCatalogReferences } from './support';
import type { Finding, SemanticCheck, SemanticContext } from './types';

/*
 * What esmini refuses (an error) or runs otherwise than written (a warning) beyond one element or attribute at a
 * time (those are the profile's tables, core/profiles/esmini.ts), each finding stating its fact's source lines.
 */

/** The ScenarioObjects after an ExternalObjectReference that the document references: esmini never reads them, and refuses the reference. */
function entitiesAfterExternal(context: SemanticContext, root: XmlElement): Finding[] {
  const objects =
    root.children.find((child) => child.name === 'Entities')?.children.filter((child) => child.name === 'ScenarioObject') ?? [];
  const external = objects.findIndex((object) => object.children.some((child) => child.name === 'ExternalObjectReference'));
  if (external < 0) return [];
  const referenced = new Set(context.model.entityReferences.map((reference) => reference.attribute.value));
  const externalName = attribute(objects[external], 'name')?.value ?? '';
  return objects.slice(external + 1).flatMap((object) => {
    const name = attribute(object, 'name');
    if (!name || !referenced.has(name.value)) return [];
    return [
      {
        ...at(object, name),
        ...esminiFactWording('entitiesAfterExternal', `'${name.value}' comes after '${externalName}', and the scenario references it`),
      },
    ];
  });
}

/** Each RoutePosition among `elements` whose Orientation comes after its InRoutePosition, which esmini drops (Euro NCAP's CBFA turns its obstruction so: the second one then stands 9 m away). */
function routeOrientationsAfterPosition(elements: readonly XmlElement[]): Finding[] {
  return elements.flatMap((route) => {
    if (route.name !== 'RoutePosition') return [];
    const orientation = route.children.findIndex((child) => child.name === 'Orientation');
    const position = route.children.findIndex((child) => child.name === 'InRoutePosition');
    if (orientation < 0 || position < 0 || orientation < position) return [];
    const element = route.children[orientation];
    return [
      {
        ...at(element, undefined),
        ...esminiFactWording('routeOrientationOrder', `this <Orientation> comes after <InRoutePosition>`),
        data: { orientationFirst: true },
      },
    ];
  });
}

/** A SynchronizeAction's final AbsoluteSpeed of 0 or less followed by a steady state, among `elements`, read by `textOf`. */
function steadyStateStops(
  elements: readonly XmlElement[],
  textOf: (element: XmlElement, value: XmlAttribute) => string | undefined,
): Finding[] {
  const findings: Finding[] = [];
  for (const speed of elements) {
    if (speed.name !== 'AbsoluteSpeed' || speed.parent?.name !== 'FinalSpeed' || speed.children.length === 0) continue;
    const value = attribute(speed, 'value');
    const text = value && textOf(speed, value);
    // esmini compares with SMALL_NUMBER; a value it cannot read is another check's.
    if (text === undefined || text.trim() === '' || !(Number(text) < ESMINI_SMALL_NUMBER)) continue;
    findings.push({
      ...at(speed, value),
      ...esminiFactWording('steadyStateStop', `a final speed of ${text.trim()} with <${speed.children[0].name}>`),
    });
  }
  return findings;
}

/**
 * What esmini refuses at load: a ScenarioObject after an ExternalObjectReference that is referenced, a SynchronizeAction's
 * steady state to a stop; what it drops: a RoutePosition's Orientation after its position. In a catalog entry, each is
 * found on each reference that uses the entry (with its values, as esmini reads it there), not in the catalog.
 */
export const esminiScenario: SemanticCheck = (context) => {
  const root = context.model.document.root;
  if (context.simulator !== 'esmini' || !root) return [];
  const own = descendants(root).filter((element) => !inCatalogEntry(context, element));
  const textOf = (evaluator: Evaluator) => (element: XmlElement, value: XmlAttribute) => evaluator.textOf(element, value);
  return [
    ...entitiesAfterExternal(context, root),
    ...routeOrientationsAfterPosition(own),
    ...steadyStateStops(own, textOf(context.evaluator)),
    ...onCatalogReferences(context, (entry, resolution) => {
      const evaluator = new Evaluator(entry.file.model, assignmentsOf(resolution.reference, context.evaluator), context.evaluator.reading);
      const elements = [entry.element, ...descendants(entry.element)];
      return [...routeOrientationsAfterPosition(elements), ...steadyStateStops(elements, textOf(evaluator))];
    }),
  ];
};
