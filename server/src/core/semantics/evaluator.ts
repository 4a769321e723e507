import { ValueRule } from '../profiles/facts';
import { attribute, XmlAttribute, XmlElement } from '../xml';
import { ExpressionFact, GluedCause, LiteralMismatch, ValueDifference } from '../diagnostics/expressionFacts';
import { comparedExactly, differenceMatters, esminiRule } from '../diagnostics/simulatorValue';
import { atof, esminiFromTree, EsminiText, esminiExpression, esminiTyped, plainNumber } from './esminiValues';
import { evaluateTree, LookupResult } from './expressionEvaluation';
import { ExpressionError } from './expressionParser';
import { convertValue, formatValue, integralConversionError, ParameterType, ParameterValue, parseLiteral, TypedValue } from './values';
import { resolveName } from './scopes';
import { Declaration, ParameterAssignmentInfo, Scope, SemanticModel, ValueSite } from './types';

/** Where a value comes from, for a hover. */
export type Provenance =
  | { kind: 'literal' }
  | { kind: 'declaration'; declaration: Declaration }
  | { kind: 'assignment'; declaration: Declaration; assignment: ParameterAssignmentInfo }
  | { kind: 'override'; parameterReference: XmlElement; key: string }
  | { kind: 'carried'; declaration: Declaration; from: string };

/**
 * Whose rules compute a value (SPEC 12): the standard's, or esmini's (`modular2simple.simulator` =
 * esmini), which then is the value shown and used while the standard's is named in a warning.
 */
export type Reading = 'standard' | 'esmini';

export type { ValueDifference };

export type ValueResult =
  | { ok: true; value: ParameterValue; type: ParameterType; provenance: Provenance; differs?: ValueDifference }
  | { ok: false; errors: ExpressionError[]; provenance: Provenance };

/**
 * Values set from outside a catalog entry: the `ParameterAssignment`s of the CatalogReference that
 * uses it, by parameter name (each value already evaluated in the referencing file).
 */
export type Assignments = Map<string, { value: TypedValue | undefined; assignment: ParameterAssignmentInfo }>;

/** esmini's rules worth naming in a message (substituting text and writing six decimals explain nothing alone). */
const NAMED_RULES: readonly ValueRule[] = [
  'redeclaration',
  'numbers',
  'textGluing',
  'keywords',
  'remainder',
  'divisionByZero',
  'round',
  'sign',
  'comparisons',
  'failure',
];

/** The rules of esmini's that make its value differ, as a message names them. */
function namedRules(rules: readonly ValueRule[], conversion?: ValueRule): ValueRule[] {
  const named = NAMED_RULES.filter((rule) => rules.includes(rule));
  if (named.length === 0 && conversion) named.push(conversion);
  if (named.length === 0 && rules.includes('resultText')) named.push('resultText');
  return named;
}

function reasonsOf(rules: readonly ValueRule[], conversion?: ValueRule): string[] {
  return namedRules(rules, conversion).map(esminiRule);
}

/** The error a glued text stands for: an unknown bare word, or a string parameter, where a value was expected. */
function gluedCause(error: ExpressionError | undefined): GluedCause | undefined {
  if (error?.kind === 'syntax' && error.fact === 'unknown-name') return error;
  if (error?.kind === 'type-mismatch' && error.fact === 'string-parameter') return error;
  return undefined;
}

/** Whether two values differ beyond the six decimals esmini writes a number with. */
function sameValue(a: ParameterValue, b: ParameterValue): boolean {
  if (typeof a === 'number' && typeof b === 'number') {
    if (Number.isNaN(a) || Number.isNaN(b)) return Number.isNaN(a) && Number.isNaN(b);
    if (!Number.isFinite(a) || !Number.isFinite(b)) return a === b;
    return Math.abs(a - b) <= 5.1e-7 + Math.abs(b) * 1e-15;
  }
  return a === b;
}

/** How an attribute of the standard's type reads esmini's text (a double with atof, a boolean when the text is `true`). */
function readAs(esmini: EsminiText & { ok: true }, type: ParameterType): ParameterValue {
  if (type === 'double' || type === 'int' || type === 'unsignedInt' || type === 'unsignedShort') return esmini.number ?? atof(esmini.text);
  if (type === 'boolean') return esmini.text === 'true';
  return esmini.text;
}

