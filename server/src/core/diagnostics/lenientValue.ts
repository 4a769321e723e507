import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRelatedReplacement, isSuggestion, ProblemWording } from './definition';

/** A parameter declared as `name="$X"`: `esminiReading` says how esmini reads it (core/semantics/esminiValues.ts). */
export function dollarDeclarationWording(name: string, esminiReading: string): ProblemWording<'lenient-value'> {
  return {
    severity: 'warning',
    code: 'lenient-value',
    message: `the standard declares a parameter by its name without '$' ('${name}'); ${esminiReading}, so this declares '${name}'`,
    hint: `write name="${name}"`,
  };
}

/**
 * A form esmini accepts that the standard does not (SPEC 12): its fix writes the standard's form where the
 * diagnostic is (`$` before a bare parameter, `-5` for `-5.0`, a name without `$`, glued text as a literal),
 * or at its related place in the same document (the parameterType of a string parameter read as a number).
 */
export const LENIENT_VALUE = defineDiagnostic({
  code: 'lenient-value',
  rule: { description: "A value is written in the standard's form, not only in a form esmini also accepts (SPEC 12)." },
  severity: 'warning',
  isData: (value): value is ProblemDataByCode['lenient-value'] => isSuggestion(value) || isRelatedReplacement(value),
  fixes: ({ data, range, related }) => {
    if (data && 'suggestion' in data)
      return [
        {
          title: `Write the standard form '${data.suggestion}'`,
          edits: [{ place: 'document', range, newText: data.suggestion }],
          preferred: true,
        },
      ];
    if (!data || !('relatedReplacement' in data) || !related?.sameDocument) return [];
    return [
      {
        title: `Declare the parameter parameterType="${data.relatedReplacement}"`,
        edits: [{ place: 'document', range: related.range, newText: data.relatedReplacement }],
        preferred: true,
      },
    ];
  },
});
