import { attribute, XmlElement } from '../xml';
import { ParameterAssignmentInfo, SemanticModel } from './types';

/** Collects a catalog file's `Catalog`, the `CatalogLocations` directories and every `CatalogReference` with its assignments. */
export class CatalogElementCollector {
  constructor(
    private readonly model: SemanticModel,
    private readonly rootElement: XmlElement,
  ) {}

  visit(element: XmlElement): void {
    switch (element.name) {
      case 'Catalog':
        if (element.parent === this.rootElement) this.model.catalog = element;
        break;
      case 'Directory':
        if (element.parent && element.parent.parent?.name === 'CatalogLocations') {
          this.model.catalogLocations.push({ kind: element.parent.name, directory: element, pathAttribute: attribute(element, 'path') });
        }
        break;
      case 'CatalogReference': {
        const assignments: ParameterAssignmentInfo[] = [];
        for (const child of element.children) {
          if (child.name !== 'ParameterAssignments') continue;
          for (const assignment of child.children) {
            if (assignment.name === 'ParameterAssignment') {
              assignments.push({
                element: assignment,
                parameterRef: attribute(assignment, 'parameterRef'),
                valueAttribute: attribute(assignment, 'value'),
              });
            }
          }
        }
        this.model.catalogReferences.push({
          element,
          catalogNameAttribute: attribute(element, 'catalogName'),
          entryNameAttribute: attribute(element, 'entryName'),
          assignments,
        });
        break;
      }
    }
  }
}
