import { CodeAction, CodeActionKind, Diagnostic, WorkspaceEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { ProblemCode } from '../../core/problems';
import { SourceRef } from '../../core/sources';
import { XmlDocument } from '../../core/xml';
import { Workspace } from '../../workspace';
import { DiagnosticData } from './data';

/** The diagnostic a fix answers, in the document the request is about. */
export interface FixDocument {
  uri: string;
  ref: SourceRef;
  document: TextDocument;
  diagnostic: Diagnostic;
  /** The document's parse tree (parsed at most once per request). */
  parsed(): Promise<XmlDocument>;
}

/** The fixes of some codes, as the editor's code actions (definitionFix.ts makes one of each diagnostic's module). */
export interface ProblemFix {
  readonly codes: readonly ProblemCode[];
  fixes(data: DiagnosticData, target: FixDocument, workspace: Workspace): Promise<CodeAction[]>;
}

export function quickFix(title: string, diagnostic: Diagnostic | undefined, edit: WorkspaceEdit, preferred = false): CodeAction {
  const action: CodeAction = { title, kind: CodeActionKind.QuickFix, edit };
  if (diagnostic) action.diagnostics = [diagnostic];
  if (preferred) action.isPreferred = true;
  return action;
}
