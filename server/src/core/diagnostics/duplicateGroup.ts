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

/** The related location's note of a repeated name in an Act: the earlier group. */
export const DUPLICATE_OUTER_GROUP_FIRST_NOTE = 'the first group of that name in the Act';

/**
 * A ManeuverGroup of a main file that repeats the name of an earlier group of its Act, one of the two
 * importing groups: flattening names each copy `OUTER.INNER` (SPEC 4), so the copies of two groups of one
 * name that import groups of one name are named alike (`shared`). A note, as for ManeuverGroups of one
 * name in a plain scenario, which core/semantics/checks/names.ts reports only where a reference names
 * them: esmini runs both, and the paper's library does this on purpose (Vehicle_back for two vehicles).
 */
export function duplicateOuterGroupWording(name: string, act: string, shared: string[]): ProblemWording<'duplicate-group'> {
  const copies = shared.map((inner) => `'${name}.${inner}'`).join(', ');
  return {
    severity: 'information',
    code: 'duplicate-group',
    message: `another ManeuverGroup of Act '${act}' is already named '${name}'${
      shared.length ? `: flattening names the copies of both ${copies}` : ''
    } (the standard wants the names of one Act unique; esmini runs both groups, and a reference to the name takes the first)`,
    hint: 'give each ManeuverGroup of the Act a name of its own',
  };
}

export const DUPLICATE_GROUP = defineDiagnostic({
  code: 'duplicate-group',
  rule: {
    description:
      'A referenced file has no two ManeuverGroups of the same name, nor an Act of a main file two groups of one name where one imports groups.',
  },
  severity: 'warning',
});
