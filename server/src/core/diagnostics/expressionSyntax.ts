import { defineDiagnostic } from './definition';
import { ExpressionSyntaxFact, FoundToken } from './expressionFacts';

/** The operators of the standard's expressions, as an unknown operator's message lists them. */
const STANDARD_OPERATORS = '+, -, *, /, %, and, or, not';

/** What the parser met, as its messages name it. */
function foundWords(found: FoundToken): string {
  switch (found.kind) {
    case 'end':
      return 'the end of the expression';
    case 'symbol':
      return `'${found.symbol}'`;
    case 'word':
      return `'${found.word}'`;
    case 'value':
      return 'a value';
  }
}

/** The message of a `${...}` that does not parse, or of a declaration without a value. */
export function expressionSyntaxMessage(fact: ExpressionSyntaxFact): string {
  switch (fact.fact) {
    case 'dollar-without-name':
      return `'$' must be followed by a parameter name`;
    case 'character':
      return `'${fact.character}' is not allowed in an expression`;
    case 'unclosed-parenthesis':
      return `expected ')' to close the '(' at column ${fact.column}, found ${foundWords(fact.found)}`;
    case 'call-without-parenthesis':
      return `expected '(' after the function ${fact.name}`;
    case 'arguments-not-closed':
      return `expected ',' or ')' in the arguments of ${fact.name}, found ${foundWords(fact.found)}`;
    case 'arity':
      return `${fact.name} takes ${fact.arity} argument${fact.arity === 1 ? '' : 's'}, not ${fact.given}`;
    case 'operand-expected':
      return `expected a number, a $parameter, a function or '(', found ${foundWords(fact.found)}`;
    case 'operator-expected':
      return `unexpected ${foundWords(fact.found)}: an operator or the end of the expression was expected`;
    case 'unclosed-expression':
      return `an expression must end with '}'`;
    case 'unknown-name':
      return `${unknownNameWords(fact.name)}: a parameter is written $${fact.name}; the functions are ${fact.functions.join(', ')}`;
    case 'unknown-function':
      return `unknown function '${fact.name}': the functions are ${fact.functions.join(', ')}`;
    case 'unknown-operator':
      return `unknown operator '${fact.word}': the operators are ${STANDARD_OPERATORS}`;
    case 'declaration-without-value':
      return `the declaration of '${fact.name}' has no value`;
  }
}

/**
 * The operator, function or character of a syntax error that the standard's expressions do not have (ASAM's
 * Quality Checker reports each as data_type.allowed_operators, allowed_operators.py:29-42, 130-145); undefined
 * for an error of how known parts are put together.
 */
export function nonstandardToken(fact: ExpressionSyntaxFact): string | undefined {
  switch (fact.fact) {
    case 'character':
      return fact.character;
    case 'unknown-name':
    case 'unknown-function':
      return fact.name;
    case 'unknown-operator':
      return fact.word;
    default:
      return undefined;
  }
}

/** A bare word that names nothing, in short (a glued text's warning names it so). */
export function unknownNameWords(name: string): string {
  return `unknown name '${name}'`;
}

/** A `${...}` that does not parse (its facts from the expression parser, core/semantics/expressionParser.ts). */
export const EXPRESSION_SYNTAX = defineDiagnostic({
  code: 'expression-syntax',
  rule: { description: "A ${...} expression follows the standard's grammar." },
  severity: 'error',
});
