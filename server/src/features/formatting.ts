import { FormattingOptions, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { formatXml } from '../core/format';
import { LineIndex } from '../core/text';
import { XmlDocument } from '../core/xml';

/** The edits that format a document (or the lines of `range`); a malformed document gets a message, no edits. */
export function formattingEdits(
  document: TextDocument,
  options: FormattingOptions,
  maxLineWidth: number,
  range?: { start: number; end: number },
  parsed?: XmlDocument,
): { edits: TextEdit[]; refusal?: string } {
  const text = document.getText();
  const result = formatXml(text, { tabSize: options.tabSize, insertSpaces: options.insertSpaces, maxLineWidth }, range, parsed);
  if (!result.ok) return { edits: [], refusal: result.message };
  const lines = new LineIndex(text);
  return { edits: result.edits.map((edit) => TextEdit.replace(lines.range(edit.start, edit.end), edit.newText)) };
}
