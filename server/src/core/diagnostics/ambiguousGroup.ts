import { defineDiagnostic, ProblemWording } from './definition';

/** A maneuverGroupName that `file` gives more than one ManeuverGroup. */
export function ambiguousGroupWording(file: string, name: string): ProblemWording<'ambiguous-group'> {
  return {
    severity: 'warning',
    code: 'ambiguous-group',
    message: `'${file}' has more than one ManeuverGroup named '${name}'; the first one is used`,
    hint: undefined,
  };
}

export const AMBIGUOUS_GROUP = defineDiagnostic({
  code: 'ambiguous-group',
  rule: { description: 'A maneuverGroupName names exactly one ManeuverGroup.' },
  severity: 'warning',
});
