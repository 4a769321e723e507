import { Location } from 'vscode-languageserver/node';
import { FlatSource, originOf } from '../core/flatten';
import { ScenarioModel } from '../core/model';
import { SourceRef } from '../core/sources';
import { attributesSetBy, elementPlace, overridablePlace, Place, resolvedTarget } from '../analysis';
import { syntacticTarget, Target, targetAt } from '../target';
import { Workspace } from '../workspace';
import { catalogDefinition } from './catalogs';
import { parameterDefinition } from './parameters';
import { distributionDefinition } from './distributions';

/** Where the name under the cursor is defined; empty when it resolves to nothing. */
export async function definitionPlaces(workspace: Workspace, ref: SourceRef, offset: number): Promise<Place[]> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return [];
  const distribution = await distributionDefinition(workspace, ref, offset);
  if (distribution) return distribution;
  const target = targetAt(source, offset);
  switch (target.kind) {
    case 'catalogReference': {
      // An entryName written `$name` goes both to the catalog entry and to the parameter.
      const catalog = catalogDefinition(target);
      const parameter = target.use && source.semantics && parameterDefinition(source.semantics, target.use);
      if (catalog || parameter) return [...(catalog ?? []), ...(parameter ?? [])];
      break;
    }
    case 'parameter':
      return source.semantics ? parameterDefinition(source.semantics, target.use) : [];
    case 'expression':
      if (target.use && source.semantics) return parameterDefinition(source.semantics, target.use);
      break;
  }
  return syntacticDefinition(source, model, syntacticTarget(source, target, offset));
}

function syntacticDefinition(source: FlatSource, model: ScenarioModel, target: Target): Place[] {
  switch (target.kind) {
    case 'fileReference': {
      const resolved = target.link ? resolvedTarget(target.link.resolution) : undefined;
      return resolved ? [{ ref: resolved, range: { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } } }] : [];
    }
    case 'groupReference': {
      const { link, group } = target.linked ?? {};
      if (!link?.source || !group?.target) return [];
      const place = elementPlace(link.source, group.target.element);
      return place ? [place] : [];
    }
    case 'key': {
      const linkedSource = target.linked?.link.source;
      const group = target.linked?.group;
      if (!linkedSource || !group || !target.match) return [];
      return attributesSetBy(group, target.match)
        .map((attribute) => overridablePlace(linkedSource, attribute))
        .filter((place): place is Place => place !== undefined);
    }
    case 'entityReference':
      return entityPlaces(source, model, target.hit.attribute.value);
    default:
      return [];
  }
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
