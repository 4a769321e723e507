import { ValueRule } from '../profiles/facts';

/**
 * What the expression parser and evaluators (core/semantics/) find, as facts: each error's kind (its code, see
 * `EXPRESSION_CODES`), what it is about, and its data. The module of each code words them (`expressionMessage`).
 */

/** What the parser met where it expected something else: the end, a symbol, a word, or a number or `$name`. */
export type FoundToken = { kind: 'end' } | { kind: 'symbol'; symbol: string } | { kind: 'word'; word: string } | { kind: 'value' };

/** A `${...}` that does not parse, or a declaration that has no value (expression-syntax). */
export type ExpressionSyntaxFact =
  | { kind: 'syntax'; fact: 'dollar-without-name' }
  | { kind: 'syntax'; fact: 'character'; character: string }
  | { kind: 'syntax'; fact: 'unclosed-parenthesis'; column: number; found: FoundToken }
  | { kind: 'syntax'; fact: 'call-without-parenthesis'; name: string }
  | { kind: 'syntax'; fact: 'arguments-not-closed'; name: string; found: FoundToken }
  | { kind: 'syntax'; fact: 'arity'; name: string; arity: number; given: number }
  | { kind: 'syntax'; fact: 'operand-expected'; found: FoundToken }
  | { kind: 'syntax'; fact: 'operator-expected'; found: FoundToken }
  | { kind: 'syntax'; fact: 'unclosed-expression' }
  /** A bare word that names no parameter (`functions`: the function names the standard knows). */
  | { kind: 'syntax'; fact: 'unknown-name'; name: string; functions: readonly string[] }
  /** A word where an operator was expected, which is no operator of the standard (`1 xor 2`, `2_3`). */
  | { kind: 'syntax'; fact: 'unknown-operator'; word: string }
  /** A call of a function the standard does not have (`functions`: those it has). */
  | { kind: 'syntax'; fact: 'unknown-function'; name: string; functions: readonly string[] }
  | { kind: 'syntax'; fact: 'declaration-without-value'; name: string };

/** Why a value is no value of a type: a literal's text, a number's range, a conversion, a fraction. */
export type LiteralMismatch =
  | { fact: 'not-of-type'; text: string; type: 'double' | 'int' | 'unsignedInt' | 'unsignedShort' | 'boolean' | 'dateTime' }
  | { fact: 'out-of-range'; value: number; type: 'int' | 'unsignedInt' | 'unsignedShort' }
  | { fact: 'not-convertible'; from: string; to: string }
  /** An expression's double, formatted, given to an integer type with a fraction. */
  | { fact: 'not-integral'; value: string; type: 'int' | 'unsignedInt' | 'unsignedShort' };

/** What an operator or function that needs a number was given. */
export type NumberOperand = { role: 'negation' } | { role: 'operator'; operator: string } | { role: 'function'; name: string };

/** A value of the wrong type inside an expression, or a declared value that is no value of its type (type-mismatch). */
export type ExpressionTypeFact =
  | { kind: 'type-mismatch'; fact: 'needs-number'; operand: NumberOperand; type: string; value: number | boolean | string }
  | { kind: 'type-mismatch'; fact: 'needs-boolean'; operator: string; type: string; value: number | boolean | string }
  | { kind: 'type-mismatch'; fact: 'date-time-parameter'; name: string }
  | { kind: 'type-mismatch'; fact: 'string-parameter'; name: string; value: number | boolean | string }
  | { kind: 'type-mismatch'; fact: 'no-real-value'; name: string; args: readonly number[] }
  /** A value a ParameterAssignment gives. */
  | { kind: 'type-mismatch'; fact: 'assigned-value'; mismatch: LiteralMismatch }
  /** A declaration's value (`writtenType` undefined: declared without a type). */
  | { kind: 'type-mismatch'; fact: 'declared-value'; mismatch: LiteralMismatch; name: string; writtenType: string | undefined };

export type DivisionByZeroFact = { kind: 'division-by-zero'; operator: string };

/** A number written (`number`) or computed (`result`) beyond a double's range. */
export type OverflowFact = { kind: 'overflow'; fact: 'number' | 'result' };

/** A constant the standard lacks (nonstandard-expression). */
export type NonstandardFact = { kind: 'nonstandard'; constant: 'pi' | 'e' };

