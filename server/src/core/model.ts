import { attribute, descendants, parseXml, ValueEdit, valueEditOf, XmlAttribute, XmlDocument, XmlElement } from './xml';
import { coreMemo } from './memos';

export const PARAMETER_ATTRIBUTES = 'parameterAttributes';

export interface ParameterReferenceInfo {
  key: string;
  value: string;
  element: XmlElement;
  keyAttribute: XmlAttribute | undefined;
  valueAttribute: XmlAttribute | undefined;
}

export interface ManeuverGroupReferenceInfo {
  /** The `maneuverGroupName`, possibly dotted for a group imported by a nested package. */
  name: string;
  element: XmlElement;
  nameAttribute: XmlAttribute | undefined;
  parameters: ParameterReferenceInfo[];
}

export interface ScenarioReferenceInfo {
  fileName: string;
  element: XmlElement;
  fileAttribute: XmlAttribute | undefined;
  groupReferences: ManeuverGroupReferenceInfo[];
  /** The `ManeuverGroup` that holds the reference and that flattening replaces. */
  outerGroup: ManeuverGroupInfo | undefined;
}

export interface ManeuverGroupInfo {
  name: string;
  element: XmlElement;
  nameAttribute: XmlAttribute | undefined;
  /** The first `EntityRef` of the group (its `Actors`), whose entity an imported group takes over. */
  actor: XmlElement | undefined;
  references: ScenarioReferenceInfo[];
}

/** One name listed in a `parameterAttributes` value. */
export interface ParameterAttributeName {
  name: string;
  /** Offsets of the name inside the document. */
  start: number;
  end: number;
  /** The attribute that carries the default value, when the element has it. */
  target: XmlAttribute | undefined;
}

export interface ParameterAttributesDeclaration {
  element: XmlElement;
  attribute: XmlAttribute;
  names: ParameterAttributeName[];
}

export interface EntityInfo {
  name: string;
  element: XmlElement;
  nameAttribute: XmlAttribute | undefined;
}

export interface ScenarioModel {
  document: XmlDocument;
  groups: ManeuverGroupInfo[];
  references: ScenarioReferenceInfo[];
  entities: EntityInfo[];
  declarations: ParameterAttributesDeclaration[];
  /** Storyboard structure for outlines: Storyboard, Story, Act elements. */
  structure: XmlElement[];
}

export function parseParameterAttributeNames(element: XmlElement, declaration: XmlAttribute): ParameterAttributeName[] {
  const names: ParameterAttributeName[] = [];
  const pattern = /[^,]+/g;
  // Offsets are exact when the raw value holds no entity references, which is the case for names.
  for (let match = pattern.exec(declaration.value); match; match = pattern.exec(declaration.value)) {
    const leading = match[0].length - match[0].trimStart().length;
    const name = match[0].trim();
    if (!name) continue;
    const start = declaration.valueStart + match.index + leading;
    const target = name === PARAMETER_ATTRIBUTES ? undefined : attribute(element, name);
    names.push({ name, start, end: start + name.length, target });
  }
  return names;
}

/** Where `name` is listed in the element's `parameterAttributes`, if it is. */
export function listedName(element: XmlElement, name: string): ParameterAttributeName | undefined {
  const declaration = attribute(element, PARAMETER_ATTRIBUTES);
  return declaration ? parseParameterAttributeNames(element, declaration).find((entry) => entry.name === name) : undefined;
}

const STRUCTURE_ELEMENTS = new Set(['Storyboard', 'Story', 'Act', 'Init']);

