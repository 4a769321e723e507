import { problemFix, quickFix, singleEdit } from './fix';

/** A file with more groups than this offers only the first ones as fixes of an unknown group. */
const MAX_GROUP_FIXES = 20;

/** A group the referenced file lacks: the closest name first (preferred), then every other group of the file. */
export const unknownGroupFix = problemFix(['unknown-group'], (data, { uri, diagnostic }) => {
  const names = [...new Set([...(data?.suggestion ? [data.suggestion] : []), ...(data?.groups ?? []).filter((name) => name.length > 0)])];
  return names
    .slice(0, MAX_GROUP_FIXES)
    .map((name) => quickFix(`Change to '${name}'`, diagnostic, singleEdit(uri, diagnostic.range, name), name === data?.suggestion));
});
