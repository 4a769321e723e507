import { ProblemCode } from '../problems';
import { ProblemWording } from './definition';
import { divisionByZeroMessage } from './divisionByZero';
import { EsminiComputes, ExpressionFact } from './expressionFacts';
import { expressionSyntaxMessage } from './expressionSyntax';
import { lenientValueMessage } from './lenientValue';
import { nonstandardExpressionMessage } from './nonstandardExpression';
import { overflowMessage } from './overflow';
import { esminiComputesWords, simulatorValueMessage } from './simulatorValue';
import { expressionTypeMessage } from './typeMismatch';
import { unknownParameterMessage } from './undeclaredParameter';

/** The code of each kind of an expression's facts. */
export const EXPRESSION_CODES = {
  syntax: 'expression-syntax',
  'type-mismatch': 'type-mismatch',
  'division-by-zero': 'division-by-zero',
  nonstandard: 'nonstandard-expression',
  lenient: 'lenient-value',
  simulator: 'simulator-value',
  overflow: 'overflow',
  'unknown-parameter': 'undeclared-parameter',
} as const satisfies Record<ExpressionFact['kind'], ProblemCode>;

/** What SPEC 12 makes a warning: a form esmini accepts with one clear meaning, a value esmini computes otherwise. */
const WARNING_KINDS: ReadonlySet<ExpressionFact['kind']> = new Set(['nonstandard', 'lenient', 'simulator']);

/** The words of a fact, each by its code's module (without what esmini computes instead). */
function factMessage(fact: ExpressionFact): string {
  switch (fact.kind) {
    case 'syntax':
      return expressionSyntaxMessage(fact);
    case 'type-mismatch':
      return expressionTypeMessage(fact);
    case 'division-by-zero':
      return divisionByZeroMessage(fact);
    case 'overflow':
      return overflowMessage(fact);
    case 'nonstandard':
      return nonstandardExpressionMessage(fact);
    case 'lenient':
      return lenientValueMessage(fact);
    case 'simulator':
      return simulatorValueMessage(fact, factMessage);
    case 'unknown-parameter':
      return unknownParameterMessage(fact, factMessage);
  }
}

/** The message of an expression's error or warning, as a problem, a hover, the debugger and the views say it. */
export function expressionMessage(error: ExpressionFact & { esminiComputes?: EsminiComputes }): string {
  const message = factMessage(error);
  return error.esminiComputes ? `${message} ${esminiComputesWords(error.esminiComputes)}` : message;
}

/** An expression's error or warning as a problem's words: its code, its severity (SPEC 12) and its message. */
export function expressionWording(error: ExpressionFact & { esminiComputes?: EsminiComputes }): ProblemWording {
  return {
    severity: WARNING_KINDS.has(error.kind) ? 'warning' : 'error',
    code: EXPRESSION_CODES[error.kind],
    message: expressionMessage(error),
  };
}