/** Reads the modular-scenario structure of a parsed document. */
export function buildModel(document: XmlDocument): ScenarioModel {
  const groups: ManeuverGroupInfo[] = [];
  const references: ScenarioReferenceInfo[] = [];
  const entities: EntityInfo[] = [];
  const declarations: ParameterAttributesDeclaration[] = [];
  const structure: XmlElement[] = [];
  if (!document.root) return { document, groups, references, entities, declarations, structure };

  const visit = (element: XmlElement) => {
    const declaration = attribute(element, PARAMETER_ATTRIBUTES);
    if (declaration) declarations.push({ element, attribute: declaration, names: parseParameterAttributeNames(element, declaration) });
    switch (element.name) {
      case 'ManeuverGroup':
        groups.push(readGroup(element, references));
        break;
      case 'ScenarioObject': {
        const nameAttribute = attribute(element, 'name');
        entities.push({ name: nameAttribute?.value ?? '', element, nameAttribute });
        break;
      }
      default:
        if (STRUCTURE_ELEMENTS.has(element.name)) structure.push(element);
    }
  };
  // One walk in document order with an explicit stack; no list of every element is made.
  const scenarioReferences: XmlElement[] = [];
  const stack: XmlElement[] = [document.root];
  while (stack.length > 0) {
    const element = stack.pop() as XmlElement;
    visit(element);
    if (element.name === 'ScenarioReference') scenarioReferences.push(element);
    for (let i = element.children.length - 1; i >= 0; i--) stack.push(element.children[i]);
  }
  // References found outside any group still count, so that the editor can flag them.
  if (scenarioReferences.length > references.length) {
    const known = new Set(references.map((reference) => reference.element));
    for (const element of scenarioReferences) if (!known.has(element)) references.push(readReference(element, undefined));
  }
  references.sort((a, b) => a.element.start - b.element.start);
  return { document, groups, references, entities, declarations, structure };
}

// The last model read from each parse, from which the model of the next parse after a value edit is carried.
const lastModels = coreMemo<XmlDocument, ScenarioModel>('lastScenarioModels');

/**
 * `buildModel`, carried over from the previous parse's model when `document` was re-parsed from it after an
 * edit inside one attribute value (the elements mapped, offsets moved, the edited element's entries read again);
 * the same model again for a parse already read.
 */
export function readModel(document: XmlDocument): ScenarioModel {
  // A parse read again (a change that left the text as it was, a generation that changed another file) has its model.
  const known = lastModels.get(document);
  if (known) return known;
  const edit = valueEditOf(document);
  const previous = edit && lastModels.get(edit.previous);
  const model = edit && previous ? carryModel(previous, edit, document) : buildModel(document);
  lastModels.set(document, model);
  return model;
}

function carryModel(previous: ScenarioModel, edit: ValueEdit, document: XmlDocument): ScenarioModel {
  const elementOf = edit.elementOf;
  const attributeOf = (element: XmlElement, attr: XmlAttribute | undefined) => (attr ? edit.attributeOf(element, attr) : undefined);
  const edited = edit.previousElement;
  // What refers only to elements the new tree shares (wholly before the edit) is taken as it is.
  const shared = edit.shared;
  const carryReference = (reference: ScenarioReferenceInfo, outerGroup: ManeuverGroupInfo | undefined): ScenarioReferenceInfo => {
    if (shared(reference.element) && outerGroup === reference.outerGroup) return reference;
    const touched =
      reference.element === edited ||
      reference.groupReferences.some(
        (group) => group.element === edited || group.parameters.some((parameter) => parameter.element === edited),
      );
    if (touched) return readReference(elementOf(reference.element), outerGroup);
    return {
      fileName: reference.fileName,
      element: elementOf(reference.element),
      fileAttribute: attributeOf(reference.element, reference.fileAttribute),
      groupReferences: reference.groupReferences.map((group) => ({
        name: group.name,
        element: elementOf(group.element),
        nameAttribute: attributeOf(group.element, group.nameAttribute),
        parameters: group.parameters.map((parameter) => ({
          key: parameter.key,
          value: parameter.value,
          element: elementOf(parameter.element),
          keyAttribute: attributeOf(parameter.element, parameter.keyAttribute),
          valueAttribute: attributeOf(parameter.element, parameter.valueAttribute),
        })),
      })),
      outerGroup,
    };
  };
  const groups = new Map<ManeuverGroupInfo, ManeuverGroupInfo>();
  const references = new Map<ScenarioReferenceInfo, ScenarioReferenceInfo>();
  for (const group of previous.groups) {
    if (shared(group.element)) {
      // Its references lie inside it: shared too, each taken as it is by carryReference below.
      groups.set(group, group);
      continue;
    }
    const nameAttribute = attributeOf(group.element, group.nameAttribute);
    const copy: ManeuverGroupInfo = {
      name: group.element === edited ? (nameAttribute?.value ?? '') : group.name,
      element: elementOf(group.element),
      nameAttribute,
      actor: group.actor && elementOf(group.actor),
      references: [],
    };
    groups.set(group, copy);
    for (const reference of group.references) {
      const carried = carryReference(reference, copy);
      references.set(reference, carried);
      copy.references.push(carried);
    }
  }
  return {
    document,
    groups: [...groups.values()],
    references: previous.references.map(
      (reference) => references.get(reference) ?? carryReference(reference, reference.outerGroup && groups.get(reference.outerGroup)),
    ),
    entities: previous.entities.map((entity) => {
      if (shared(entity.element)) return entity;
      const nameAttribute = attributeOf(entity.element, entity.nameAttribute);
      return {
        name: entity.element === edited ? (nameAttribute?.value ?? '') : entity.name,
        element: elementOf(entity.element),
        nameAttribute,
      };
    }),
    declarations: previous.declarations.map((declaration) => {
      if (shared(declaration.element)) return declaration;
      const element = elementOf(declaration.element);
      const declared = attributeOf(declaration.element, declaration.attribute) as XmlAttribute;
      if (declaration.element === edited) return { element, attribute: declared, names: parseParameterAttributeNames(element, declared) };
      const names = declaration.names.map((name) => ({
        name: name.name,
        start: edit.shift(name.start),
        end: edit.shift(name.end),
        target: attributeOf(declaration.element, name.target),
      }));
      return { element, attribute: declared, names };
    }),
    structure: previous.structure.every(shared) ? previous.structure : previous.structure.map(elementOf),
  };
}

