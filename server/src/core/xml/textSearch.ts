import { coreMemo } from '../memos';
import { XmlDocument } from './types';

/**
 * A search of a whole text, answered once per parse. `span`: the most characters a match looks at, its
 * lookarounds and `\b`s included (the pattern has no anchors and no `g` flag); `literal`: a string every
 * match holds, looked for first, so a large text without it is not run through the pattern.
 */
export interface TextSearch {
  readonly pattern: RegExp;
  readonly literal: string;
  readonly span: number;
}

const answers = coreMemo<XmlDocument, Map<TextSearch, boolean>>('textSearches');

/** Whether `text` holds a match of the search. */
export function textMatches(text: string, search: TextSearch): boolean {
  return text.includes(search.literal) && search.pattern.test(text);
}

/** Whether the parse's text holds a match: searched once per parse, or carried from the parse an edit inside one value came from. */
export function parseTextMatches(document: XmlDocument, search: TextSearch): boolean {
  let known = answers.get(document);
  const answer = known?.get(search);
  if (answer !== undefined) return answer;
  if (!known) answers.set(document, (known = new Map()));
  const found = textMatches(document.text, search);
  known.set(search, found);
  return found;
}

/**
 * Gives the parse after one edit (`[prefix, removedEnd)` of the previous text replaced by `[prefix, insertedEnd)`
 * of the new) the previous parse's answers where the edit cannot change them: when neither text has a match
 * within a span of the edit, every match of either lies wholly before or after it, the same in both. A match
 * near the edit leaves the answer to be searched for again.
 */
export function carryTextSearches(
  previous: XmlDocument,
  document: XmlDocument,
  prefix: number,
  removedEnd: number,
  insertedEnd: number,
): void {
  const known = answers.get(previous);
  if (!known) return;
  const carried = new Map<TextSearch, boolean>();
  for (const [search, answer] of known) {
    const start = Math.max(0, prefix - search.span);
    const near = (text: string, end: number) => search.pattern.test(text.slice(start, end + search.span));
    if (!near(previous.text, removedEnd) && !near(document.text, insertedEnd)) carried.set(search, answer);
  }
  if (carried.size > 0) answers.set(document, carried);
}
