import { SimpleType, ValueAlternative } from './model';

/** `$name`: the schemas' `parameter` type. */
export const PARAMETER_PATTERN = /^\$[A-Za-z_][A-Za-z0-9_]*$/;
/** `${...}`: the schemas' `expression` type (1.1 and later). */
export const EXPRESSION_PATTERN = /^\$\{[ A-Za-z0-9_+\-*/%$().,]*\}$/;

const DOUBLE = /^[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?$|^(-?INF|\+INF|NaN)$/;
const INTEGER = /^[+-]?\d+$/;
const DATE_TIME = /^-?\d{4,}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d+)?(Z|[+-]\d\d:\d\d)?$/;

const compiledPatterns = new Map<string, RegExp>();

function patternOf(xsdPattern: string): RegExp {
  let compiled = compiledPatterns.get(xsdPattern);
  if (!compiled) {
    // XSD patterns are anchored at both ends; the schemas' patterns use only syntax JavaScript shares.
    compiled = new RegExp(`^(?:${xsdPattern})$`);
    compiledPatterns.set(xsdPattern, compiled);
  }
  return compiled;
}

function inRange(text: string, low: number, high: number): boolean {
  if (!INTEGER.test(text)) return false;
  const value = Number(text);
  return value >= low && value <= high;
}

/** Whether `value` is valid for a built-in type; XSD collapses white space around these. */
function builtinAccepts(builtin: NonNullable<ValueAlternative['builtin']>, value: string): boolean {
  const text = builtin === 'string' ? value : value.trim();
  switch (builtin) {
    case 'string':
      return true;
    case 'boolean':
      return text === 'true' || text === 'false' || text === '1' || text === '0';
    case 'double':
      return DOUBLE.test(text);
    case 'int':
      return inRange(text, -2147483648, 2147483647);
    case 'unsignedInt':
      return inRange(text, 0, 4294967295);
    case 'unsignedShort':
      return inRange(text, 0, 65535);
    case 'dateTime':
      return DATE_TIME.test(text);
  }
}

export interface ValueCheck {
  valid: boolean;
  /** A valid enumeration value that the schema marks deprecated. */
  deprecated?: boolean;
  /** Valid only as an expression, which this version's type does not admit (1.0). */
  expressionNotInVersion?: boolean;
}

// The common answers are shared (and frozen): a check runs for every attribute of every file read.
const VALID: ValueCheck = Object.freeze({ valid: true });
const INVALID: ValueCheck = Object.freeze({ valid: false });

function matchesAnyPattern(patterns: readonly string[], value: string): boolean {
  for (let i = 0; i < patterns.length; i++) if (patternOf(patterns[i]).test(value)) return true;
  return false;
}

export function checkValue(type: SimpleType, value: string): ValueCheck {
  if (type.parameter && PARAMETER_PATTERN.test(value)) return VALID;
  if (type.expression && EXPRESSION_PATTERN.test(value)) return VALID;
  const alternatives = type.alternatives;
  for (let i = 0; i < alternatives.length; i++) {
    const alternative = alternatives[i];
    if (alternative.builtin && builtinAccepts(alternative.builtin, value)) return VALID;
    if (alternative.enumeration?.includes(value)) return { valid: true, deprecated: alternative.deprecatedValues?.includes(value) };
    if (alternative.patterns && matchesAnyPattern(alternative.patterns, value)) return VALID;
  }
  if (!type.expression && type.parameter && EXPRESSION_PATTERN.test(value)) return { valid: false, expressionNotInVersion: true };
  return INVALID;
}

/**
 * The value a person meant, written as the type wants it, where the slip is one of form: a date without its time
 * (`2020-02-17`, the ScenarioRunner examples' FileHeader), a blank for the `T`, `True` for `true`, a decimal comma.
 */
export function repairedValue(type: SimpleType, value: string): string | undefined {
  const text = value.trim();
  const candidates = [
    /^-?\d{4,}-\d\d-\d\d$/.test(text) ? `${text}T00:00:00` : undefined,
    /^-?\d{4,}-\d\d-\d\d +\d\d:\d\d:\d\d/.test(text) ? text.replace(/ +/, 'T') : undefined,
    /^(true|false)$/i.test(text) ? text.toLowerCase() : undefined,
    /^[+-]?\d+,\d+$/.test(text) ? text.replace(',', '.') : undefined,
  ];
  return candidates.find((candidate) => candidate !== undefined && candidate !== value && checkValue(type, candidate).valid);
}

export function enumerationValues(type: SimpleType): string[] {
  return type.alternatives.flatMap((alternative) => alternative.enumeration ?? []);
}

export function builtinOf(type: SimpleType): ValueAlternative['builtin'] | undefined {
  return type.alternatives.find((alternative) => alternative.builtin)?.builtin;
}

/** What a type allows, in words: `a double, $parameter or ${expression}`. */
export function describeType(type: SimpleType): string {
  const parts: string[] = [];
  for (const alternative of type.alternatives) {
    if (alternative.builtin) parts.push(alternative.builtin === 'string' ? 'any text' : `xsd:${alternative.builtin}`);
    if (alternative.enumeration) parts.push(`one of ${alternative.enumeration.join(', ')}`);
    if (alternative.patterns) parts.push(`text matching ${alternative.patterns.join(' or ')}`);
  }
  if (type.parameter) parts.push('a $parameter');
  if (type.expression) parts.push('an ${expression}');
  return parts.join(', ');
}
