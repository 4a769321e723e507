import { problemFix, quickFix, singleEdit } from './fix';

/** A key no group lists: the closest listed key, or the listed name rewritten in the simple scenario where the mistake lives. */
export const unknownKeyFix = problemFix(['unknown-key'], async (data, { uri, diagnostic }, workspace) => {
  if (data && 'suggestion' in data && data.suggestion)
    return [quickFix(`Change key to '${data.suggestion}'`, diagnostic, singleEdit(uri, diagnostic.range, data.suggestion), true)];
  const relatedReplacement = data && 'relatedReplacement' in data ? data.relatedReplacement : undefined;
  const related = diagnostic.relatedInformation?.[0];
  if (!relatedReplacement || !related) return [];
  const targetRef = await workspace.uris.toRef(related.location.uri);
  if (!targetRef || (targetRef.entries.length > 0 && !workspace.editablePackages)) return [];
  const fileName = related.location.uri.slice(related.location.uri.lastIndexOf('/') + 1);
  return [
    quickFix(
      `List '${relatedReplacement}' in ${decodeURIComponent(fileName)} instead`,
      diagnostic,
      singleEdit(workspace.uriOf(targetRef), related.location.range, relatedReplacement),
      true,
    ),
  ];
});
