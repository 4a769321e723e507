import { problemFix, quickFix, singleEdit } from './fix';

/**
 * A form esmini accepts that the standard does not (SPEC 12): the standard's form, written where the
 * diagnostic is (`$` before a bare parameter, `-5` for `-5.0`, a name without `$`, glued text as a
 * literal) or at its related place (the parameterType of a string parameter read as a number).
 */
export const lenientValueFix = problemFix(['lenient-value'], (data, { uri, diagnostic }) => {
  if (data && 'suggestion' in data)
    return [quickFix(`Write the standard form '${data.suggestion}'`, diagnostic, singleEdit(uri, diagnostic.range, data.suggestion), true)];
  const related = diagnostic.relatedInformation?.[0];
  if (!data || !('relatedReplacement' in data) || !related || related.location.uri !== uri) return [];
  return [
    quickFix(
      `Declare the parameter parameterType="${data.relatedReplacement}"`,
      diagnostic,
      singleEdit(uri, related.location.range, data.relatedReplacement),
      true,
    ),
  ];
});
