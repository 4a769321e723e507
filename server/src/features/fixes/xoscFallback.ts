import { problemFix, quickFix, singleEdit } from './fix';

/** A `.xosc` that does not exist, read from the flattened package of its name: name the package. */
export const xoscFallbackFix = problemFix(['xosc-fallback'], (data, { uri, diagnostic }) =>
  data?.replacement
    ? [quickFix(`Change to '${data.replacement}'`, diagnostic, singleEdit(uri, diagnostic.range, data.replacement), true)]
    : [],
);

/** A misspelt `scenarioFileName`: name the closest file that exists where it was looked up. */
export const missingFileFix = problemFix(['missing-file'], (data, { uri, diagnostic }) =>
  data?.suggestion
    ? [quickFix(`Change to '${data.suggestion}'`, diagnostic, singleEdit(uri, diagnostic.range, data.suggestion), true)]
    : [],
);