function readGroup(element: XmlElement, allReferences: ScenarioReferenceInfo[]): ManeuverGroupInfo {
  const nameAttribute = attribute(element, 'name');
  const group: ManeuverGroupInfo = {
    name: nameAttribute?.value ?? '',
    element,
    nameAttribute,
    actor: undefined,
    references: [],
  };
  const actors = element.children.find((child) => child.name === 'Actors');
  group.actor = actors?.children.find((child) => child.name === 'EntityRef');
  if (!group.actor) {
    for (const candidate of descendants(element)) {
      if (candidate.name === 'ScenarioReference') break;
      if (candidate.name === 'EntityRef') {
        group.actor = candidate;
        break;
      }
    }
  }
  for (const child of element.children) {
    if (child.name === 'ScenarioReference') {
      const reference = readReference(child, group);
      group.references.push(reference);
      allReferences.push(reference);
    }
  }
  return group;
}

function readReference(element: XmlElement, outerGroup: ManeuverGroupInfo | undefined): ScenarioReferenceInfo {
  const fileAttribute = attribute(element, 'scenarioFileName');
  const groupReferences: ManeuverGroupReferenceInfo[] = [];
  for (const child of element.children) {
    if (child.name !== 'ManeuverGroupReference') continue;
    const nameAttribute = attribute(child, 'maneuverGroupName');
    const parameters: ParameterReferenceInfo[] = [];
    for (const parameter of child.children) {
      if (parameter.name !== 'ParameterReference') continue;
      const keyAttribute = attribute(parameter, 'key');
      const valueAttribute = attribute(parameter, 'value');
      parameters.push({
        key: keyAttribute?.value.trim() ?? '',
        value: valueAttribute?.value ?? '',
        element: parameter,
        keyAttribute,
        valueAttribute,
      });
    }
    groupReferences.push({ name: nameAttribute?.value.trim() ?? '', element: child, nameAttribute, parameters });
  }
  return {
    fileName: fileAttribute?.value.trim() ?? '',
    element,
    fileAttribute,
    groupReferences,
    outerGroup,
  };
}

export function parseScenario(text: string): ScenarioModel {
  return buildModel(parseXml(text));
}

/** Groups of a source in document order, by name; the first of a name wins (SPEC 4.1). */
export function findGroup(model: ScenarioModel, name: string): ManeuverGroupInfo | undefined {
  return model.groups.find((group) => group.name === name);
}

/** Whether the scenario holds references and so must be flattened before its groups are used. */
export function isModular(model: ScenarioModel): boolean {
  return model.references.length > 0;
}
