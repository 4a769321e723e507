/** Markdown for hovers: text from scenario files shown literally, never read as emphasis or links. */

/** A code span holding `text` exactly: a fence longer than any run of backticks inside it (CommonMark 6.1). */
export function code(text: string): string {
  const longest = Math.max(0, ...[...text.matchAll(/`+/g)].map((run) => run[0].length));
  const fence = '`'.repeat(longest + 1);
  // A space on each side keeps a leading or trailing backtick out of the fence; CommonMark strips it again.
  const padded = text.startsWith('`') || text.endsWith('`') || text === '' ? ` ${text} ` : text;
  return `${fence}${padded}${fence}`;
}

/** Text with every ASCII punctuation character that Markdown could read escaped by a backslash. */
export function escapeMarkdown(text: string): string {
  return text.replace(/[\\`*_{}[\]()<>#+\-.!|~$&]/g, (char) => `\\${char}`);
}
