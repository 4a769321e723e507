import { DocumentDiagnosticReport, DocumentDiagnosticReportKind } from 'vscode-languageserver/node';
import { refId } from '../core/sources';
import { fileDiagnostics, problemsByFile } from '../features/workspaceDiagnostics';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/diagnostic';

/** `textDocument/diagnostic` (pull): an open file's own problems and those other files' analyses place in it. */
export function register(context: ServerContext): void {
  const { workspace } = context;
  context.connection.languages.diagnostics.on(
    request(context, METHOD, async (params, token): Promise<DocumentDiagnosticReport> => {
      const version = String(workspace.version);
      if (params.previousResultId === version) return { kind: DocumentDiagnosticReportKind.Unchanged, resultId: version };
      const open = await openDocument(context, params.textDocument.uri);
      if (!open) return { kind: DocumentDiagnosticReportKind.Full, items: [] };
      const mains = [open.ref, ...(await workspace.referringFiles(open.ref))];
      checkCancelled(token, METHOD);
      const placed = (await problemsByFile(workspace, mains, token)).get(refId(open.ref))?.problems ?? [];
      checkCancelled(token, METHOD);
      const items = await fileDiagnostics(workspace, open.ref, placed);
      context.outsideWatchers.schedule();
      return { kind: DocumentDiagnosticReportKind.Full, resultId: version, items };
    }),
  );
}
