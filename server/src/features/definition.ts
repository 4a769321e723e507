import { Location } from 'vscode-languageserver/node';
import { FlatSource, originOf } from '../core/flatten';
import { ScenarioModel } from '../core/model';
import { SourceRef } from '../core/sources';
import { attributesSetBy, elementPlace, groupLinkOf, keyMatchOf, linkOf, overridablePlace, Place, resolvedTarget } from '../analysis';
import { ancestor, attributeAt } from '../cursor';
import { Workspace } from '../workspace';
import { catalogDefinition } from './catalogs';
import { parameterDefinition } from './parameters';

/** Where the name under the cursor is defined; empty when it resolves to nothing. */
export async function definitionPlaces(workspace: Workspace, ref: SourceRef, offset: number): Promise<Place[]> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return [];
  // An entryName written `$name` goes both to the catalog entry and to the parameter.
  const catalog = source.semantics && catalogDefinition(source.semantics, offset);
  const parameter = source.semantics && parameterDefinition(source.semantics, offset);
  if (catalog || parameter) return [...(catalog ?? []), ...(parameter ?? [])];
  const hit = attributeAt(model.document, offset);
  if (!hit) return [];
  const { element, attribute } = hit;
  if (element.name === 'ScenarioReference' && attribute.name === 'scenarioFileName') {
    const link = linkOf(source, element);
    const target = link ? resolvedTarget(link.resolution) : undefined;
    return target ? [{ ref: target, range: { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } } }] : [];
  }
  if (element.name === 'ManeuverGroupReference' && attribute.name === 'maneuverGroupName') {
    const reference = ancestor(element.parent, 'ScenarioReference');
    const link = reference ? linkOf(source, reference) : undefined;
    const group = link ? groupLinkOf(link, element) : undefined;
    if (!link?.source || !group?.target) return [];
    const place = elementPlace(link.source, group.target.element);
    return place ? [place] : [];
  }
  if (element.name === 'ParameterReference' && attribute.name === 'key') {
    const found = keyMatchOf(source, element);
    if (!found?.link.source) return [];
    const linkedSource = found.link.source;
    return attributesSetBy(found.group, found.match)
      .map((target) => overridablePlace(linkedSource, target))
      .filter((place): place is Place => place !== undefined);
  }
  if (attribute.name === 'entityRef') return entityPlaces(source, model, attribute.value);
  return [];
}

function entityPlaces(source: FlatSource, model: ScenarioModel, name: string): Place[] {
  const entity = model.entities.find((candidate) => candidate.name === name);
  if (!entity) return [];
  const origin = originOf(source, entity.element);
  const place = elementPlace(origin.source, origin.element);
  return place ? [place] : [];
}

export function toLocations(workspace: Workspace, places: Place[]): Location[] {
  return places.map((place) => ({ uri: workspace.uriOf(place.ref), range: place.range }));
}
