import { defineDiagnostic, ProblemWording } from './definition';

/** The related location's note: the group that a reference to the name takes. */
export const DUPLICATE_GROUP_FIRST_NOTE = 'the first group of that name';

/** A later ManeuverGroup of a name a reference uses. */
export function duplicateGroupWording(name: string): ProblemWording<'duplicate-group'> {
  return {
    severity: 'warning',
    code: 'duplicate-group',
    message: `another ManeuverGroup is already named '${name}'; a reference to that name takes the first one`,
    hint: 'give each ManeuverGroup a unique name',
  };
}

export const DUPLICATE_GROUP = defineDiagnostic({
  code: 'duplicate-group',
  rule: { description: 'A referenced file has no two ManeuverGroups of the same name.' },
  severity: 'warning',
});
