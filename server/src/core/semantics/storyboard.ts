import { attribute, XmlElement } from '../xml';
import { SemanticModel } from './types';

/** The storyboard element kinds a StoryboardElementStateCondition may name, by their XML element name. */
export const STORYBOARD_ELEMENT_TYPES: Record<string, string> = {
  story: 'Story',
  act: 'Act',
  maneuverGroup: 'ManeuverGroup',
  maneuver: 'Maneuver',
  event: 'Event',
  action: 'Action',
};

export const STORYBOARD_ELEMENT_NAMES: ReadonlySet<string> = new Set(Object.values(STORYBOARD_ELEMENT_TYPES));

/** Collects the named storyboard elements (Story ... Action) and the conditions that name one. */
export class StoryboardCollector {
  constructor(private readonly model: SemanticModel) {}

  visit(element: XmlElement): void {
    if (element.name === 'StoryboardElementStateCondition') {
      const refAttribute = attribute(element, 'storyboardElementRef');
      if (refAttribute)
        this.model.storyboardReferences.push({ element, refAttribute, type: attribute(element, 'storyboardElementType')?.value });
    } else if (STORYBOARD_ELEMENT_NAMES.has(element.name)) {
      const nameAttribute = attribute(element, 'name');
      const named = { name: nameAttribute?.value ?? '', element, nameAttribute };
      this.model.storyboardElements.push(named);
      const sameName = this.model.storyboardByName.get(named.name);
      if (sameName) sameName.push(named);
      else this.model.storyboardByName.set(named.name, [named]);
    }
  }
}
