import { problemFix, quickFix, singleEdit } from './fix';

/** A `.xosc` that does not exist, read from the flattened package of its name: name the package. */
export const xoscFallbackFix = problemFix(['xosc-fallback'], (data, { uri, diagnostic }) =>
  data?.replacement ? [quickFix(`Change to '${data.replacement}'`, diagnostic, singleEdit(uri, diagnostic.range, data.replacement), true)] : [],
);
