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
