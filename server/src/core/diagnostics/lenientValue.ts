import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRelatedReplacement, isSuggestion } from './definition';

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