/** The words of the error a glued text stands for: an unknown name, or a string parameter. */
export type GluedCause =
  Extract<ExpressionSyntaxFact, { fact: 'unknown-name' }> | Extract<ExpressionTypeFact, { fact: 'string-parameter' }>;

/** A form esmini accepts with one clear meaning that the standard does not (lenient-value). */
export type LenientFact =
  /** A string parameter in an expression, whose text reads as a number or boolean (`read`: that value as text). */
  | { kind: 'lenient'; fact: 'string-parameter'; name: string; value: number | boolean | string; type: string; read: string }
  | { kind: 'lenient'; fact: 'bare-parameter'; name: string }
  /** An integer written with a fraction of zero (`standard`: the integer as the standard writes it). */
  | { kind: 'lenient'; fact: 'integral-fraction'; text: string; type: 'int' | 'unsignedInt' | 'unsignedShort'; standard: string }
  /** An expression esmini glues as text (`text`: what esmini makes of it). */
  | { kind: 'lenient'; fact: 'glued-text'; cause: GluedCause; text: string };

/** A value the standard and esmini compute differently: both as text, and the words of esmini's rules that make the difference. */
export interface ValueDifference {
  standard: string;
  esmini: string;
  reasons: string[];
}

/** Why esmini's expression evaluator (zserge/expr as esmini 3.6 builds it) fails on a text. */
export type EsminiEvaluationFailure =
  | { failure: 'unknown-function'; word: string }
  | { failure: 'number-where-operator'; rest: string }
  | { failure: 'unexpected-character'; character: string }
  | { failure: 'operator-where-operand'; character: string }
  | { failure: 'unknown-operator'; operator: string }
  | { failure: 'operand-missing' }
  | { failure: 'not-a-number'; text: string }
  | { failure: 'parenthesis-not-closed' }
  | { failure: 'arguments-not-closed'; name: string }
  | { failure: 'too-few-arguments'; name: string; count: number }
  | { failure: 'operand-expected' }
  | { failure: 'trailing-text' }
  | { failure: 'assignment' }
  | { failure: 'result-not-a-number' };

/** Why esmini stops a scenario at a value. */
export type EsminiStop =
  | { stop: 'unresolved-parameter'; name: string }
  | { stop: 'depends-on-itself'; name: string }
  | { stop: 'names-itself' }
  | { stop: 'evaluation'; failure: EsminiEvaluationFailure; text: string };

/** A value esmini computes otherwise than the standard, or stops at (simulator-value). */
export type SimulatorFact =
  | { kind: 'simulator'; fact: 'differs'; difference: ValueDifference }
  | { kind: 'simulator'; fact: 'declaration-differs'; name: string; difference: ValueDifference }
  | { kind: 'simulator'; fact: 'esmini-stops'; stop: EsminiStop }
  /** A declared type esmini 3.6 does not support, whose value it keeps as `text`. */
  | { kind: 'simulator'; fact: 'unsupported-type'; name: string; type: string; text: string }
  /** esmini stops where the standard gives `standard`. */
  | { kind: 'simulator'; fact: 'esmini-stops-beside'; stop: EsminiStop; standard: string }
  /**
   * A literal the standard refuses for its type (`cause`) that esmini runs: `text` where the text is used,
   * `value` where a `type` is, by esmini's rules (`rules`).
   */
  | {
      kind: 'simulator';
      fact: 'refused-literal';
      cause: ExpressionFact;
      rules: readonly ValueRule[];
      text: string;
      value: string;
      type: string;
    };

/** A `$name` no declaration resolves, or whose declaration has no valid value (`cause`: why, where known). */
export type UnknownParameterFact =
  | { kind: 'unknown-parameter'; fact: 'undeclared'; name: string }
  | { kind: 'unknown-parameter'; fact: 'no-valid-value'; name: string; cause: ExpressionFact | undefined };

/** Every fact an expression's parser or evaluators report. */
export type ExpressionFact =
  | ExpressionSyntaxFact
  | ExpressionTypeFact
  | DivisionByZeroFact
  | OverflowFact
  | NonstandardFact
  | LenientFact
  | SimulatorFact
  | UnknownParameterFact;

export type ExpressionErrorKind = ExpressionFact['kind'];

/** What esmini computes where the standard fails (`rules`: the rules that make the difference, none where none is named). */
export interface EsminiComputes {
  text: string;
  rules: readonly ValueRule[];
}
