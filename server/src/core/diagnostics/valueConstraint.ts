import { defineDiagnostic } from './definition';

/** A parameter's value outside its declaration's ConstraintGroups. */
export const VALUE_CONSTRAINT = defineDiagnostic({
  code: 'value-constraint',
  rule: {
    description: "A parameter's value satisfies one of its declaration's ConstraintGroups (all the ValueConstraints of the group).",
  },
  severity: 'error',
});
