import { LenientFact, LiteralMismatch } from '../diagnostics/expressionFacts';

/**
 * ASAM OpenSCENARIO 1.x parameter values: the declared types, literals read in their XSD lexical
 * forms, and the conversion of a value (an expression's result) to a declared `parameterType`.
 */

export type ParameterType = 'double' | 'int' | 'unsignedInt' | 'unsignedShort' | 'boolean' | 'string' | 'dateTime';

/** A value a parameter or an expression takes. */
export type ParameterValue = number | boolean | string;

/** What the standard's `parameterType` names (1.0 wrote `integer`); undefined for anything else. */
export function normalizeParameterType(written: string | undefined): ParameterType | undefined {
  switch (written?.trim()) {
    case 'double':
      return 'double';
    case 'int':
    case 'integer':
      return 'int';
    case 'unsignedInt':
      return 'unsignedInt';
    case 'unsignedShort':
      return 'unsignedShort';
    case 'boolean':
      return 'boolean';
    case 'string':
      return 'string';
    case 'dateTime':
      return 'dateTime';
    default:
      return undefined;
  }
}

/** A value with the type the standard gives it inside expressions. */
export interface TypedValue {
  value: ParameterValue;
  type: ParameterType;
}

const DOUBLE_TEXT = /^[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$/;

/** The number or boolean a string parameter's text reads as, as esmini and the ASAM OpenSCENARIO API read it. */
export function readStringAsValue(text: string): TypedValue | undefined {
  const trimmed = text.trim();
  if (DOUBLE_TEXT.test(trimmed)) return { value: Number(trimmed), type: 'double' };
  if (trimmed === 'true' || trimmed === 'false') return { value: trimmed === 'true', type: 'boolean' };
  return undefined;
}

const isNumeric = (type: ParameterType) => type === 'double' || type === 'int' || type === 'unsignedInt' || type === 'unsignedShort';

/** Half away from zero, as the standard's round() and C's round() do (esmini uses rint, half to even). */
export function roundHalfAwayFromZero(value: number): number {
  return value < 0 ? -Math.round(-value) : Math.round(value);
}

/** The functions of expressions that the standard and esmini compute alike (round, sign, min and max differ: each evaluator has its own). */
export const SHARED_MATH_FUNCTIONS = {
  floor: Math.floor,
  ceil: Math.ceil,
  sqrt: Math.sqrt,
  pow: Math.pow,
  abs: Math.abs,
  sin: Math.sin,
  cos: Math.cos,
  tan: Math.tan,
  asin: Math.asin,
  acos: Math.acos,
  atan: Math.atan,
} as const satisfies Record<string, (a: number, b: number) => number>;

export type SharedMathFunction = keyof typeof SHARED_MATH_FUNCTIONS;

const INTEGER = /^[+-]?[0-9]+$/;
const DOUBLE = /^[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$|^[+-]?INF$|^NaN$/;
const DATE_TIME = /^-?[0-9]{4,}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}(?:\.[0-9]+)?(?:Z|[+-][0-9]{2}:[0-9]{2})?$/;

const INTEGRAL_WITH_FRACTION = /^([+-]?[0-9]+)\.0*$/;

/** Why a value does not fit a type (worded by core/diagnostics/typeMismatch.ts). */
export type Mismatch = { mismatch: LiteralMismatch };

/**
 * Reads a literal written for a parameter of `type` (XSD lexical forms); why not when it does not fit.
 * `lenient` names a form the standard refuses that has one clear meaning (`-5.0` for an int).
 */
export function parseLiteral(
  text: string,
  type: ParameterType,
): { value: ParameterValue; lenient?: Extract<LenientFact, { fact: 'integral-fraction' }> } | Mismatch {
  const trimmed = text.trim();
  switch (type) {
    case 'double':
      if (!DOUBLE.test(trimmed)) return { mismatch: { fact: 'not-of-type', text, type } };
      return { value: trimmed.endsWith('INF') ? (trimmed.startsWith('-') ? -Infinity : Infinity) : Number(trimmed) };
    case 'int':
    case 'unsignedInt':
    case 'unsignedShort': {
      const integral = INTEGRAL_WITH_FRACTION.exec(trimmed);
      if (integral) {
        const value = Number(integral[1]);
        const standard = String(value);
        const range = checkRange(value, type);
        if (range) return range;
        return { value, lenient: { kind: 'lenient', fact: 'integral-fraction', text: trimmed, type, standard } };
      }
      if (!INTEGER.test(trimmed)) return { mismatch: { fact: 'not-of-type', text, type } };
      return checkRange(Number(trimmed), type) ?? { value: Number(trimmed) };
    }
    case 'boolean':
      if (trimmed === 'true' || trimmed === '1') return { value: true };
      if (trimmed === 'false' || trimmed === '0') return { value: false };
      return { mismatch: { fact: 'not-of-type', text, type } };
    case 'dateTime':
      return DATE_TIME.test(trimmed) ? { value: trimmed } : { mismatch: { fact: 'not-of-type', text, type } };
    case 'string':
      return { value: text };
  }
}

function checkRange(value: number, type: ParameterType): Mismatch | undefined {
  if (
    (type === 'int' && (value < -2147483648 || value > 2147483647)) ||
    (type === 'unsignedInt' && (value < 0 || value > 4294967295)) ||
    (type === 'unsignedShort' && (value < 0 || value > 65535))
  )
    return { mismatch: { fact: 'out-of-range', value, type } };
  return undefined;
}

/**
 * Converts an evaluated value to a declared type. A double given to an integer type is rounded half
 * away from zero (the standard converts expression results to the attribute's type; the rounding rule
 * is this project's choice, stated here). A string target takes the value's text.
 */
export function convertValue(value: TypedValue, target: ParameterType): { value: ParameterValue } | Mismatch {
  if (target === 'string') return { value: String(value.value) };
  if (target === value.type) return { value: value.value };
  if (typeof value.value === 'number' && isNumeric(target)) {
    const converted = target === 'double' ? value.value : roundHalfAwayFromZero(value.value);
    return checkRange(converted, target) ?? { value: converted };
  }
  if (typeof value.value === 'string') return parseLiteral(value.value, target);
  return { mismatch: { fact: 'not-convertible', from: value.type, to: target } };
}

/** The standard's error for an expression value given to an integer type that is not integral (convertValue would round it). */
export function integralConversionError(value: TypedValue, target: ParameterType): LiteralMismatch | undefined {
  if (typeof value.value !== 'number' || (target !== 'int' && target !== 'unsignedInt' && target !== 'unsignedShort')) return undefined;
  if (Number.isInteger(value.value)) return undefined;
  return { fact: 'not-integral', value: formatValue(value.value), type: target };
}

/** A value as the simulator would write it back into the attribute (for hovers and inlay hints). */
export function formatValue(value: ParameterValue): string {
  if (typeof value === 'number') return Number.isInteger(value) ? String(value) : String(Number(value.toPrecision(12)));
  return String(value);
}
