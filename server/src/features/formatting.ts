import { FormattingOptions, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { editorEdits, formatXml } from '../core/format';
import { parseXml, XmlDocument } from '../core/xml';

/** The edits that format a document (or the lines of `range`); a malformed document gets a message, no edits. */
export function formattingEdits(
  document: TextDocument,
  options: FormattingOptions,
  maxLineWidth: number,
  range?: { start: number; end: number },
  parsed?: XmlDocument,
): { edits: TextEdit[]; refusal?: string } {
  const text = document.getText();
  // One parse serves the formatter and the line positions of its edits (the server's own, when it holds one).
  const xml = parsed && parsed.text === text ? parsed : parseXml(text);
  const result = formatXml(text, { tabSize: options.tabSize, insertSpaces: options.insertSpaces, maxLineWidth }, range, xml);
  if (!result.ok) return { edits: [], refusal: result.message };
  const edits = editorEdits(text, result);
  const ranges = xml.lines.rangesInOrder(edits);
  return { edits: edits.map((edit, index) => ({ range: ranges[index], newText: edit.newText })) };
}
