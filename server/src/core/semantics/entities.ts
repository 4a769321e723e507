import { attribute, XmlElement } from '../xml';
import { SemanticModel } from './types';

/** Attributes that name an entity (ASAM OpenSCENARIO 1.x: EntityRef and the actions/positions that take one). */
export const ENTITY_REFERENCE_ATTRIBUTES: ReadonlySet<string> = new Set(['entityRef', 'masterEntityRef']);

/** Collects the declared entities (`ScenarioObject`, `EntitySelection`) and every attribute that names one. */
export class EntityCollector {
  constructor(private readonly model: SemanticModel) {}

  visit(element: XmlElement): void {
    switch (element.name) {
      case 'Entities':
        this.model.hasEntities = true;
        break;
      case 'ScenarioObject':
      case 'EntitySelection': {
        const nameAttribute = attribute(element, 'name');
        this.model.entities.push({ name: nameAttribute?.value ?? '', element, nameAttribute });
        break;
      }
    }
    const attributes = element.attributes;
    for (let i = 0; i < attributes.length; i++)
      if (ENTITY_REFERENCE_ATTRIBUTES.has(attributes[i].name)) this.model.entityReferences.push({ element, attribute: attributes[i] });
  }
}