/** A declaration's value that is no value of its declared type. */
function declaredValue(declaration: Declaration, mismatch: LiteralMismatch): ExpressionFact {
  return { kind: 'type-mismatch', fact: 'declared-value', mismatch, name: declaration.name, writtenType: declaration.writtenType };
}

/** The parameter types esmini declares with an error and no type of its own (esmini 3.6 Parameters.cpp: "Type ... is not supported yet"). */
const ESMINI_UNSUPPORTED_TYPES: ReadonlySet<ParameterType> = new Set<ParameterType>(['unsignedInt', 'unsignedShort', 'dateTime']);

/**
 * Evaluates declarations and value sites of one model, memoized. A declaration whose entry is
 * instantiated with assignments gets its own evaluator (one per CatalogReference). Every value is
 * computed by the standard's rules and by esmini's; `reading` chooses the one given as the value.
 */
export class Evaluator {
  private readonly declarationValues = new Map<Declaration, ValueResult>();
  private readonly standardValues = new Map<Declaration, ValueResult>();
  private readonly esminiTexts = new Map<Declaration, EsminiText>();
  private readonly warnings = new Map<Declaration, ExpressionError[]>();
  // A site's value depends only on the model and the assignments, both fixed: each is computed once.
  private readonly siteValues = new Map<ValueSite, ValueResult & { warnings?: ExpressionError[] }>();
  private readonly esminiSiteTexts = new Map<ValueSite, EsminiText>();
  private readonly lenientValues = new Map<ValueSite, { standard: ValueResult & { warnings?: ExpressionError[] }; esmini: EsminiText }>();

  constructor(
    readonly model: SemanticModel,
    readonly assignments?: Assignments,
    readonly reading: Reading = 'standard',
  ) {}

  /** The value of a declaration, converted to its declared type (a string when no type is given). */
  declarationValue(declaration: Declaration): ValueResult {
    const known = this.declarationValues.get(declaration);
    if (known) return known;
    const standard = this.standardDeclaration(declaration);
    let result = standard;
    if (standard.ok) {
      const esmini = this.esminiDeclarationText(declaration);
      const type = declaration.type ?? 'string';
      if (esmini.ok) {
        const typed =
          declaration.type === 'double' && esmini.number !== undefined
            ? { value: esmini.number, rule: 'doubleConversion' as const }
            : esminiTyped(esmini.text, declaration.type);
        if (this.reading === 'esmini') result = { ok: true, value: typed.value, type, provenance: standard.provenance };
        const unsupported = declaration.type !== undefined && ESMINI_UNSUPPORTED_TYPES.has(declaration.type);
        const typeAttribute = declaration.typeAttribute;
        if (unsupported && typeAttribute && standard.provenance.kind === 'declaration') {
          this.warn(declaration, {
            kind: 'simulator',
            fact: 'unsupported-type',
            name: declaration.name,
            type: declaration.type as ParameterType,
            text: esmini.text,
            start: typeAttribute.valueStart,
            end: typeAttribute.valueEnd,
          });
        } else if (!sameValue(standard.value, typed.value)) {
          const differs = {
            standard: formatValue(standard.value),
            esmini: formatValue(typed.value),
            reasons: reasonsOf(esmini.rules, typed.rule),
          };
          result =
            this.reading === 'esmini'
              ? { ok: true, value: typed.value, type, provenance: standard.provenance, differs }
              : { ...standard, differs };
          const attr = declaration.valueAttribute;
          if (
            attr &&
            standard.provenance.kind === 'declaration' &&
            differenceMatters(standard.value, typed.value, declaration.type !== 'double' || this.readExactly(declaration))
          ) {
            this.warn(declaration, {
              kind: 'simulator',
              fact: 'declaration-differs',
              name: declaration.name,
              difference: differs,
              start: attr.valueStart,
              end: attr.valueEnd,
            });
          }
        }
      } else if (
        declaration.valueAttribute &&
        standard.provenance.kind === 'declaration' &&
        this.model.siteOf.get(declaration.valueAttribute)?.form.kind !== 'expression'
      ) {
        this.warn(declaration, {
          kind: 'simulator',
          fact: 'esmini-stops',
          stop: esmini.stop,
          start: declaration.valueAttribute.valueStart,
          end: declaration.valueAttribute.valueEnd,
        });
      }
    } else if (this.reading === 'esmini') result = this.esminiReadingOfRefused(declaration, standard);
    this.declarationValues.set(declaration, result);
    return result;
  }

