import { FormattingOptions, MessageType, ShowMessageNotification, TextEdit } from 'vscode-languageserver/node';
import { XmlDocument } from '../core/xml';
import { formattingEdits } from '../features/formatting';
import { openDocument, request, ServerContext } from './context';

/** The server's own parse of an open scenario file, so that formatting need not parse it again. */
async function parsed(context: ServerContext, uri: string): Promise<XmlDocument | undefined> {
  const open = await openDocument(context, uri);
  return open ? (await context.workspace.source(open.ref)).original?.document : undefined;
}

/** Formats a whole document or the lines of `range`; a malformed document gets a message and no edits. */
export async function formatDocument(
  context: ServerContext,
  uri: string,
  options: FormattingOptions,
  range?: { start: number; end: number },
): Promise<TextEdit[]> {
  const document = context.workspace.documents.text(uri);
  // The client sends only documents of the xosc language (untitled ones too); a package is never text.
  if (!document || /\.mosc$/i.test(uri)) return [];
  const { edits, refusal } = formattingEdits(
    document,
    options,
    context.workspace.settings.formatMaxLineWidth,
    range,
    await parsed(context, uri),
  );
  // A notification, not a request: nothing waits for the user to dismiss it.
  if (refusal) void context.connection.sendNotification(ShowMessageNotification.type, { type: MessageType.Warning, message: refusal });
  return edits;
}

/** `textDocument/formatting`: Format Document, with the editor's indentation options. */
export function register(context: ServerContext): void {
  context.connection.onDocumentFormatting(
    request(context, 'textDocument/formatting', (params) => formatDocument(context, params.textDocument.uri, params.options)),
  );
}
