import { attribute, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import {
  convertValue,
  evaluateTree,
  ExpressionError,
  normalizeParameterType,
  ParameterType,
  ParameterValue,
  parseLiteral,
  TypedValue,
  ValueForm,
  valueForm,
} from './expressions';

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

/** Attributes that name an entity (ASAM OpenSCENARIO 1.x: EntityRef and the actions/positions that take one). */
export const ENTITY_REFERENCE_ATTRIBUTES: ReadonlySet<string> = new Set(['entityRef', 'masterEntityRef']);

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

/** Elements whose `parameterRef` names a parameter of the enclosing scopes (1.0-1.1 parameter actions and conditions). */
const PARAMETER_REF_ELEMENTS = new Set(['ParameterCondition', 'ParameterAction', 'ParameterSetAction', 'ParameterModifyAction']);
const VARIABLE_REF_ELEMENTS = new Set(['VariableCondition', 'VariableAction']);
/** Attributes that name a parameter or variable rather than use its value; esmini accepts them with a leading `$`. */
const NAME_REFERENCE_ATTRIBUTES = new Set(['parameterRef', 'variableRef']);

/**
 * CARLA scenario_runner reads a StopTrigger condition named `criteria_NAME` as its evaluation
 * criterion NAME, whose ParameterCondition `parameterRef` is an argument name, not a parameter
 * (scenario_runner srunner/tools/openscenario_parser.py, `convert_condition_to_atomic`).
 */
function isCarlaCriterion(element: XmlElement): boolean {
  for (let current = element.parent; current; current = current.parent) {
    if (current.name === 'Condition') return attribute(current, 'name')?.value.startsWith('criteria_') ?? false;
  }
  return false;
}

/** The name a `parameterRef`/`variableRef` gives, without the `$` some files write, and its offsets. */
export function referencedName(attr: XmlAttribute): { name: string; start: number; end: number } {
  const leading = attr.value.length - attr.value.trimStart().length;
  const dollar = attr.value.trimStart().startsWith('$') ? 1 : 0;
  const name = attr.value.trim().slice(dollar);
  const start = attr.valueStart + leading + dollar;
  return { name, start, end: start + name.length };
}

/** Builds the model of a document; linear in its size. */
export function buildSemanticModel(document: XmlDocument): SemanticModel {
  const scopes: Scope[] = [];
  const declarations: Declaration[] = [];
  const variables = new Map<string, Declaration>();
  const uses: ParameterUse[] = [];
  const sites: ValueSite[] = [];
  const siteOf = new Map<XmlAttribute, ValueSite>();
  const usesOf = new Map<Declaration, ParameterUse[]>();
  const catalogLocations: CatalogLocationInfo[] = [];
  const catalogReferences: CatalogReferenceInfo[] = [];
  const entities: NamedElement[] = [];
  const storyboardElements: NamedElement[] = [];
  const storyboardByName = new Map<string, NamedElement[]>();
  const storyboardReferences: StoryboardReferenceInfo[] = [];
  const variableReferences: SemanticModel['variableReferences'] = [];
  const entityReferences: SemanticModel['entityReferences'] = [];
  const scopeByElement = new Map<XmlElement, Scope>();
  let catalog: XmlElement | undefined;
  let hasEntities = false;
  const rootElement = document.root;

  const model: SemanticModel = {
    document,
    root: undefined,
    scopes,
    declarations,
    variables,
    uses,
    sites,
    siteOf,
    usesOf,
    catalogLocations,
    catalogReferences,
    catalog,
    entities,
    hasEntities,
    storyboardElements,
    storyboardByName,
    storyboardReferences,
    variableReferences,
    entityReferences,
    scopeOf(element) {
      for (let current: XmlElement | undefined = element; current; current = current.parent) {
        const scope = scopeByElement.get(current);
        if (scope) return scope;
      }
      return undefined;
    },
  };
  if (!rootElement) return model;

  const declare = (scope: Scope, element: XmlElement, kind: DeclarationKind) => {
    const nameAttribute = attribute(element, 'name');
    const typeAttribute = attribute(element, kind === 'parameter' ? 'parameterType' : 'variableType');
    const declaration: Declaration = {
      kind,
      name: nameAttribute?.value.trim() ?? '',
      type: normalizeParameterType(typeAttribute?.value),
      writtenType: typeAttribute?.value,
      value: attribute(element, 'value')?.value ?? '',
      element,
      nameAttribute,
      valueAttribute: attribute(element, 'value'),
      typeAttribute,
      scope,
      index: scope.declarations.length,
    };
    if (kind === 'parameter') {
      scope.declarations.push(declaration);
      if (!scope.byName.has(declaration.name)) scope.byName.set(declaration.name, declaration);
    } else if (!variables.has(declaration.name)) {
      variables.set(declaration.name, declaration);
    }
    declarations.push(declaration);
    usesOf.set(declaration, []);
    return declaration;
  };

  const declarationByElement = new Map<XmlElement, Declaration>();
  /** Opens the scope an element holds, declaring its parameters before anything below it is read. */
  const enter = (element: XmlElement, current: Scope | undefined): Scope | undefined => {
    const holdsDeclarations = element.children.some((child) => child.name === 'ParameterDeclarations');
    const isCatalogEntry = element.parent !== undefined && element.parent.name === 'Catalog';
    if (!holdsDeclarations && element !== rootElement && !isCatalogEntry) return current;
    const scope: Scope = { element, parent: current, children: [], declarations: [], byName: new Map(), catalogEntry: isCatalogEntry };
    current?.children.push(scope);
    scopes.push(scope);
    scopeByElement.set(element, scope);
    for (const child of element.children) {
      if (child.name !== 'ParameterDeclarations') continue;
      for (const declaration of child.children) {
        if (declaration.name === 'ParameterDeclaration') declarationByElement.set(declaration, declare(scope, declaration, 'parameter'));
      }
    }
    return scope;
  };

  const addUse = (use: ParameterUse) => {
    uses.push(use);
    if (use.declaration) usesOf.get(use.declaration)?.push(use);
  };

  // One walk in document order with an explicit stack (files nest deeply); two parallel stacks allocate nothing per element.
  const elementStack: XmlElement[] = [rootElement];
  const scopeStack: (Scope | undefined)[] = [undefined];
  while (elementStack.length > 0) {
    const element = elementStack.pop() as XmlElement;
    const scope = enter(element, scopeStack.pop()) as Scope;
    if (element === rootElement) model.root = scope;
    for (let i = element.children.length - 1; i >= 0; i--) {
      elementStack.push(element.children[i]);
      scopeStack.push(scope);
    }
    if (element.name === 'VariableDeclarations') {
      for (const declaration of element.children) if (declaration.name === 'VariableDeclaration') declare(scope, declaration, 'variable');
    }
    const ownDeclaration = declarationByElement.get(element);
    for (const attr of element.attributes) {
      if (attr.value.charCodeAt(0) !== 36 || NAME_REFERENCE_ATTRIBUTES.has(attr.name)) continue;
      // The offsets of a decoded value are exact only when it was written without references.
      const form = valueForm(attr.value, attr.valueStart);
      if (form.kind === 'literal') continue;
      const declaration = ownDeclaration && attr.name === 'value' ? ownDeclaration : undefined;
      const site: ValueSite = { element, attribute: attr, form, scope, declaration };
      sites.push(site);
      siteOf.set(attr, site);
      const names = form.kind === 'parameter' ? [{ name: form.name, start: form.start, end: form.end }] : form.expression.parameters;
      for (const name of names) {
        addUse({
          name: name.name,
          start: name.start,
          end: name.end,
          element,
          attribute: attr,
          declaration: resolveName(scope, name.name, declaration),
          via: form.kind === 'parameter' ? 'value' : 'expression',
        });
      }
    }
    switch (element.name) {
      case 'Catalog':
        if (element.parent === rootElement) catalog = element;
        break;
      case 'Entities':
        hasEntities = true;
        break;
      case 'ScenarioObject':
      case 'EntitySelection': {
        const nameAttribute = attribute(element, 'name');
        entities.push({ name: nameAttribute?.value ?? '', element, nameAttribute });
        break;
      }
      case 'Directory':
        if (element.parent && element.parent.parent?.name === 'CatalogLocations') {
          catalogLocations.push({ kind: element.parent.name, directory: element, pathAttribute: attribute(element, 'path') });
        }
        break;
      case 'CatalogReference': {
        const assignments: ParameterAssignmentInfo[] = [];
        for (const child of element.children) {
          if (child.name !== 'ParameterAssignments') continue;
          for (const assignment of child.children) {
            if (assignment.name === 'ParameterAssignment') {
              assignments.push({ element: assignment, parameterRef: attribute(assignment, 'parameterRef'), valueAttribute: attribute(assignment, 'value') });
            }
          }
        }
        catalogReferences.push({ element, catalogNameAttribute: attribute(element, 'catalogName'), entryNameAttribute: attribute(element, 'entryName'), assignments });
        break;
      }
      case 'StoryboardElementStateCondition': {
        const refAttribute = attribute(element, 'storyboardElementRef');
        if (refAttribute) storyboardReferences.push({ element, refAttribute, type: attribute(element, 'storyboardElementType')?.value });
        break;
      }
      default:
        if (STORYBOARD_ELEMENT_NAMES.has(element.name)) {
          const nameAttribute = attribute(element, 'name');
          const named = { name: nameAttribute?.value ?? '', element, nameAttribute };
          storyboardElements.push(named);
          const sameName = storyboardByName.get(named.name);
          if (sameName) sameName.push(named);
          else storyboardByName.set(named.name, [named]);
        }
    }
    if (PARAMETER_REF_ELEMENTS.has(element.name) && !isCarlaCriterion(element)) {
      const ref = attribute(element, 'parameterRef');
      if (ref && ref.value.trim()) {
        const { name, start, end } = referencedName(ref);
        addUse({ name, start, end, element, attribute: ref, declaration: resolveName(scope, name, undefined), via: 'parameterRef' });
      }
    }
    if (VARIABLE_REF_ELEMENTS.has(element.name)) {
      const ref = attribute(element, 'variableRef');
      if (ref) variableReferences.push({ element, attribute: ref, declaration: undefined });
    }
    for (const attr of element.attributes) if (ENTITY_REFERENCE_ATTRIBUTES.has(attr.name)) entityReferences.push({ element, attribute: attr });
  }
  // Variables are global (declared at the root), so references are resolved once all are known.
  for (const reference of variableReferences) reference.declaration = variables.get(referencedName(reference.attribute).name);
  model.catalog = catalog;
  model.hasEntities = hasEntities;
  return model;
}

/**
 * The declaration `name` resolves to from `scope`: the innermost scope that declares it wins. For the
 * value of a declaration, only the declarations before it in its own scope are visible (a value may
 * use earlier parameters, so no value can depend on itself).
 */
export function resolveName(scope: Scope | undefined, name: string, within: Declaration | undefined): Declaration | undefined {
  for (let current = scope; current; current = current.parent) {
    if (within && current === within.scope) {
      // The first declaration of the name is the one found, when it comes before the value being read.
      const first = current.byName.get(name);
      if (!first || first.index >= within.index) continue;
      for (const candidate of current.declarations) {
        if (candidate.index >= within.index) break;
        if (candidate.name === name) return candidate;
      }
      continue;
    }
    const found = current.byName.get(name);
    if (found) return found;
  }
  return undefined;
}

/** Every declaration visible from a scope (innermost first, shadowed ones left out). */
export function visibleDeclarations(scope: Scope | undefined, within?: Declaration): Declaration[] {
  const seen = new Set<string>();
  const result: Declaration[] = [];
  for (let current = scope; current; current = current.parent) {
    for (const candidate of current.declarations) {
      if (within && current === within.scope && candidate.index >= within.index) break;
      if (seen.has(candidate.name)) continue;
      seen.add(candidate.name);
      result.push(candidate);
    }
  }
  return result;
}

/** Where a value comes from, for a hover. */
export type Provenance =
  | { kind: 'literal' }
  | { kind: 'declaration'; declaration: Declaration }
  | { kind: 'assignment'; declaration: Declaration; assignment: ParameterAssignmentInfo }
  | { kind: 'override'; parameterReference: XmlElement; key: string }
  | { kind: 'carried'; declaration: Declaration; from: string };

export type ValueResult =
  | { ok: true; value: ParameterValue; type: ParameterType; provenance: Provenance }
  | { ok: false; errors: ExpressionError[]; provenance: Provenance };

/**
 * Values set from outside a catalog entry: the `ParameterAssignment`s of the CatalogReference that
 * uses it, by parameter name (each value already evaluated in the referencing file).
 */
export type Assignments = Map<string, { value: TypedValue | undefined; assignment: ParameterAssignmentInfo }>;

/**
 * Evaluates declarations and value sites of one model, memoized. A declaration whose entry is
 * instantiated with assignments gets its own evaluator (one per CatalogReference).
 */
export class Evaluator {
  private readonly declarationValues = new Map<Declaration, ValueResult>();

  constructor(
    readonly model: SemanticModel,
    readonly assignments?: Assignments,
  ) {}

  /** The value of a declaration, converted to its declared type (a string when no type is given). */
  declarationValue(declaration: Declaration): ValueResult {
    const known = this.declarationValues.get(declaration);
    if (known) return known;
    const result = this.computeDeclaration(declaration);
    this.declarationValues.set(declaration, result);
    return result;
  }

  private computeDeclaration(declaration: Declaration): ValueResult {
    const type = declaration.type ?? 'string';
    const assigned = declaration.scope.catalogEntry ? this.assignments?.get(declaration.name) : undefined;
    if (assigned?.value) {
      const provenance: Provenance = { kind: 'assignment', declaration, assignment: assigned.assignment };
      const converted = convertValue(assigned.value, type);
      if ('message' in converted) return { ok: false, errors: [this.errorAt(assigned.assignment.valueAttribute, 'type-mismatch', converted.message)], provenance };
      return { ok: true, value: converted.value, type, provenance };
    }
    const provenance: Provenance = { kind: 'declaration', declaration };
    const attr = declaration.valueAttribute;
    if (!attr) return { ok: false, errors: [this.errorAt(undefined, 'syntax', `the declaration of '${declaration.name}' has no value`, declaration.element)], provenance };
    const site = this.model.siteOf.get(attr);
    if (!site) {
      const literal = parseLiteral(attr.value, type);
      if ('message' in literal) return { ok: false, errors: [this.errorAt(attr, 'type-mismatch', `${literal.message}, but '${declaration.name}' is declared ${declaration.writtenType ?? 'without a type'}`)], provenance };
      return { ok: true, value: literal.value, type, provenance };
    }
    const evaluated = this.evaluateSite(site);
    if (!evaluated.ok) return { ok: false, errors: evaluated.errors, provenance };
    const converted = convertValue({ value: evaluated.value, type: evaluated.type }, type);
    if ('message' in converted) return { ok: false, errors: [this.errorAt(attr, 'type-mismatch', `${converted.message}, but '${declaration.name}' is declared ${declaration.writtenType}`)], provenance };
    return { ok: true, value: converted.value, type, provenance };
  }

  /** The value of a `$name` or `${...}` attribute, with the type the expression yields. */
  evaluateSite(site: ValueSite): ValueResult & { warnings?: ExpressionError[] } {
    const lookup = (name: string, start: number, end: number) => {
      const declaration = resolveName(site.scope, name, site.declaration);
      if (!declaration) return undefined;
      const value = this.declarationValue(declaration);
      if (!value.ok) return { error: { kind: 'unknown-parameter' as const, message: `'${name}' has no valid value (${value.errors[0]?.message ?? 'see its declaration'})`, start, end } };
      return { value: value.value, type: value.type };
    };
    if (site.form.kind === 'parameter') {
      const declaration = resolveName(site.scope, site.form.name, site.declaration);
      if (!declaration) {
        return { ok: false, errors: [{ kind: 'unknown-parameter', message: `parameter '${site.form.name}' is not declared in this scope`, start: site.form.start, end: site.form.end }], provenance: { kind: 'literal' } };
      }
      const value = this.declarationValue(declaration);
      return value.ok ? { ...value, provenance: value.provenance } : { ok: false, errors: [lookup(site.form.name, site.form.start, site.form.end) as { error: ExpressionError }].map((entry) => entry.error), provenance: value.provenance };
    }
    const expression = site.form.expression;
    if (!expression.tree) return { ok: false, errors: expression.errors, provenance: { kind: 'literal' } };
    const warnings: ExpressionError[] = [];
    const evaluated = evaluateTree(expression.tree, lookup, warnings);
    return evaluated.ok ? { ok: true, value: evaluated.value, type: evaluated.type, provenance: { kind: 'literal' }, warnings } : { ok: false, errors: evaluated.errors, provenance: { kind: 'literal' }, warnings };
  }

  /** The value an attribute takes: itself when literal, else its parameter's or expression's value. */
  attributeValue(element: XmlElement, attr: XmlAttribute): ValueResult {
    const site = this.model.siteOf.get(attr);
    if (!site || site.element !== element) return { ok: true, value: attr.value, type: 'string', provenance: { kind: 'literal' } };
    return this.evaluateSite(site);
  }

  /** An attribute's value as text (the literal itself, or the evaluated value); undefined when it cannot be evaluated. */
  textOf(element: XmlElement, attr: XmlAttribute | undefined): string | undefined {
    if (!attr) return undefined;
    const result = this.attributeValue(element, attr);
    return result.ok ? String(result.value) : undefined;
  }

  private errorAt(attr: XmlAttribute | undefined, kind: ExpressionError['kind'], message: string, element?: XmlElement): ExpressionError {
    if (attr) return { kind, message, start: attr.valueStart, end: attr.valueEnd };
    return { kind, message, start: element?.start ?? 0, end: element?.nameEnd ?? 0 };
  }
}
