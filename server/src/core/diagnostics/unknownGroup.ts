import { ProblemDataByCode } from '../problems';
import { changeTo, defineDiagnostic, isOptionalString, isRecordOf, isStringList, ProblemWording } from './definition';

/** A file with more groups than this offers only the first ones as fixes of an unknown group. */
const MAX_GROUP_FIXES = 20;

/** A maneuverGroupName that `file` does not have; `groups`: the names it has, `suggestion`: the closest. */
export function unknownGroupWording(
  file: string,
  name: string,
  groups: readonly string[],
  suggestion: string | undefined,
): ProblemWording<'unknown-group'> {
  return {
    severity: 'error',
    code: 'unknown-group',
    message:
      `'${file}' has no ManeuverGroup named '${name}'` + (groups.length ? `; it has: ${groups.join(', ')}` : '; it has no ManeuverGroup'),
    hint: suggestion ? `did you mean '${suggestion}'?` : undefined,
  };
}

export function unknownGroupData(groups: string[], suggestion: string | undefined): ProblemDataByCode['unknown-group'] {
  return { ...(suggestion ? { suggestion } : {}), groups };
}

/** A group the referenced file lacks: the closest name first (preferred), then every other group of the file. */
export const UNKNOWN_GROUP = defineDiagnostic({
  code: 'unknown-group',
  rule: { description: 'A maneuverGroupName names a ManeuverGroup of the referenced file.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['unknown-group'] =>
    isRecordOf<ProblemDataByCode['unknown-group']>(value, { suggestion: isOptionalString, groups: isStringList }),
  fixes: ({ data, range }) => {
    const names = [...new Set([...(data?.suggestion ? [data.suggestion] : []), ...(data?.groups ?? []).filter((name) => name.length > 0)])];
    return names.slice(0, MAX_GROUP_FIXES).map((name) => changeTo(range, name, name === data?.suggestion));
  },
});
