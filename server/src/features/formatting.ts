import { Connection, FormattingOptions, MessageType, ResponseError, ShowMessageNotification, TextDocuments, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { formatXml } from '../core/format';
import { LineIndex } from '../core/text';
import { XmlDocument } from '../core/xml';
import { Workspace } from '../workspace';

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

export interface FormattingContext {
  documents: TextDocuments<TextDocument>;
  workspace: Workspace;
  /** The server's parse of an open document, when it has one (formatting then need not parse again). */
  parsed?: (uri: string) => Promise<XmlDocument | undefined>;
}

/** Registers Format Document and Format Selection for `.xosc` documents. */
export function register(connection: Connection, context: FormattingContext): void {
  const run = async (name: string, uri: string, options: FormattingOptions, range?: { start: number; end: number }): Promise<TextEdit[]> => {
    const document = context.documents.get(uri);
    // The client sends only documents of the xosc language (untitled ones too); a package is never text.
    if (!document || /\.mosc$/i.test(uri)) return [];
    try {
      const parsed = await context.parsed?.(uri);
      const { edits, refusal } = formattingEdits(document, options, context.workspace.settings.formatMaxLineWidth, range, parsed);
      // A notification, not a request: nothing waits for the user to dismiss it.
      if (refusal) void connection.sendNotification(ShowMessageNotification.type, { type: MessageType.Warning, message: refusal });
      return edits;
    } catch (error) {
      connection.console.error(`${name} failed: ${(error as Error)?.stack ?? String(error)}`);
      throw new ResponseError(-32603, `${name} failed: ${(error as Error)?.message ?? String(error)}`);
    }
  };
  connection.onDocumentFormatting((params) => run('formatting', params.textDocument.uri, params.options));
  connection.onDocumentRangeFormatting((params) => {
    const document = context.documents.get(params.textDocument.uri);
    if (!document) return [];
    const range = { start: document.offsetAt(params.range.start), end: document.offsetAt(params.range.end) };
    return run('rangeFormatting', params.textDocument.uri, params.options, range);
  });
}

/** The capabilities this module serves, for the initialize result. */
export const formattingCapabilities = { documentFormattingProvider: true, documentRangeFormattingProvider: true } as const;
