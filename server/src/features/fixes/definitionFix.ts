import { CodeAction, CodeActionKind, RenameFile, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { EXPORT_FOR_CARLA_COMMAND } from '../../../../common/src/protocol';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { CoreFix, EditorCommand, FixContext, RegisteredDiagnostic, RelatedPlace } from '../../core/diagnostics';
import { fileUri } from '../../uris';
import { SourceRef } from '../../core/sources';
import { Workspace } from '../../workspace';
import { FixDocument, ProblemFix, quickFix } from './fix';
import { parameterScopesOf } from './parameterScopes';

/** The file of the diagnostic's first related location, where a fix may edit it: its ref and the URI edits name. */
type EditableFile = { ref: SourceRef; uri: string } | undefined;

function relatedPlace(target: FixDocument, workspace: Workspace, file: () => Promise<EditableFile>): RelatedPlace | undefined {
  const related = target.diagnostic.relatedInformation?.[0];
  if (!related) return undefined;
  const uri = related.location.uri;
  return {
    range: related.location.range,
    sameDocument: uri === target.uri,
    fileName: decodeURIComponent(uri.slice(uri.lastIndexOf('/') + 1)),
    editable: async () => (await file()) !== undefined,
    text: async () => {
      const editable = await file();
      const text = editable && (await workspace.text(editable.ref));
      return text === undefined ? undefined : TextDocument.create(uri, 'xml', 0, text);
    },
  };
}

/** The editor's command for each command a core fix may offer. */
const EDITOR_COMMANDS: Record<EditorCommand, string> = { 'export-for-carla': EXPORT_FOR_CARLA_COMMAND };

/** A fix of the core (text edits in the document or its related file, a file's rename, an editor command) as a code action of the diagnostic. */
async function codeAction(fix: CoreFix, target: FixDocument, file: () => Promise<EditableFile>): Promise<CodeAction> {
  if (fix.command)
    return {
      title: fix.title,
      kind: CodeActionKind.QuickFix,
      diagnostics: [target.diagnostic],
      command: { title: fix.title, command: EDITOR_COMMANDS[fix.command], arguments: [target.uri] },
    };
  if (fix.rename) {
    const rename = RenameFile.create(fileUri(fix.rename.from).toString(), fileUri(fix.rename.to).toString(), { overwrite: false });
    return quickFix(fix.title, target.diagnostic, { documentChanges: [rename] }, fix.preferred);
  }
  const changes: NonNullable<WorkspaceEdit['changes']> = {};
  for (const edit of fix.edits) {
    const uri = edit.place === 'document' ? target.uri : (await file())?.uri;
    // A module asks `related.editable()` before it edits there: an edit of another file is a mistake of the module.
    if (uri === undefined) throw new Error(`the fix '${fix.title}' edits a related file it may not edit`);
    (changes[uri] ??= []).push(TextEdit.replace(edit.range, edit.newText));
  }
  return quickFix(fix.title, target.diagnostic, { changes }, fix.preferred);
}

/** The fixes of a diagnostic's module (core/diagnostics/) as the editor's quick fixes. */
export function definitionFix(definition: RegisteredDiagnostic): ProblemFix {
  return {
    codes: [definition.code],
    fixes: async (data, target, workspace) => {
      if (data.code !== definition.code || !definition.fixes) return [];
      const related = target.diagnostic.relatedInformation?.[0];
      let editable: Promise<EditableFile> | undefined;
      const file = () =>
        (editable ??= (async () => {
          const ref = related ? await workspace.uris.toRef(related.location.uri) : undefined;
          if (!ref || (ref.entries.length > 0 && !workspace.editablePackages)) return undefined;
          return { ref, uri: workspace.uriOf(ref) };
        })());
      const context: FixContext<unknown> = {
        data: 'data' in data ? data.data : undefined,
        document: target.document,
        range: target.diagnostic.range,
        parsed: target.parsed,
        related: relatedPlace(target, workspace, file),
        schemaVersion: workspace.settings.schemaVersion,
        parameters: () => parameterScopesOf(workspace, target),
      };
      const fixes = await definition.fixes(context);
      return Promise.all(fixes.map((fix) => codeAction(fix, target, file)));
    },
  };
}
