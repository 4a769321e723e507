import { defineDiagnostic, ProblemWording, setByWords } from './definition';

/** A variable's or parameter's `kind`, name and type as written, as the messages name it: `variable 'v' (int)`. */
function targetWords(target: { kind: string; name: string; writtenType: string | undefined }): string {
  return `${target.kind} '${target.name}' (${target.writtenType})`;
}

/** A value a SetAction or condition gives a variable (or parameter) that is no value of its type (`reason`: why not). */
export function variableValueWording(
  text: string,
  target: { kind: string; name: string; writtenType: string | undefined },
  reason: string,
): ProblemWording<'type-mismatch'> {
  return { severity: 'error', code: 'type-mismatch', message: `'${text}' is not a value of ${targetWords(target)}: ${reason}` };
}

/** A ModifyAction of a variable (or parameter) that is no number. */
export function modifyNonNumberWording(target: {
  kind: string;
  name: string;
  writtenType: string | undefined;
}): ProblemWording<'type-mismatch'> {
  return {
    severity: 'error',
    code: 'type-mismatch',
    message: `a ModifyAction adds to or multiplies a number; ${targetWords(target)} is not a number`,
    hint: 'set it with a SetAction',
  };
}

/** Why a parameter's value does not fit an attribute's type. */
export type ValueMismatch =
  /** A whole number written with a fraction of zero for an integer type: one clear meaning, a warning. */
  | { kind: 'fraction'; target: string; whole: number }
  /** A value that does not convert to the attribute's number, boolean or date type. */
  | { kind: 'conversion'; target: string }
  /** Text that the attribute's type (an enumeration, a pattern) does not admit, `expected` describing what it does. */
  | { kind: 'text'; type: string; expected: string };

/** What the check of a `$name` against the attribute it stands in found. */
export interface ParameterSiteFacts {
  /** The parameter's value, formatted. */
  value: string;
  parameter: string;
  /** Its type as declared; undefined where it is declared without one. */
  writtenType: string | undefined;
  mismatch: ValueMismatch;
  /** The attribute, as `Element.attribute`. */
  attribute: string;
  /** The ParameterReference that sets the attribute to the parameter, where an override does. */
  setBy?: string;
}

function mismatchWords(mismatch: ValueMismatch): { reason: string; hint: string } {
  switch (mismatch.kind) {
    case 'fraction':
      return {
        reason: `is a number with a fraction of zero for the attribute's type ${mismatch.target}: the standard wants an integer, esmini reads it as ${mismatch.whole}`,
        hint: `declare the parameter with the value ${mismatch.whole}`,
      };
    case 'conversion':
      return {
        reason: `cannot be converted to the attribute's type ${mismatch.target}`,
        hint: `use a parameter whose value is a ${mismatch.target}, or write the value here`,
      };
    case 'text':
      return {
        reason: `cannot be converted to the attribute's type ${mismatch.type} (${mismatch.expected})`,
        hint: `use a parameter whose value is a ${mismatch.type}, or write the value here`,
      };
  }
}

/** A `$name` whose value does not fit the attribute it stands in: a warning for a whole number written with a fraction of zero. */
export function parameterSiteWording(facts: ParameterSiteFacts): ProblemWording<'type-mismatch'> {
  const declared = facts.writtenType ? `declared ${facts.writtenType}` : 'declared without a type';
  const { reason, hint } = mismatchWords(facts.mismatch);
  const message = `'${facts.value}', the value of parameter '${facts.parameter}' (${declared}), ${reason} (${facts.attribute})`;
  return {
    severity: facts.mismatch.kind === 'fraction' ? 'warning' : 'error',
    code: 'type-mismatch',
    message: facts.setBy === undefined ? message : setByWords(message, facts.setBy),
    hint,
  };
}

/** The related location's note: the parameter's declaration and its value. */
export function parameterDeclaredNote(parameter: string, value: string): string {
  return `'${parameter}' is declared here with the value '${value}'`;
}

/**
 * A value that does not convert to the type that uses it: a variable's value and a `$name` in an attribute are
 * worded here; a value in an expression or a declaration by the expression evaluator (core/semantics/).
 */
export const TYPE_MISMATCH = defineDiagnostic({
  code: 'type-mismatch',
  rule: { description: 'A value converts to the type that uses it.' },
  severity: 'error',
});
