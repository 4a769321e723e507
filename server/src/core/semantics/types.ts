import { XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { ValueForm } from './expressionParser';
import { ParameterType } from './values';

/**
 * The OpenSCENARIO semantic model of one parsed document (synchronous, no file access): parameter
 * and variable scopes with their declarations, every use of a parameter, catalog locations and
 * references, entities and storyboard elements. Catalog files are resolved separately
 * (./catalogs.ts), since that reads other files. See ./index.ts for the API the features use.
 */

export type DeclarationKind = 'parameter' | 'variable';

export interface Declaration {
  kind: DeclarationKind;
  name: string;
  /** The declared type; undefined when `parameterType`/`variableType` is missing or unknown. */
  type: ParameterType | undefined;
  writtenType: string | undefined;
  /** The value as written (decoded), or '' when the attribute is missing. */
  value: string;
  element: XmlElement;
  nameAttribute: XmlAttribute | undefined;
  valueAttribute: XmlAttribute | undefined;
  typeAttribute: XmlAttribute | undefined;
  scope: Scope;
  /** Position among the declarations of its scope, in document order. */
  index: number;
}

/** The subtree of an element holding a `ParameterDeclarations` (or, at the root, `VariableDeclarations`). */
export interface Scope {
  /** The element whose subtree sees the declarations (`OpenSCENARIO`, `Story`, `Vehicle`, ...). */
  element: XmlElement;
  parent: Scope | undefined;
  children: Scope[];
  declarations: Declaration[];
  /** The first declaration of each name (a second one of a name in one scope is a problem). */
  byName: Map<string, Declaration>;
  /** The last declaration of each name: the one esmini reads (core/profiles/esmini.ts valueRules.redeclaration). */
  lastByName: Map<string, Declaration>;
  /** True for an entry of a `Catalog` (its parameters are set by a CatalogReference's assignments). */
  catalogEntry: boolean;
}

/** Where a value refers to a parameter: a `$name` (whole value or inside `${...}`) or a `parameterRef`. */
export interface ParameterUse {
  name: string;
  /** Offsets of `$name` (or of the plain name of a parameterRef) in the document. */
  start: number;
  end: number;
  element: XmlElement;
  attribute: XmlAttribute;
  /** The declaration it resolves to in its scope; undefined when none is visible. */
  declaration: Declaration | undefined;
  via: 'value' | 'expression' | 'parameterRef';
}

/** An attribute whose value is a `$name` or a `${...}`. */
export interface ValueSite {
  element: XmlElement;
  attribute: XmlAttribute;
  form: Exclude<ValueForm, { kind: 'literal' }>;
  scope: Scope;
  /** For the value of a declaration: that declaration (it sees only the earlier ones of its scope). */
  declaration: Declaration | undefined;
}

export interface CatalogLocationInfo {
  /** `VehicleCatalog`, `ControllerCatalog`, ... */
  kind: string;
  directory: XmlElement;
  pathAttribute: XmlAttribute | undefined;
}

export interface ParameterAssignmentInfo {
  element: XmlElement;
  parameterRef: XmlAttribute | undefined;
  valueAttribute: XmlAttribute | undefined;
}

export interface CatalogReferenceInfo {
  element: XmlElement;
  catalogNameAttribute: XmlAttribute | undefined;
  entryNameAttribute: XmlAttribute | undefined;
  assignments: ParameterAssignmentInfo[];
}

export interface NamedElement {
  name: string;
  element: XmlElement;
  nameAttribute: XmlAttribute | undefined;
}

export interface StoryboardReferenceInfo {
  element: XmlElement;
  refAttribute: XmlAttribute;
  /** `story`, `act`, `maneuverGroup`, `maneuver`, `event` or `action`. */
  type: string | undefined;
}

export interface SemanticModel {
  document: XmlDocument;
  /** The root scope (`OpenSCENARIO`); undefined without a root element. */
  root: Scope | undefined;
  scopes: Scope[];
  declarations: Declaration[];
  /** Variables (1.2+ `VariableDeclarations`), by name: the first of each name. */
  variables: Map<string, Declaration>;
  uses: ParameterUse[];
  sites: ValueSite[];
  /** The site of each `$`-valued attribute. */
  siteOf: Map<XmlAttribute, ValueSite>;
  /** Uses of each declaration, filled while building. */
  usesOf: Map<Declaration, ParameterUse[]>;
  catalogLocations: CatalogLocationInfo[];
  catalogReferences: CatalogReferenceInfo[];
  /** The `Catalog` of a catalog file, or undefined for a scenario. */
  catalog: XmlElement | undefined;
  entities: NamedElement[];
  /** Whether the file declares `Entities` (a catalog file does not, so entity names are not checked there). */
  hasEntities: boolean;
  /** Story, Act, ManeuverGroup, Maneuver, Event and Action elements with their names. */
  storyboardElements: NamedElement[];
  /** The same, by name. */
  storyboardByName: Map<string, NamedElement[]>;
  storyboardReferences: StoryboardReferenceInfo[];
  variableReferences: { element: XmlElement; attribute: XmlAttribute; declaration: Declaration | undefined }[];
  /** Every attribute that names an entity (ENTITY_REFERENCE_ATTRIBUTES), in document order. */
  entityReferences: { element: XmlElement; attribute: XmlAttribute }[];
  /** The scope each element belongs to (its own for a scope holder). */
  scopeOf(element: XmlElement): Scope | undefined;
}