  /**
   * A literal the standard refuses for its declared type ('time' for a double) that esmini converts all the same
   * (atof, atoi, == 'true'): under the esmini reading the scenario runs with esmini's value, a warning that gives both.
   */
  private esminiReadingOfRefused(declaration: Declaration, standard: ValueResult & { ok: false }): ValueResult {
    const attr = declaration.valueAttribute;
    const type = declaration.type;
    if (
      !attr ||
      standard.provenance.kind !== 'declaration' ||
      (type !== 'double' && type !== 'int' && type !== 'boolean') ||
      this.model.siteOf.get(attr) ||
      !standard.errors.every((error) => error.kind === 'type-mismatch')
    )
      return standard;
    const esmini = this.esminiDeclarationText(declaration);
    if (!esmini.ok) return standard;
    const typed = esminiTyped(esmini.text, type);
    this.warn(declaration, {
      kind: 'simulator',
      fact: 'refused-literal',
      cause: standard.errors[0],
      rules: typed.rule ? ['declarationText', typed.rule] : ['declarationText'],
      text: esmini.text,
      value: formatValue(typed.value),
      type,
      start: attr.valueStart,
      end: attr.valueEnd,
    });
    return { ok: true, value: typed.value, type, provenance: standard.provenance };
  }

  /** Warnings about a declaration's own value: a lenient literal, or a value esmini computes otherwise (after declarationValue). */
  declarationWarnings(declaration: Declaration): ExpressionError[] {
    this.declarationValue(declaration);
    return this.warnings.get(declaration) ?? [];
  }

  private warn(declaration: Declaration, warning: ExpressionError): void {
    const list = this.warnings.get(declaration) ?? [];
    list.push(warning);
    this.warnings.set(declaration, list);
  }

  /** A declaration's value by the standard's rules, whatever the reading (what a rule of the standard alone, such as a ConstraintGroup, is about). */
  standardDeclarationValue(declaration: Declaration): ValueResult {
    return this.reading === 'standard' ? this.declarationValue(declaration) : this.standardDeclaration(declaration);
  }

  /** The value by the standard's rules alone. */
  private standardDeclaration(declaration: Declaration): ValueResult {
    const known = this.standardValues.get(declaration);
    if (known) return known;
    const result = this.computeDeclaration(declaration);
    this.standardValues.set(declaration, result);
    return result;
  }

  private computeDeclaration(declaration: Declaration): ValueResult {
    const type = declaration.type ?? 'string';
    const assigned = declaration.scope.catalogEntry ? this.assignments?.get(declaration.name) : undefined;
    if (assigned?.value) {
      const provenance: Provenance = { kind: 'assignment', declaration, assignment: assigned.assignment };
      const converted = convertValue(assigned.value, type);
      if ('mismatch' in converted)
        return {
          ok: false,
          errors: [
            this.errorAt(assigned.assignment.valueAttribute, {
              kind: 'type-mismatch',
              fact: 'assigned-value',
              mismatch: converted.mismatch,
            }),
          ],
          provenance,
        };
      return { ok: true, value: converted.value, type, provenance };
    }
    const provenance: Provenance = { kind: 'declaration', declaration };
    const attr = declaration.valueAttribute;
    if (!attr)
      return {
        ok: false,
        errors: [
          this.errorAt(undefined, { kind: 'syntax', fact: 'declaration-without-value', name: declaration.name }, declaration.element),
        ],
        provenance,
      };
    const site = this.model.siteOf.get(attr);
    if (!site) {
      const literal = parseLiteral(attr.value, type);
      if ('mismatch' in literal)
        return { ok: false, errors: [this.errorAt(attr, declaredValue(declaration, literal.mismatch))], provenance };
      if (literal.lenient) {
        const leading = attr.value.length - attr.value.trimStart().length;
        const exact = attr.value.length === attr.valueEnd - attr.valueStart;
        const start = exact ? attr.valueStart + leading : attr.valueStart;
        const end = exact ? attr.valueStart + attr.value.trimEnd().length : attr.valueEnd;
        this.warn(declaration, {
          ...literal.lenient,
          start,
          end,
          fix: { start, end, text: literal.lenient.standard },
        });
      }
      return { ok: true, value: literal.value, type, provenance };
    }
    const evaluated =
      site.form.kind === 'expression'
        ? this.lenientSite(site as ValueSite & { form: { kind: 'expression' } }).standard
        : this.standardSite(site);
    if (!evaluated.ok) return { ok: false, errors: evaluated.errors, provenance };
    const integral =
      site.form.kind === 'expression' ? integralConversionError({ value: evaluated.value, type: evaluated.type }, type) : undefined;
    if (integral) return { ok: false, errors: [this.errorAt(attr, declaredValue(declaration, integral))], provenance };
    const converted = convertValue({ value: evaluated.value, type: evaluated.type }, type);
    if ('mismatch' in converted)
      return { ok: false, errors: [this.errorAt(attr, declaredValue(declaration, converted.mismatch))], provenance };
    return { ok: true, value: converted.value, type, provenance };
  }

