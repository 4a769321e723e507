import { TextDocument } from 'vscode-languageserver-textdocument';
import { FlatSource, LinkedGroupReference, LinkedReference } from './core/flatten';
import { KeyMatch } from './core/keys';
import { PARAMETER_ATTRIBUTES, parseParameterAttributeNames } from './core/model';
import {
  CatalogReferenceResolution,
  catalogReferenceAt,
  Declaration,
  declarationAt,
  ParameterUse,
  parameterUseAt,
  ValueSite,
} from './core/semantics';
import {
  ancestor,
  attributeAt,
  attributeNameContextAt,
  elementNameContextAt,
  openElementAt,
  valueContextAt,
  ValueContext,
} from './core/cursor';
import { SourceRef } from './core/sources';
import { elementAt, parseXml, XmlAttribute, XmlDocument, XmlElement } from './core/xml';
import { groupLinkOf, linkOf } from './analysis';
import { Workspace } from './workspace';

/**
 * "What is at this offset", answered once per request from the file's tolerant tree and its models;
 * definition, hover, references, rename and completion each dispatch on the answer's kind.
 */

/** The attribute under the cursor (its name or its value). */
export interface Hit {
  element: XmlElement;
  attribute: XmlAttribute;
  /** Whether the cursor stands in the value (else in the name). */
  inValue: boolean;
}

/** The ScenarioReference link and group reference a ManeuverGroupReference or ParameterReference belongs to. */
export interface GroupLink {
  link: LinkedReference;
  group: LinkedGroupReference | undefined;
}

export type Target =
  | { kind: 'nothing' }
  /** A CatalogReference's `catalogName` or `entryName` value, or one of its ParameterAssignments' `parameterRef` (an entryName may also be a `$name`). */
  | {
      kind: 'catalogReference';
      part: 'catalogName' | 'entryName' | 'parameterRef';
      resolution: CatalogReferenceResolution;
      attribute: XmlAttribute;
      use: ParameterUse | undefined;
      hit: Hit | undefined;
    }
  /** A `$name` value or a parameterRef; `site` when it is a whole `$name` value. */
  | { kind: 'parameter'; use: ParameterUse; site: ValueSite | undefined; hit: Hit | undefined }
  /** A value written `${...}`; `use` is the name inside it under the cursor. */
  | { kind: 'expression'; site: ValueSite; use: ParameterUse | undefined; hit: Hit }
  /** The name of a ParameterDeclaration (or VariableDeclaration). */
  | { kind: 'declaration'; declaration: Declaration; hit: Hit }
  | { kind: 'fileReference'; hit: Hit; link: LinkedReference | undefined }
  | { kind: 'groupReference'; hit: Hit; linked: GroupLink | undefined }
  | { kind: 'key'; hit: Hit; linked: GroupLink | undefined; match: KeyMatch | undefined }
  | { kind: 'entityReference'; hit: Hit }
  /** A ManeuverGroup's name: the group's own declaration. */
  | { kind: 'groupDeclaration'; hit: Hit }
  /** An overridable attribute at its declaration: a name listed in parameterAttributes, or the attribute's own name. */
  | { kind: 'listedAttribute'; hit: Hit; name: string; start: number; end: number }
  /** Schema territory: a tag name, an attribute name or an attribute value no other kind claims. */
  | { kind: 'elementName'; element: XmlElement }
  | { kind: 'attributeName'; hit: Hit }
  | { kind: 'attributeValue'; hit: Hit };

/** What an attribute names by its place in the tree, whatever its value is written as. */
export type SyntacticTarget = Exclude<Target, { kind: 'catalogReference' | 'parameter' | 'expression' | 'declaration' }>;

function within(attr: XmlAttribute | undefined, offset: number): attr is XmlAttribute {
  return attr !== undefined && offset >= attr.valueStart && offset <= attr.valueEnd;
}

