import { ProblemDataByCode } from '../problems';
import { escapeAttributeValue } from '../xml';
import { defineDiagnostic, indentOfLine, isRelatedReplacement, isSuggestion, ProblemWording } from './definition';

/** What the flattener found about a ParameterReference key that matches no listed attribute. */
export interface UnknownKeyFacts {
  key: string;
  group: string;
  /** A name listed as a whole key (`Ego.speed` where `speed` was meant), its element and the file that lists it. */
  listedVerbatim?: { element: string; name: string; file: string };
  /** The closest listed key. */
  suggestion?: string;
}

/** The related location's note: where the whole key is listed. */
export const UNKNOWN_KEY_LISTED_NOTE = 'listed here as a whole key instead of an attribute name';

export function unknownKeyWording({ key, group, listedVerbatim, suggestion }: UnknownKeyFacts): ProblemWording<'unknown-key'> {
  const hint = listedVerbatim
    ? `<${listedVerbatim.element}> in ${listedVerbatim.file} lists '${listedVerbatim.name}', which names no attribute; list '${attributeNameOf(listedVerbatim.name)}' there instead`
    : suggestion
      ? `did you mean '${suggestion}'?`
      : 'list the attribute in parameterAttributes of its element in the simple scenario';
  return {
    severity: 'error',
    code: 'unknown-key',
    message: `key '${key}' matches no attribute listed in a parameterAttributes of group '${group}'`,
    hint,
  };
}

/** The last segment of a dotted name: the attribute a whole key names. */
function attributeNameOf(listed: string): string {
  return listed.split('.').pop() ?? listed;
}

/** The mistake lives in the simple scenario when a whole key is listed: the fix rewrites the listed name there. */
export function unknownKeyData({ listedVerbatim, suggestion }: UnknownKeyFacts): ProblemDataByCode['unknown-key'] | undefined {
  if (listedVerbatim) return { relatedReplacement: attributeNameOf(listedVerbatim.name) };
  return suggestion ? { suggestion } : undefined;
}

/** A key no group lists: the closest listed key, or the listed name rewritten in the simple scenario where the mistake lives. */
export const UNKNOWN_KEY = defineDiagnostic({
  code: 'unknown-key',
  rule: { description: 'A ParameterReference key matches an attribute listed in parameterAttributes.' },
  severity: 'error',
  skippedByForce: true,
  isData: (value): value is ProblemDataByCode['unknown-key'] => isSuggestion(value) || isRelatedReplacement(value),
  fixes: async ({ data, range, related }) => {
    if (data && 'suggestion' in data && data.suggestion)
      return [
        { title: `Change key to '${data.suggestion}'`, edits: [{ place: 'document', range, newText: data.suggestion }], preferred: true },
      ];
    const relatedReplacement = data && 'relatedReplacement' in data ? data.relatedReplacement : undefined;
    if (!relatedReplacement || !related || !(await related.editable())) return [];
    return [
      {
        title: `List '${relatedReplacement}' in ${related.fileName} instead`,
        edits: [{ place: 'related', range: related.range, newText: relatedReplacement }],
        preferred: true,
      },
    ];
  },
});

/** A key a group reference may add: its shortest form and the attribute's default. */
export interface MissingKey {
  key: string;
  defaultValue: string;
}

/**
 * The ParameterReferences that add the missing keys with their defaults, inserted before the closing tag
 * of the ManeuverGroupReference (`groupStart`, `groupEnd`), indented as its last ParameterReference (which
 * starts at `lastParameterStart`) or one level inside the reference.
 */
export function missingKeysInsertion(
  text: string,
  groupStart: number,
  groupEnd: number,
  lastParameterStart: number | undefined,
  missing: readonly MissingKey[],
): { title: string; offset: number; newText: string } {
  const closeTag = text.lastIndexOf('</', groupEnd - 1);
  const outerIndent = indentOfLine(text, groupStart);
  const unit = /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '    ';
  const indent = lastParameterStart !== undefined ? indentOfLine(text, lastParameterStart) : outerIndent + unit;
  const eol = text.includes('\r\n') ? '\r\n' : '\n';
  const lines = missing.map(
    (choice) => `${indent}<ParameterReference key="${choice.key}" value="${escapeAttributeValue(choice.defaultValue)}"/>`,
  );
  // Insert at the start of the closing tag's line, so that its indentation stays as written.
  const closeLineStart = text.lastIndexOf('\n', closeTag - 1) + 1;
  const onOwnLine = /^[ \t]*$/.test(text.slice(closeLineStart, closeTag));
  return {
    title: `Add ${missing.length} missing key${missing.length === 1 ? '' : 's'} with their defaults`,
    offset: onOwnLine ? closeLineStart : closeTag,
    newText: onOwnLine ? lines.join(eol) + eol : eol + lines.join(eol) + eol + outerIndent,
  };
}