  /** The text esmini holds for a declaration (Parameters::parseParameterDeclarations keeps every value as text). */
  esminiDeclarationText(declaration: Declaration): EsminiText {
    const known = this.esminiTexts.get(declaration);
    if (known) return known;
    // A declaration met again while its own text is computed names itself: esmini cannot resolve it.
    this.esminiTexts.set(declaration, { ok: false, stop: { stop: 'depends-on-itself', name: declaration.name }, rules: ['failure'] });
    const result = this.computeEsminiText(declaration);
    this.esminiTexts.set(declaration, result);
    return result;
  }

  private computeEsminiText(declaration: Declaration): EsminiText {
    const assigned = declaration.scope.catalogEntry ? this.assignments?.get(declaration.name) : undefined;
    if (assigned?.value) {
      const written = assigned.assignment.valueAttribute?.value;
      return { ok: true, text: written !== undefined && !written.startsWith('$') ? written : String(assigned.value.value), rules: [] };
    }
    const attr = declaration.valueAttribute;
    if (!attr) return { ok: true, text: '', rules: [] };
    const site = this.model.siteOf.get(attr);
    if (!site) return { ok: true, text: attr.value, rules: [], number: plainNumber(attr.value) };
    return this.esminiSiteText(site);
  }

  private esminiName(scope: Scope, name: string, within: Declaration | undefined): EsminiText | undefined {
    const plain = name.startsWith('$') ? name.slice(1) : name;
    const declaration = resolveName(scope, plain, within, true);
    if (!declaration) return undefined;
    const text = this.esminiDeclarationText(declaration);
    // esmini reads the last of two declarations of the name, the standard's references the first.
    return declaration === resolveName(scope, plain, within) ? text : { ...text, rules: [...text.rules, 'redeclaration'] };
  }

  /** The declaration `name` names from `scope` in this evaluator's reading: esmini's is the last of two in one scope. */
  declarationOf(scope: Scope | undefined, name: string, within?: Declaration): Declaration | undefined {
    return resolveName(scope, name, within, this.reading === 'esmini');
  }

  /** The text esmini makes of a `$name` or `${...}` attribute value. */
  esminiSiteText(site: ValueSite): EsminiText {
    const known = this.esminiSiteTexts.get(site);
    if (known) return known;
    const result = this.computeEsminiSiteText(site);
    this.esminiSiteTexts.set(site, result);
    return result;
  }

  private computeEsminiSiteText(site: ValueSite): EsminiText {
    if (site.form.kind === 'parameter') {
      return (
        this.esminiName(site.scope, site.form.name, site.declaration) ?? {
          ok: false,
          stop: { stop: 'unresolved-parameter', name: site.form.name },
          rules: ['failure'],
        }
      );
    }
    const body = site.attribute.value.trimEnd().slice(2);
    const lookup = (name: string) => this.esminiName(site.scope, name, site.declaration);
    const tree = site.form.expression.tree;
    // Most expressions read the same on the tree as in esmini's text, without building any text.
    return (
      (tree && body.endsWith('}') && body.indexOf('}') === body.length - 1 ? esminiFromTree(tree, body.slice(0, -1), lookup) : undefined) ??
      esminiExpression(body, lookup)
    );
  }