function groupLinkAt(source: FlatSource, groupReference: XmlElement | undefined): GroupLink | undefined {
  const reference = ancestor(groupReference?.parent, 'ScenarioReference');
  const link = reference ? linkOf(source, reference) : undefined;
  return link && groupReference ? { link, group: groupLinkOf(link, groupReference) } : undefined;
}

/** The syntactic kinds: what the attribute under the cursor names, whatever its value is written as. */
export function attributeTarget(source: FlatSource, hit: Hit, offset: number): SyntacticTarget {
  const { element, attribute } = hit;
  if (element.name === 'ScenarioReference' && attribute.name === 'scenarioFileName')
    return { kind: 'fileReference', hit, link: linkOf(source, element) };
  if (element.name === 'ManeuverGroupReference' && attribute.name === 'maneuverGroupName')
    return { kind: 'groupReference', hit, linked: groupLinkAt(source, element) };
  if (element.name === 'ParameterReference' && attribute.name === 'key') {
    const linked = groupLinkAt(source, ancestor(element.parent, 'ManeuverGroupReference'));
    return { kind: 'key', hit, linked, match: linked?.group?.plan?.matches.find((candidate) => candidate.parameter.element === element) };
  }
  if (attribute.name === 'entityRef') return { kind: 'entityReference', hit };
  if (element.name === 'ManeuverGroup' && attribute.name === 'name') return { kind: 'groupDeclaration', hit };
  if (attribute.name === PARAMETER_ATTRIBUTES) {
    const listed = parseParameterAttributeNames(element, attribute).find((name) => offset >= name.start && offset <= name.end);
    if (listed) return { kind: 'listedAttribute', hit, name: listed.name, start: listed.start, end: listed.end };
  } else if (!hit.inValue) {
    const declarationAttribute = element.attributes.find((candidate) => candidate.name === PARAMETER_ATTRIBUTES);
    if (declarationAttribute && parseParameterAttributeNames(element, declarationAttribute).some((name) => name.name === attribute.name)) {
      return { kind: 'listedAttribute', hit, name: attribute.name, start: attribute.nameStart, end: attribute.nameEnd };
    }
  }
  return hit.inValue ? { kind: 'attributeValue', hit } : { kind: 'attributeName', hit };
}

/** What the offset of the file's original text holds. */
export function targetAt(source: FlatSource, offset: number): Target {
  const model = source.original;
  if (!model) return { kind: 'nothing' };
  const found = attributeAt(model.document, offset);
  const hit: Hit | undefined = found && { ...found, inValue: offset >= found.attribute.valueStart && offset <= found.attribute.valueEnd };
  const semantics = source.semantics;
  if (semantics) {
    const use = parameterUseAt(semantics, offset);
    const resolution = catalogReferenceAt(semantics, offset);
    if (resolution) {
      const { reference } = resolution;
      if (within(reference.entryNameAttribute, offset))
        return { kind: 'catalogReference', part: 'entryName', resolution, attribute: reference.entryNameAttribute, use, hit };
      if (within(reference.catalogNameAttribute, offset))
        return { kind: 'catalogReference', part: 'catalogName', resolution, attribute: reference.catalogNameAttribute, use, hit };
      const assignment = reference.assignments.find((candidate) => within(candidate.parameterRef, offset));
      if (assignment?.parameterRef)
        return { kind: 'catalogReference', part: 'parameterRef', resolution, attribute: assignment.parameterRef, use, hit };
    }
    const site = hit?.inValue ? semantics.model.siteOf.get(hit.attribute) : undefined;
    if (site && hit && site.form.kind === 'expression') return { kind: 'expression', site, use, hit };
    if (use) return { kind: 'parameter', use, site, hit };
    const declaration = declarationAt(semantics, offset);
    if (declaration && hit) return { kind: 'declaration', declaration, hit };
  }
  if (hit) return attributeTarget(source, hit, offset);
  const element = elementAt(model.document, offset);
  if (element && offset >= element.start && offset <= element.nameEnd) return { kind: 'elementName', element };
  return { kind: 'nothing' };
}

