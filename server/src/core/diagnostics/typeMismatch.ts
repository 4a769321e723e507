import { defineDiagnostic, ProblemWording, setByWords } from './definition';
import { ExpressionTypeFact, LiteralMismatch, NumberOperand } from './expressionFacts';

/** A variable's or parameter's `kind`, name and type as written, as the messages name it: `variable 'v' (int)`. */
function targetWords(target: { kind: string; name: string; writtenType: string | undefined }): string {
  return `${target.kind} '${target.name}' (${target.writtenType})`;
}

/** Why a value is no value of a type. */
export function literalMismatchWords(mismatch: LiteralMismatch): string {
  switch (mismatch.fact) {
    case 'not-of-type':
      switch (mismatch.type) {
        case 'double':
          return `'${mismatch.text}' is not a double`;
        case 'boolean':
          return `'${mismatch.text}' is not a boolean (true or false)`;
        case 'dateTime':
          return `'${mismatch.text}' is not a dateTime (YYYY-MM-DDThh:mm:ss)`;
        default:
          return `'${mismatch.text}' is not an ${mismatch.type}`;
      }
    case 'out-of-range':
      switch (mismatch.type) {
        case 'int':
          return `${mismatch.value} is outside the range of an int`;
        case 'unsignedInt':
          return `${mismatch.value} is outside the range of an unsignedInt (0 to 4294967295)`;
        case 'unsignedShort':
          return `${mismatch.value} is outside the range of an unsignedShort (0 to 65535)`;
      }
      break;
    case 'not-convertible':
      return `a ${mismatch.from} value cannot be a ${mismatch.to}`;
    case 'not-integral':
      return `${mismatch.value} is not integral: the standard converts a double to an ${mismatch.type} only when it has no fraction`;
  }
}

function operandWords(operand: NumberOperand): string {
  switch (operand.role) {
    case 'negation':
      return `unary '-'`;
    case 'operator':
      return `'${operand.operator}'`;
    case 'function':
      return `${operand.name}()`;
  }
}

/** The message of a value of the wrong type inside an expression, or of a declared or assigned value that is no value of its type. */
export function expressionTypeMessage(fact: ExpressionTypeFact): string {
  switch (fact.fact) {
    case 'needs-number':
      return `${operandWords(fact.operand)} needs a number, but this is the ${fact.type} ${JSON.stringify(fact.value)}`;
    case 'needs-boolean':
      return `'${fact.operator}' needs a boolean, but this is the ${fact.type} ${JSON.stringify(fact.value)}`;
    case 'date-time-parameter':
      return `the dateTime parameter '${fact.name}' cannot be used in an expression`;
    case 'string-parameter':
      return `the string parameter '${fact.name}' (${JSON.stringify(fact.value)}) cannot be used in an expression`;
    case 'no-real-value':
      return `${fact.name}(${fact.args.join(', ')}) has no real value`;
    case 'assigned-value':
      return literalMismatchWords(fact.mismatch);
    case 'declared-value':
      return `${literalMismatchWords(fact.mismatch)}, but '${fact.name}' is declared ${fact.writtenType ?? 'without a type'}`;
  }
}

/** A value a SetAction or condition gives a variable (or parameter) that is no value of its type (`mismatch`: why not). */
export function variableValueWording(
  text: string,
  target: { kind: string; name: string; writtenType: string | undefined },
  mismatch: LiteralMismatch,
): ProblemWording<'type-mismatch'> {
  return {
    severity: 'error',
    code: 'type-mismatch',
    message: `'${text}' is not a value of ${targetWords(target)}: ${literalMismatchWords(mismatch)}`,
  };
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

/** A value that does not convert to the type that uses it: in an expression, a declaration, a variable's value, a `$name` in an attribute. */
export const TYPE_MISMATCH = defineDiagnostic({
  code: 'type-mismatch',
  rule: { description: 'A value converts to the type that uses it.' },
  severity: 'error',
});
