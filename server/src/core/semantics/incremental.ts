import { attribute, ValueEdit, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { carryElementIndex } from './elementIndex';
import { ExpressionNode } from './expressionParser';
import { ParameterUseCollector } from './parameterUses';
import { Declaration, NamedElement, ParameterUse, Scope, SemanticModel, ValueSite } from './types';
import { coreMemo } from '../memos';

/**
 * Attributes whose value the model reads beyond a `$name` or `${...}` (names resolve, types and
 * `parameterRef`s decide what a use is): an edit of one of them builds the model again.
 */
const STRUCTURAL_ATTRIBUTES: ReadonlySet<string> = new Set([
  'name',
  'parameterType',
  'variableType',
  'parameterRef',
  'variableRef',
  'storyboardElementType',
]);

/**
 * How a carried model relates to the one it was carried from, for check results that carry over
 * (checks/carriedResults.ts): the previous model, each site's index there (undefined for the edited
 * value's fresh sites), the declarations whose element was edited, and how offsets moved. Declarations
 * keep their order and count. Dropped once read, and when the next model is carried from this one,
 * so at most one previous model is kept alive.
 */
export interface ModelCarry {
  previous: SemanticModel;
  siteOrigins: (number | undefined)[];
  /** The declarations of the edited element (a parameter's or a variable's). */
  editedDeclarations: Declaration[];
  removedEnd: number;
  delta: number;
}

const carries = coreMemo<SemanticModel, ModelCarry>('modelCarries');

/** The carry a model was made by, forgotten as it is taken. */
export function takeModelCarry(model: SemanticModel): ModelCarry | undefined {
  const carry = carries.get(model);
  carries.delete(model);
  return carry;
}

/** An expression tree with every offset moved by `delta`. */
function shiftedNode(node: ExpressionNode, delta: number): ExpressionNode {
  // Literals in the parser's field order keep one object shape per kind (a spread would not).
  const start = node.start + delta;
  const end = node.end + delta;
  switch (node.kind) {
    case 'number':
      return { kind: 'number', value: node.value, start, end };
    case 'boolean':
      return { kind: 'boolean', value: node.value, start, end };
    case 'constant':
      return { kind: 'constant', name: node.name, start, end };
    case 'parameter':
      return { kind: 'parameter', name: node.name, start, end };
    case 'name':
      return { kind: 'name', name: node.name, start, end };
    case 'unary':
      return { kind: 'unary', operator: node.operator, operand: shiftedNode(node.operand, delta), start, end };
    case 'binary':
      return {
        kind: 'binary',
        operator: node.operator,
        left: shiftedNode(node.left, delta),
        right: shiftedNode(node.right, delta),
        start,
        end,
      };
    case 'call':
      return { kind: 'call', name: node.name, args: node.args.map((arg) => shiftedNode(arg, delta)), start, end };
    default:
      return unknownNode(node);
  }
}

function unknownNode(node: never): never {
  throw new Error(`an expression node of an unknown kind: ${JSON.stringify(node)}`);
}

/** A value form with every offset moved by `delta` (the form of a value after the edit). */
function shiftedForm(form: ValueSite['form'], delta: number): ValueSite['form'] {
  if (form.kind === 'parameter') return { kind: 'parameter', name: form.name, start: form.start + delta, end: form.end + delta };
  const expression = form.expression;
  return {
    kind: 'expression',
    expression: {
      start: expression.start + delta,
      end: expression.end + delta,
      bodyStart: expression.bodyStart + delta,
      bodyEnd: expression.bodyEnd + delta,
      tree: expression.tree && shiftedNode(expression.tree, delta),
      errors: expression.errors.map((error) => ({
        ...error,
        start: error.start + delta,
        end: error.end + delta,
        ...(error.fix ? { fix: { start: error.fix.start + delta, end: error.fix.end + delta, text: error.fix.text } } : {}),
      })),
      parameters: expression.parameters.map((parameter) => ({
        name: parameter.name,
        start: parameter.start + delta,
        end: parameter.end + delta,
      })),
      names: expression.names.map((name) => ({ name: name.name, start: name.start + delta, end: name.end + delta })),
    },
  };
}

type SiteForm = ValueSite['form'];

/**
 * A site carried over edits: its parsed form is moved by `formDelta` when first read. Most sites of a
 * carried model are never read before the next edit carries them again, so their forms are not copied
 * on each keystroke: the deltas of successive edits add up instead.
 */
class CarriedSite implements ValueSite {
  private moved: SiteForm | undefined;

  constructor(
    readonly element: XmlElement,
    readonly attribute: XmlAttribute,
    readonly scope: Scope,
    readonly declaration: Declaration | undefined,
    readonly baseForm: SiteForm,
    readonly formDelta: number,
  ) {}

  get form(): SiteForm {
    this.moved ??= this.formDelta === 0 ? this.baseForm : shiftedForm(this.baseForm, this.formDelta);
    return this.moved;
  }

  /** The form and delta a carried copy starts from: the unmoved form while it was never read. */
  static origin(site: ValueSite): { form: SiteForm; delta: number } {
    if (site instanceof CarriedSite && site.moved === undefined) return { form: site.baseForm, delta: site.formDelta };
    return { form: site.form, delta: 0 };
  }
}

/** Whether a use or site of `element` comes after those of `attr` of `edited` in the model's walk (document order, then attribute order). */
function comesAfter(element: XmlElement, attr: XmlAttribute | undefined, edited: XmlElement, editedIndex: number): boolean {
  if (element !== edited) return element.start > edited.start;
  return attr === undefined || edited.attributes.indexOf(attr) > editedIndex;
}

/**
 * The model of `document` carried over from `previous`, the model of the parse it was re-parsed from
 * after an edit inside one attribute value: every element and attribute replaced by its counterpart,
 * offsets moved, and the edited value read again. Undefined when the edit can change more than that
 * value's own site and declaration (a name, a type, a reference): then the model is built anew.
 */
export function carrySemanticModel(previous: SemanticModel, edit: ValueEdit, document: XmlDocument): SemanticModel | undefined {
  if (previous.document !== edit.previous || STRUCTURAL_ATTRIBUTES.has(edit.attribute.name)) return undefined;
  const elementOf = edit.elementOf;
  // What refers only to elements the new tree shares (wholly before the edit) is taken as it is.
  const shared = edit.shared;
  const attributeOf = (element: XmlElement, attr: XmlAttribute | undefined) => (attr ? edit.attributeOf(element, attr) : undefined);
  const { previousElement, previousAttribute, delta } = edit;
  const editedIndex = previousElement.attributes.indexOf(previousAttribute);

  const scopes = new Map<Scope, Scope>();
  const scopeByElement = new Map<XmlElement, Scope>();
  for (const scope of previous.scopes) {
    const copy: Scope = {
      element: elementOf(scope.element),
      parent: scope.parent && scopes.get(scope.parent),
      children: [],
      declarations: [],
      byName: new Map(),
      lastByName: new Map(),
      catalogEntry: scope.catalogEntry,
    };
    copy.parent?.children.push(copy);
    scopes.set(scope, copy);
    scopeByElement.set(copy.element, copy);
  }
  const scopeOf = scopeLookup(scopeByElement);
  const model: SemanticModel = {
    document,
    root: previous.root && scopes.get(previous.root),
    scopes: [...scopes.values()],
    declarations: [],
    variables: new Map(),
    uses: [],
    sites: [],
    siteOf: new Map(),
    usesOf: new Map(),
    catalogLocations: previous.catalogLocations.map((location) =>
      shared(location.directory)
        ? location
        : {
            kind: location.kind,
            directory: elementOf(location.directory),
            pathAttribute: attributeOf(location.directory, location.pathAttribute),
          },
    ),
    catalogReferences: previous.catalogReferences.map((reference) =>
      shared(reference.element)
        ? reference
        : {
            element: elementOf(reference.element),
            catalogNameAttribute: attributeOf(reference.element, reference.catalogNameAttribute),
            entryNameAttribute: attributeOf(reference.element, reference.entryNameAttribute),
            assignments: reference.assignments.map((assignment) => ({
              element: elementOf(assignment.element),
              parameterRef: attributeOf(assignment.element, assignment.parameterRef),
              valueAttribute: attributeOf(assignment.element, assignment.valueAttribute),
            })),
          },
    ),
    catalog: previous.catalog && elementOf(previous.catalog),
    entities: [],
    hasEntities: previous.hasEntities,
    storyboardElements: [],
    storyboardByName: new Map(),
    storyboardReferences: previous.storyboardReferences.map((reference) =>
      shared(reference.element)
        ? reference
        : {
            element: elementOf(reference.element),
            refAttribute: attributeOf(reference.element, reference.refAttribute) as XmlAttribute,
            type: reference.type,
          },
    ),
    variableReferences: [],
    // Kept as it is when the edit leaves every one alone: the check of entities skips a list it found declared (checks.ts).
    entityReferences: edit.carriedEntries(
      previous.entityReferences,
      (reference) => reference.element,
      (reference) => ({
        element: elementOf(reference.element),
        attribute: attributeOf(reference.element, reference.attribute) as XmlAttribute,
      }),
    ),
    scopeOf,
  };
  const named = (entry: NamedElement): NamedElement =>
    shared(entry.element)
      ? entry
      : {
          name: entry.name,
          element: elementOf(entry.element),
          nameAttribute: attributeOf(entry.element, entry.nameAttribute),
        };
  model.entities = previous.entities.map(named);
  // Only the entries of elements the new tree does not share are copied, and looked up by halves (lists in document order).
  const copiedEntries = new Map<NamedElement, NamedElement>();
  const copyEntry = (entry: NamedElement) => {
    const copy = named(entry);
    copiedEntries.set(entry, copy);
    return copy;
  };
  model.storyboardElements = edit.carriedEntries(previous.storyboardElements, (entry) => entry.element, copyEntry);
  // Only the lists by name holding a copied entry change; the others are taken as they are (a file may name hundreds).
  model.storyboardByName = new Map(previous.storyboardByName);
  for (const { name } of copiedEntries.keys()) {
    const entries = previous.storyboardByName.get(name);
    if (entries)
      model.storyboardByName.set(
        name,
        edit.carriedEntries(
          entries,
          (entry) => entry.element,
          (entry) => copiedEntries.get(entry) as NamedElement,
        ),
      );
  }

  // Declarations, in the order they were made; the edited one (its value) is read again.
  const declarations = new Map<Declaration, Declaration>();
  let ownDeclaration: Declaration | undefined;
  const editedDeclarations: Declaration[] = [];
  for (const declaration of previous.declarations) {
    const element = elementOf(declaration.element);
    const valueAttribute = attributeOf(declaration.element, declaration.valueAttribute);
    // A literal in the field order of the model's own (a spread makes slower objects of another shape).
    const copy: Declaration = {
      kind: declaration.kind,
      name: declaration.name,
      type: declaration.type,
      writtenType: declaration.writtenType,
      value: declaration.element === previousElement ? (attribute(element, 'value')?.value ?? '') : declaration.value,
      element,
      nameAttribute: attributeOf(declaration.element, declaration.nameAttribute),
      valueAttribute,
      typeAttribute: attributeOf(declaration.element, declaration.typeAttribute),
      scope: scopes.get(declaration.scope) as Scope,
      index: declaration.index,
    };
    declarations.set(declaration, copy);
    if (declaration.element === previousElement) editedDeclarations.push(copy);
    if (copy.kind === 'parameter') {
      copy.scope.declarations.push(copy);
      if (!copy.scope.byName.has(copy.name)) copy.scope.byName.set(copy.name, copy);
      copy.scope.lastByName.set(copy.name, copy);
      if (declaration.element === previousElement) ownDeclaration = copy;
    } else if (!model.variables.has(copy.name)) {
      model.variables.set(copy.name, copy);
    }
    model.declarations.push(copy);
    model.usesOf.set(copy, []);
  }
  const declarationOf = (declaration: Declaration | undefined) => declaration && declarations.get(declaration);
  model.variableReferences = previous.variableReferences.map((reference) => ({
    element: elementOf(reference.element),
    attribute: attributeOf(reference.element, reference.attribute) as XmlAttribute,
    declaration: declarationOf(reference.declaration),
  }));

  // The edited value's own site and uses, read as the walk reads them, go where the walk put them.
  const fresh: Pick<SemanticModel, 'sites' | 'siteOf' | 'uses' | 'usesOf'> = { sites: [], siteOf: new Map(), uses: [], usesOf: new Map() };
  const scope = scopeOf(edit.element);
  if (scope) new ParameterUseCollector(fresh).visitValue(edit.element, edit.attribute, scope, ownDeclaration);

  const siteOrigins: (number | undefined)[] = [];
  let sitesPlaced = false;
  for (const [index, site] of previous.sites.entries()) {
    if (site.attribute === previousAttribute) continue;
    if (!sitesPlaced && comesAfter(site.element, site.attribute, previousElement, editedIndex)) {
      model.sites.push(...fresh.sites);
      for (let i = 0; i < fresh.sites.length; i++) siteOrigins.push(undefined);
      sitesPlaced = true;
    }
    siteOrigins.push(index);
    // A value before the edit keeps its offsets; one after it moves by the edit's delta when its form is read.
    const origin = CarriedSite.origin(site);
    model.sites.push(
      new CarriedSite(
        elementOf(site.element),
        attributeOf(site.element, site.attribute) as XmlAttribute,
        scopes.get(site.scope) as Scope,
        declarationOf(site.declaration),
        origin.form,
        site.attribute.valueStart >= edit.removedEnd ? origin.delta + delta : origin.delta,
      ),
    );
  }
  if (!sitesPlaced) model.sites.push(...fresh.sites);
  for (let i = siteOrigins.length; i < model.sites.length; i++) siteOrigins.push(undefined);
  for (const site of model.sites) model.siteOf.set(site.attribute, site);

  let usesPlaced = false;
  for (const use of previous.uses) {
    if (use.attribute === previousAttribute) continue;
    if (!usesPlaced && comesAfter(use.element, use.via === 'parameterRef' ? undefined : use.attribute, previousElement, editedIndex)) {
      model.uses.push(...fresh.uses);
      usesPlaced = true;
    }
    const copy: ParameterUse = {
      name: use.name,
      start: use.start >= edit.removedEnd ? use.start + delta : use.start,
      end: use.start >= edit.removedEnd ? use.end + delta : use.end,
      element: elementOf(use.element),
      attribute: attributeOf(use.element, use.attribute) as XmlAttribute,
      declaration: declarationOf(use.declaration),
      via: use.via,
    };
    model.uses.push(copy);
  }
  if (!usesPlaced) model.uses.push(...fresh.uses);
  for (const use of model.uses) if (use.declaration) model.usesOf.get(use.declaration)?.push(use);
  carryElementIndex(previous, model, edit);
  carries.delete(previous);
  carries.set(model, { previous, siteOrigins, editedDeclarations, removedEnd: edit.removedEnd, delta });
  return model;
}

// Made outside carrySemanticModel: a closure there would keep the previous model alive through the new one.
function scopeLookup(scopeByElement: Map<XmlElement, Scope>): (element: XmlElement) => Scope | undefined {
  return (element) => {
    for (let current: XmlElement | undefined = element; current; current = current.parent) {
      const scope = scopeByElement.get(current);
      if (scope) return scope;
    }
    return undefined;
  };
}
