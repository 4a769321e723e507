import { XmlAttribute, XmlElement } from '../xml';
import { convertValue, evaluateTree, ExpressionError, ParameterType, ParameterValue, parseLiteral, TypedValue } from './expressions';
import { resolveName } from './scopes';
import { Declaration, ParameterAssignmentInfo, SemanticModel, ValueSite } from './types';

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
      if (value.ok) return value;
      const error = lookup(site.form.name, site.form.start, site.form.end) as { error: ExpressionError };
      return { ok: false, errors: [error.error], provenance: value.provenance };
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
