import { DocumentDiagnosticReportKind, WorkspaceDocumentDiagnosticReport } from 'vscode-languageserver/node';
import { refId, SourceRef } from '../core/sources';
import { fileDiagnostics, problemsByFile, ProblemsByFile, workspaceMains } from '../features/workspaceDiagnostics';
import { checkCancelled, request, ServerContext } from './context';

const METHOD = 'workspace/diagnostic';

/** `workspace/diagnostic` (pull): every scenario file of the workspace, as `modular2simple check` reports it. */
export function register(context: ServerContext): void {
  const { workspace } = context;
  // VS Code asks again every two seconds: while nothing changed, the files and their problems are kept.
  let last: { version: string; files: Map<string, SourceRef>; byFile: ProblemsByFile } | undefined;
  context.connection.languages.diagnostics.onWorkspace(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      const version = String(workspace.version);
      const previous = new Map(params.previousResultIds.map((entry) => [entry.uri, entry.value]));
      if (last?.version !== version) {
        const files = new Map<string, SourceRef>();
        for (const main of await workspaceMains(workspace)) files.set(refId(main), main);
        for (const open of workspace.documents.values()) files.set(refId(open.ref), open.ref);
        checkCancelled(token, METHOD);
        const byFile = await problemsByFile(workspace, [...files.values()], token);
        checkCancelled(token, METHOD);
        for (const [id, entry] of byFile) files.set(id, entry.ref);
        last = { version, files, byFile };
      }
      const { files, byFile } = last;
      const items: WorkspaceDocumentDiagnosticReport[] = [];
      for (const [id, ref] of files) {
        const uri = workspace.uriOf(ref);
        const documentVersion = workspace.documents.get(id)?.document.version ?? null;
        if (previous.get(uri) === version) {
          items.push({ kind: DocumentDiagnosticReportKind.Unchanged, uri, version: documentVersion, resultId: version });
        } else {
          items.push({
            kind: DocumentDiagnosticReportKind.Full,
            uri,
            version: documentVersion,
            resultId: version,
            items: await fileDiagnostics(workspace, ref, byFile.get(id)?.problems ?? []),
          });
        }
        checkCancelled(token, METHOD);
      }
      // A file the client still shows that is no scenario file any more (deleted, renamed): VS Code leaves its
      // problems up until told otherwise. No result id, so the client stops asking about it.
      const reported = new Set(items.map((item) => item.uri));
      for (const uri of previous.keys())
        if (!reported.has(uri)) items.push({ kind: DocumentDiagnosticReportKind.Full, uri, version: null, items: [] });
      return { items };
    }),
  );
}