  /** The value of a `$name` or `${...}` by the standard's rules, with the lenient forms it accepts (as warnings). */
  private standardSite(site: ValueSite): ValueResult & { warnings?: ExpressionError[] } {
    const lookup = (name: string, start: number, end: number): LookupResult | { error: ExpressionError } | undefined => {
      const declaration = resolveName(site.scope, name, site.declaration);
      if (!declaration) return undefined;
      const value = this.standardDeclaration(declaration);
      if (!value.ok)
        return {
          error: {
            kind: 'unknown-parameter',
            fact: 'no-valid-value',
            name,
            cause: value.errors[0],
            start,
            end,
          },
        };
      const typeAttribute = declaration.typeAttribute;
      if (value.type !== 'string' || !typeAttribute || typeAttribute.value.length !== typeAttribute.valueEnd - typeAttribute.valueStart)
        return { value: value.value, type: value.type };
      return { value: value.value, type: value.type, retype: { start: typeAttribute.valueStart, end: typeAttribute.valueEnd } };
    };
    if (site.form.kind === 'parameter') {
      const declaration = resolveName(site.scope, site.form.name, site.declaration);
      if (!declaration) {
        return {
          ok: false,
          errors: [
            {
              kind: 'unknown-parameter',
              fact: 'undeclared',
              name: site.form.name,
              start: site.form.start,
              end: site.form.end,
            },
          ],
          provenance: { kind: 'literal' },
        };
      }
      const value = this.standardDeclaration(declaration);
      if (value.ok) return value;
      const error = lookup(site.form.name, site.form.start, site.form.end) as { error: ExpressionError };
      return { ok: false, errors: [error.error], provenance: value.provenance };
    }
    const expression = site.form.expression;
    if (!expression.tree) return { ok: false, errors: expression.errors, provenance: { kind: 'literal' } };
    const warnings: ExpressionError[] = [];
    const evaluated = evaluateTree(expression.tree, lookup, warnings);
    return evaluated.ok
      ? { ok: true, value: evaluated.value, type: evaluated.type, provenance: { kind: 'literal' }, warnings }
      : { ok: false, errors: evaluated.errors, provenance: { kind: 'literal' }, warnings };
  }

  /**
   * The value of a `$name` or `${...}` attribute, with the type the expression yields, in this
   * evaluator's reading. Its warnings: the lenient forms, and where esmini computes another value (for
   * the value of a declaration that is reported at the declaration, converted to its type).
   */
  /**
   * The standard's value of a `${...}` with the lenient forms (SPEC 12): where the standard fails on
   * text that esmini glues, the glued text, with a warning whose fix writes it as a literal.
   */
  private lenientSite(site: ValueSite & { form: { kind: 'expression' } }): {
    standard: ValueResult & { warnings?: ExpressionError[] };
    esmini: EsminiText;
  } {
    const known = this.lenientValues.get(site);
    if (known) return known;
    const result = this.computeLenientSite(site);
    this.lenientValues.set(site, result);
    return result;
  }

  private computeLenientSite(site: ValueSite & { form: { kind: 'expression' } }): {
    standard: ValueResult & { warnings?: ExpressionError[] };
    esmini: EsminiText;
  } {
    const standard = this.standardSite(site);
    const esmini = this.esminiSiteText(site);
    const cause = gluedCause(standard.ok ? undefined : standard.errors[0]);
    if (!esmini.ok || !cause || !esmini.rules.includes('textGluing')) return { standard, esmini };
    const whole = { start: site.form.expression.start, end: site.form.expression.end };
    const warning: ExpressionError = {
      kind: 'lenient',
      fact: 'glued-text',
      cause,
      text: esmini.text,
      ...whole,
      // A lone `${$name}` is the plain reference `$name`; anything else becomes the glued literal.
      fix: { ...whole, text: site.form.expression.tree?.kind === 'parameter' ? `$${site.form.expression.tree.name}` : esmini.text },
    };
    return {
      standard: {
        ok: true,
        value: esmini.text,
        type: 'string',
        provenance: { kind: 'literal' },
        warnings: [...(standard.warnings ?? []), warning],
      },
      esmini,
    };
  }

  /**
   * The value evaluateSite gives under the standard reading, without computing esmini's reading where the
   * standard gives a value (an export writes the value and has no use for the differences).
   */
  standardValue(site: ValueSite): ValueResult {
    if (this.reading !== 'standard') return this.evaluateSite(site);
    let standard: ValueResult | undefined;
    if (site.form.kind === 'parameter') {
      const declaration = resolveName(site.scope, site.form.name, site.declaration);
      if (declaration) standard = this.standardDeclaration(declaration);
    } else if (site.form.expression.tree) standard = this.standardSite(site);
    return standard?.ok ? standard : this.evaluateSite(site);
  }

