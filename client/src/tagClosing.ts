/**
 * Closing tags as the user types: after `<Name ...>` the matching `</Name>` is inserted behind the
 * cursor. Pure text logic here; the editor wiring is in extension.ts.
 */

const NAME = /[A-Za-z_][\w.:-]*/.source;
const OPEN_TAG_BEFORE_CURSOR = new RegExp(`<(${NAME})(?:\\s+[^<>]*?)?>$`);

/**
 * The closing tag to insert when the text before the cursor (the document up to it, or at least its
 * line) ends with the `>` just typed, or undefined when that `>` does not end an opening tag (an empty
 * element, a closing tag, the end of a comment, a `>` inside an attribute value or inside a comment)
 * or the tag is already closed right after the cursor.
 */
export function closingTagFor(textBeforeCursor: string, lineAfterCursor: string): string | undefined {
  if (!textBeforeCursor.endsWith('>') || textBeforeCursor.endsWith('/>') || textBeforeCursor.endsWith('->')) return undefined;
  if (textBeforeCursor.lastIndexOf('<!--') > textBeforeCursor.lastIndexOf('-->')) return undefined;
  const start = textBeforeCursor.lastIndexOf('<');
  if (start === -1) return undefined;
  const tag = textBeforeCursor.slice(start);
  if (!isOutsideQuotes(tag)) return undefined;
  const match = OPEN_TAG_BEFORE_CURSOR.exec(tag);
  if (!match) return undefined;
  const closing = `</${match[1]}>`;
  return lineAfterCursor.trimStart().startsWith(closing) ? undefined : closing;
}

/** True when every quote opened in the tag is closed, so its last `>` is not inside a value. */
function isOutsideQuotes(tag: string): boolean {
  let quote: string | undefined;
  for (const character of tag) {
    if (quote) {
      if (character === quote) quote = undefined;
    } else if (character === '"' || character === "'") {
      quote = character;
    }
  }
  return quote === undefined;
}
