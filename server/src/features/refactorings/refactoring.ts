import {
  CodeAction,
  CreateFile,
  OptionalVersionedTextDocumentIdentifier,
  TextDocumentEdit,
  TextEdit,
  WorkspaceEdit,
} from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { TextEdit as CoreTextEdit } from '../../core/flatten/edits';
import { FlatSource } from '../../core/flatten';
import { ScenarioModel } from '../../core/model';
import { SourceRef } from '../../core/sources';
import { isWellFormed } from '../../core/xml';
import { Workspace } from '../../workspace';

/** What the client said it can apply, filled in by `initialize`. */
export interface ClientEdits {
  /** `workspace.workspaceEdit.documentChanges`. */
  documentChanges: boolean;
  /** `workspace.workspaceEdit.resourceOperations` includes `create`. */
  createFiles: boolean;
  /** The client shows a pick list of attributes before extracting a group (the VS Code extension). */
  extractPicker: boolean;
  /** The client has INSERT_LIBRARY_MODULE_COMMAND, which picks a library module and asks for the edit (the VS Code extension). */
  libraryPicker: boolean;
}

export const NO_CLIENT_EDITS: ClientEdits = { documentChanges: false, createFiles: false, extractPicker: false, libraryPicker: false };

/** The place a refactoring is asked about: one document, one range, its model as read. */
export interface RefactoringTarget {
  workspace: Workspace;
  uri: string;
  ref: SourceRef;
  document: TextDocument;
  /** Offsets of the range's start and end. */
  start: number;
  end: number;
  source: FlatSource;
  model: ScenarioModel;
  client: ClientEdits;
}

/** A refactoring module: the code action kind it offers and its actions at a target. */
export interface Refactoring {
  readonly kind: string;
  actions(target: RefactoringTarget): Promise<CodeAction[]>;
}

/** Core edits (offsets) as LSP edits of `document`. */
export function lspEdits(document: TextDocument, edits: readonly CoreTextEdit[]): TextEdit[] {
  return edits.map((edit) => TextEdit.replace({ start: document.positionAt(edit.start), end: document.positionAt(edit.end) }, edit.text));
}

/** The edits of one document, versioned when the client can check the version. */
export function documentEdit(target: RefactoringTarget, edits: readonly CoreTextEdit[]): WorkspaceEdit {
  if (!target.client.documentChanges) return { changes: { [target.uri]: lspEdits(target.document, edits) } };
  return {
    documentChanges: [
      TextDocumentEdit.create(
        OptionalVersionedTextDocumentIdentifier.create(target.uri, target.document.version),
        lspEdits(target.document, edits),
      ),
    ],
  };
}

/** Why a client cannot take an edit that creates files, or undefined when it can. */
export function cannotCreateFiles(client: ClientEdits): string | undefined {
  if (!client.documentChanges) return 'the editor cannot apply edits that create files (no workspaceEdit.documentChanges)';
  if (!client.createFiles) return 'the editor cannot create files through an edit (no workspaceEdit.resourceOperations "create")';
  return undefined;
}

/** Another file a refactoring writes: created with `text`, or edited (`edits`, offsets of `text`, its current content). */
export interface FileChange {
  uri: string;
  create: boolean;
  text: string;
  edits: readonly CoreTextEdit[];
  /** The version of the open document, when the client has it open. */
  version?: number;
}

/** An edit that creates or edits `files`, then edits the target's document. */
export function createAndEdit(target: RefactoringTarget, files: readonly FileChange[], edits: readonly CoreTextEdit[]): WorkspaceEdit {
  const changes: (CreateFile | TextDocumentEdit)[] = [];
  for (const file of files) {
    const identifier = OptionalVersionedTextDocumentIdentifier.create(file.uri, file.version ?? null);
    if (file.create) {
      changes.push(CreateFile.create(file.uri, { overwrite: false, ignoreIfExists: false }));
      changes.push(TextDocumentEdit.create(identifier, [TextEdit.insert({ line: 0, character: 0 }, file.text)]));
    } else if (file.edits.length > 0) {
      changes.push(TextDocumentEdit.create(identifier, lspEdits(TextDocument.create(file.uri, 'xml', 0, file.text), file.edits)));
    }
  }
  changes.push(
    TextDocumentEdit.create(
      OptionalVersionedTextDocumentIdentifier.create(target.uri, target.document.version),
      lspEdits(target.document, edits),
    ),
  );
  return { documentChanges: changes };
}

/** The target of a refactoring at `start`..`end` of an open document; undefined while the analysis lags behind the text or it is not well-formed. */
export async function refactoringTarget(
  workspace: Workspace,
  uri: string,
  ref: SourceRef,
  document: TextDocument,
  start: number,
  end: number,
  client: ClientEdits,
): Promise<RefactoringTarget | undefined> {
  const source = await workspace.source(ref);
  const model = source.original;
  // A source of an older text than the document's would put the edits in the wrong places; a text
  // that is not well-formed XML has no trustworthy element boundaries to move.
  if (!model || model.document.text !== document.getText() || !isWellFormed(model.document)) return undefined;
  return { workspace, uri, ref, document, start, end, source, model, client };
}