  evaluateSite(site: ValueSite): ValueResult & { warnings?: ExpressionError[] } {
    const known = this.siteValues.get(site);
    if (known) return known;
    const result = this.computeSite(site);
    this.siteValues.set(site, result);
    return result;
  }

  private computeSite(site: ValueSite): ValueResult & { warnings?: ExpressionError[] } {
    if (site.form.kind === 'parameter') {
      const declaration = resolveName(site.scope, site.form.name, site.declaration);
      if (!declaration) return this.standardSite(site);
      const esminis = this.reading === 'esmini' ? resolveName(site.scope, site.form.name, site.declaration, true) : declaration;
      if (!esminis || esminis === declaration) return this.declarationValue(declaration);
      // Declared twice in one scope: esmini reads the last declaration (its value, where it was declared).
      const esmini = this.declarationValue(esminis);
      const standard = this.declarationValue(declaration);
      if (!esmini.ok || !standard.ok || sameValue(esmini.value, standard.value)) return esmini;
      const differs: ValueDifference = {
        standard: formatValue(standard.value),
        esmini: formatValue(esmini.value),
        reasons: reasonsOf(['redeclaration']),
      };
      return { ...esmini, differs };
    }
    const expression = site.form.expression;
    if (!expression.tree) return this.standardSite(site);
    const { standard, esmini } = this.lenientSite(site as ValueSite & { form: { kind: 'expression' } });
    const warnings = [...(standard.warnings ?? [])];
    const whole = { start: expression.start, end: expression.end };
    if (!standard.ok) {
      if (esmini.ok) {
        const errors = standard.errors.map((error, index) =>
          index === 0 ? { ...error, esminiComputes: { text: esmini.text, rules: namedRules(esmini.rules) } } : error,
        );
        return { ...standard, errors, warnings };
      }
      return standard;
    }
    if (!esmini.ok) {
      if (!site.declaration)
        warnings.push({
          kind: 'simulator',
          fact: 'esmini-stops-beside',
          stop: esmini.stop,
          standard: formatValue(standard.value),
          ...whole,
        });
      return { ...standard, warnings };
    }
    const esminiValue = readAs(esmini, standard.type);
    if (sameValue(standard.value, esminiValue)) return this.reading === 'esmini' ? { ...standard, value: esminiValue, warnings } : standard;
    const chosen = this.reading === 'esmini' ? { value: esminiValue } : {};
    const differs: ValueDifference = {
      standard: formatValue(standard.value),
      esmini: formatValue(esminiValue),
      reasons: reasonsOf(esmini.rules),
    };
    if (
      !site.declaration &&
      differenceMatters(standard.value, esminiValue, standard.type !== 'double' || this.comparedExactlyAt(site.element, site.attribute))
    )
      warnings.push({ kind: 'simulator', fact: 'differs', difference: differs, ...whole });
    return { ...standard, ...chosen, differs, warnings };
  }

  /** Whether an attribute's value is compared exactly where it is written (simulatorValue.ts comparedExactly). */
  private comparedExactlyAt(element: XmlElement, attr: XmlAttribute): boolean {
    return comparedExactly(element.name, attr.name, this.textOf(element, attribute(element, 'rule')));
  }

  /**
   * Whether a declaration's value is compared exactly by one of its uses: a whole attribute so compared, or a parameterRef that
   * reads or sets it (a use inside an expression is judged by that expression's own value).
   */
  private readExactly(declaration: Declaration): boolean {
    return (this.model.usesOf.get(declaration) ?? []).some((use) =>
      use.via === 'parameterRef'
        ? use.element.name !== 'ParameterAssignment'
        : use.via === 'value' && this.comparedExactlyAt(use.element, use.attribute),
    );
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
    // A literal is its own text: no result object for each of the many names the checks read.
    const site = this.model.siteOf.get(attr);
    if (!site || site.element !== element) return attr.value;
    const result = this.evaluateSite(site);
    return result.ok ? String(result.value) : undefined;
  }

  private errorAt(attr: XmlAttribute | undefined, fact: ExpressionFact, element?: XmlElement): ExpressionError {
    if (attr) return { ...fact, start: attr.valueStart, end: attr.valueEnd };
    return { ...fact, start: element?.start ?? 0, end: element?.nameEnd ?? 0 };
  }
}