/** The syntactic kind of the attribute under the cursor, for a feature that has no answer for a parameter written there. */
export function syntacticTarget(source: FlatSource, target: Target, offset: number): SyntacticTarget {
  switch (target.kind) {
    case 'catalogReference':
    case 'parameter':
    case 'expression':
    case 'declaration':
      return target.hit ? attributeTarget(source, target.hit, offset) : { kind: 'nothing' };
    default:
      return target;
  }
}

/** The declaration a target names: through a parameter use, or a declaration's own name. */
export function declarationOf(target: Target): Declaration | undefined {
  switch (target.kind) {
    case 'declaration':
      return target.declaration;
    case 'parameter':
    case 'expression':
    case 'catalogReference':
      return target.use?.declaration;
    default:
      return undefined;
  }
}

/** The parse of the document's current text: the workspace's when it is up to date, else a fresh one. */
export async function currentDocument(workspace: Workspace, ref: SourceRef, document: TextDocument): Promise<XmlDocument> {
  const text = document.getText();
  const source = await workspace.source(ref);
  const parsed = source.original?.document;
  return parsed && parsed.text === text ? parsed : parseXml(text);
}

/** What completion at an offset fills in, read from the current text's tolerant parse (it works while typing). */
export type CompletionTarget =
  | { kind: 'nothing' }
  /** A `$` and a name typed in a value: the parameters in scope. */
  | { kind: 'parameter'; context: ValueContext }
  | { kind: 'catalogReference'; part: 'catalogName' | 'entryName'; context: ValueContext }
  | { kind: 'fileReference'; context: ValueContext }
  | { kind: 'groupReference'; context: ValueContext }
  | { kind: 'key'; context: ValueContext }
  /** A ParameterReference's `value`. */
  | { kind: 'keyValue'; context: ValueContext }
  /** A parameterAttributes list. */
  | { kind: 'listedAttribute'; context: ValueContext }
  | { kind: 'entityReference'; context: ValueContext }
  | { kind: 'attributeValue'; context: ValueContext }
  | { kind: 'attributeName'; tagStart: number; element: string; written: string[]; start: number; prefix: string }
  /** A tag name being typed (or an empty one in element content); `open` is the element it goes into. */
  | { kind: 'elementName'; start: number; prefix: string; open: XmlElement | undefined };

/** The `$` and name typed before the cursor in an attribute value, when the cursor is completing a parameter. */
export function dollarPrefix(context: ValueContext): string | undefined {
  return /\$[A-Za-z0-9_]*$/.exec(context.prefix)?.[0];
}

/** What completion fills in at the offset; the parameter and catalog kinds only where the file has a semantic model. */
export function completionTargetAt(document: XmlDocument, offset: number, semantic: boolean): CompletionTarget {
  const context = valueContextAt(document, offset);
  if (context) {
    const { element, attribute: name } = context;
    if (semantic && dollarPrefix(context) !== undefined) return { kind: 'parameter', context };
    if (semantic && element === 'CatalogReference' && (name === 'catalogName' || name === 'entryName'))
      return { kind: 'catalogReference', part: name, context };
    if (element === 'ScenarioReference' && name === 'scenarioFileName') return { kind: 'fileReference', context };
    if (element === 'ManeuverGroupReference' && name === 'maneuverGroupName') return { kind: 'groupReference', context };
    if (element === 'ParameterReference' && name === 'key') return { kind: 'key', context };
    if (element === 'ParameterReference' && name === 'value') return { kind: 'keyValue', context };
    if (name === PARAMETER_ATTRIBUTES) return { kind: 'listedAttribute', context };
    if (name === 'entityRef') return { kind: 'entityReference', context };
    return { kind: 'attributeValue', context };
  }
  const attributeName = attributeNameContextAt(document, offset);
  if (attributeName) return { kind: 'attributeName', ...attributeName };
  const elementName = elementNameContextAt(document, offset);
  return elementName
    ? { kind: 'elementName', ...elementName, open: openElementAt(document, elementName.start, offset) }
    : { kind: 'nothing' };
}
