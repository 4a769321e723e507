import { defineDiagnostic, ProblemWording } from './definition';
import { LiteralMismatch } from './expressionFacts';
import { literalMismatchWords } from './typeMismatch';

/** A ValueConstraint's rule and value, the value as a message writes it. */
export interface ConstraintFacts {
  rule: 'equalTo' | 'notEqualTo' | 'lessThan' | 'lessOrEqual' | 'greaterThan' | 'greaterOrEqual';
  value: string;
}

const RULE_WORDS: Record<ConstraintFacts['rule'], string> = {
  equalTo: '=',
  notEqualTo: '≠',
  lessThan: '<',
  lessOrEqual: '≤',
  greaterThan: '>',
  greaterOrEqual: '≥',
};

/** The constraints a value breaks, group by group (one group of them holds no more). */
function brokenWords(broken: readonly (readonly ConstraintFacts[])[]): string {
  const groups = broken.map((group) => group.map((constraint) => `${RULE_WORDS[constraint.rule]} ${constraint.value}`).join(' and '));
  return groups.length === 1 ? `it is not ${groups[0]}` : `no constraint group holds (${groups.map((group) => `not ${group}`).join('; ')})`;
}

/** The related location's note: a constraint the value breaks. */
export function brokenConstraintNote({ rule, value }: ConstraintFacts): string {
  return `${rule} ${value}`;
}

/** What the constraint check found. */
export type ValueConstraintFacts =
  /** A rule other than equalTo and notEqualTo for a boolean or string parameter. */
  | { kind: 'rule'; rule: string; type: string; parameter: string }
  /** A constraint's value that is no value of the parameter's type (`reason`: why not). */
  | { kind: 'value'; value: string; type: string; parameter: string; reason: LiteralMismatch }
  /** A declared value (`entry` unset) or a value a CatalogReference gives an entry's parameter, and the constraints it breaks. */
  | { kind: 'broken'; value: string; parameter: string; entry?: string; broken: ConstraintFacts[][] };

export function valueConstraintWording(facts: ValueConstraintFacts): ProblemWording<'value-constraint'> {
  const wording = (message: string): ProblemWording<'value-constraint'> => ({ severity: 'error', code: 'value-constraint', message });
  switch (facts.kind) {
    case 'rule':
      return wording(
        `the rule '${facts.rule}' does not apply to the ${facts.type} parameter '${facts.parameter}': a ${facts.type} is only equalTo or notEqualTo a value`,
      );
    case 'value':
      return wording(
        `the constraint's value '${facts.value}' is not a value of the ${facts.type} parameter '${facts.parameter}': ${literalMismatchWords(facts.reason)}`,
      );
    case 'broken':
      return wording(
        facts.entry === undefined
          ? `the value ${facts.value} of parameter '${facts.parameter}' breaks its ConstraintGroup: ${brokenWords(facts.broken)}`
          : `the value ${facts.value} given to parameter '${facts.parameter}' of catalog entry '${facts.entry}' breaks the entry's ConstraintGroup: ${brokenWords(facts.broken)}`,
      );
  }
}

/** A parameter's value outside its declaration's ConstraintGroups. */
export const VALUE_CONSTRAINT = defineDiagnostic({
  code: 'value-constraint',
  rule: {
    description: "A parameter's value satisfies one of its declaration's ConstraintGroups (all the ValueConstraints of the group).",
  },
  severity: 'error',
});
