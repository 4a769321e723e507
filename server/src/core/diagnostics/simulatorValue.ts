import { ESMINI_PROFILE } from '../profiles/esmini';
import { ValueRule } from '../profiles/facts';
import { defineDiagnostic } from './definition';
import { EsminiComputes, EsminiEvaluationFailure, EsminiStop, ExpressionFact, SimulatorFact, ValueDifference } from './expressionFacts';

/** "esmini <does> (<source>)" for a rule of the profile. */
export function esminiRule(rule: ValueRule): string {
  const fact = ESMINI_PROFILE.valueRules?.[rule];
  return fact ? `esmini ${fact.does} (${fact.source})` : `esmini (${rule})`;
}

function failureWords(failure: EsminiEvaluationFailure): string {
  switch (failure.failure) {
    case 'unknown-function':
      return `'${failure.word}' is not a function esmini knows`;
    case 'number-where-operator':
      return `a number where an operator was expected, at '${failure.rest}'`;
    case 'unexpected-character':
      return `unexpected '${failure.character}'`;
    case 'operator-where-operand':
      return `'${failure.character}' where an operand was expected`;
    case 'unknown-operator':
      return `unknown operator '${failure.operator}'`;
    case 'operand-missing':
      return 'the expression ends where an operand was expected';
    case 'not-a-number':
      return `'${failure.text}' is not a number`;
    case 'parenthesis-not-closed':
      return "a '(' is not closed";
    case 'arguments-not-closed':
      return `the arguments of ${failure.name} are not closed`;
    case 'too-few-arguments':
      return `${failure.name} needs ${failure.count} arguments`;
    case 'operand-expected':
      return 'an operand was expected';
    case 'trailing-text':
      return 'unexpected text after the expression';
    case 'assignment':
      return 'an assignment';
    case 'result-not-a-number':
      return 'the result is not a number';
  }
}

/** Why esmini stops the scenario at a value. */
export function esminiStopWords(stop: EsminiStop): string {
  switch (stop.stop) {
    case 'unresolved-parameter':
      return `esmini stops: "Failed to resolve parameter $${stop.name}"`;
    case 'depends-on-itself':
      return `esmini stops: '${stop.name}' depends on itself`;
    case 'names-itself':
      return 'esmini stops: a parameter value names itself';
    case 'evaluation':
      return `esmini stops: "Failed to evaluate the expression" (${failureWords(stop.failure)}: '${stop.text}')`;
  }
}

/** Where a value is read by a comparison of a stored value (a parameter's, a variable's) or stored for one: any difference can flip it. */
const STORED_COMPARISONS: ReadonlySet<string> = new Set([
  'ParameterCondition',
  'VariableCondition',
  'UserDefinedValueCondition',
  'ParameterSetAction',
  'VariableSetAction',
  'ParameterAddValueRule',
  'ParameterMultiplyByValueRule',
  'VariableAddValueRule',
  'VariableMultiplyByValueRule',
]);

/**
 * Whether the attribute `attribute` of an `element` is compared exactly: the `value` of a condition on a stored value (or of an
 * action storing one), or of any condition whose `rule` (`ruleText`, evaluated) is equalTo or notEqualTo.
 */
export function comparedExactly(element: string, attribute: string, ruleText: string | undefined): boolean {
  if (attribute !== 'value') return false;
  return STORED_COMPARISONS.has(element) || ruleText === 'equalTo' || ruleText === 'notEqualTo';
}

/**
 * The largest difference between esmini's number and the standard's, as a share of the value (absolute below 1), that no run
 * shows where the value is a quantity (metres, seconds, m/s, radians): 1 cm on a position of 100 m, 10 ms on a time of 100 s
 * (a fifth of esmini's 0.05 s step), while esmini's six decimals (resultText) carried through a chain of expressions make
 * differences of 1e-8 to 1e-5 of the value (Euro NCAP's trajectory parameters).
 */
export const UNSEEN_DIFFERENCE = 1e-4;

/**
 * Whether esmini's value differs from the standard's in a way the scenario can show (SPEC 12's warning): any difference where
 * the value is no double or is compared exactly (`exact`); for a quantity, one beyond UNSEEN_DIFFERENCE of it (e.g. 100.000002
 * for a start position of 100 m is no warning, 0.01 for a time of 0.014 s is).
 */
export function differenceMatters(standard: number | string | boolean, esmini: number | string | boolean, exact: boolean): boolean {
  if (typeof standard !== 'number' || typeof esmini !== 'number' || exact) return standard !== esmini;
  if (!Number.isFinite(standard) || !Number.isFinite(esmini)) return !Object.is(standard, esmini);
  return Math.abs(standard - esmini) > UNSEEN_DIFFERENCE * Math.max(1, Math.abs(standard));
}

/** The values of the standard and of esmini, and the rules that make them differ. */
export function differenceWords(difference: ValueDifference): string {
  return `esmini computes ${difference.esmini} where the standard gives ${difference.standard}${difference.reasons.length ? `: ${difference.reasons.join('; ')}` : ''}`;
}

/** What esmini computes where the standard fails, added to the standard's error. */
export function esminiComputesWords(computes: EsminiComputes): string {
  return `(esmini computes ${computes.text}: ${computes.rules.map(esminiRule).join('; ') || 'it reads the expression otherwise'})`;
}

/** The message of a value esmini computes otherwise, or stops at (`words`: the message of a fact it names as its cause). */
export function simulatorValueMessage(fact: SimulatorFact, words: (cause: ExpressionFact) => string): string {
  switch (fact.fact) {
    case 'differs':
      return differenceWords(fact.difference);
    case 'declaration-differs':
      return `'${fact.name}': ${differenceWords(fact.difference)}`;
    case 'esmini-stops':
      return esminiStopWords(fact.stop);
    case 'unsupported-type':
      return `'${fact.name}': esmini does not support parameters of type ${fact.type}: it logs "Type ${fact.type} is not supported yet" and keeps the value as text ('${fact.text}'), which an attribute then reads as written (esmini 3.6 Parameters.cpp parseParameterDeclarations)`;
    case 'esmini-stops-beside':
      return `${esminiStopWords(fact.stop)}; the standard gives ${fact.standard}`;
    case 'refused-literal':
      return `${words(fact.cause)}, so the standard refuses it; esmini runs it: ${fact.rules.map(esminiRule).join('; ')}: '${fact.text}' where the text is used, ${fact.value} where a ${fact.type} is`;
  }
}

/** A value the selected simulator computes otherwise than the standard (SPEC 12). */
export const SIMULATOR_VALUE = defineDiagnostic({
  code: 'simulator-value',
  rule: { description: 'A value is the same in the standard and in the selected simulator.' },
  severity: 'warning',
});
