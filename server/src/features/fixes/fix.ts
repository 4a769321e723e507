import { CodeAction, CodeActionKind, Diagnostic, Range as LspRange, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { ProblemCode, ProblemCodeWithData, ProblemDataByCode } from '../../core/problems';
import { SourceRef } from '../../core/sources';
import { XmlDocument } from '../../core/xml';
import { Workspace } from '../../workspace';
import { DiagnosticData, DiagnosticDataOf } from './data';

/** The diagnostic a fix answers, in the document the request is about. */
export interface FixDocument {
  uri: string;
  ref: SourceRef;
  document: TextDocument;
  diagnostic: Diagnostic;
  /** The document's parse tree (parsed at most once per request). */
  parsed(): Promise<XmlDocument>;
}

/** The data a code carries to its fix: the shape `ProblemDataByCode` names, none for a code without data. */
export type FixDataOf<C extends ProblemCode> = C extends ProblemCodeWithData ? ProblemDataByCode[C] : never;

/** The quick fixes of one diagnostic of one of a module's codes. */
export type FixFunction<C extends ProblemCode> = (
  data: FixDataOf<C> | undefined,
  target: FixDocument,
  workspace: Workspace,
) => CodeAction[] | Promise<CodeAction[]>;

/** A fix module: the codes it handles and their fixes. */
export interface ProblemFix {
  readonly codes: readonly ProblemCode[];
  fixes(data: DiagnosticData, target: FixDocument, workspace: Workspace): Promise<CodeAction[]>;
}

function hasCode<C extends ProblemCode>(data: DiagnosticData, codes: readonly C[]): data is DiagnosticDataOf<C> {
  return (codes as readonly ProblemCode[]).includes(data.code);
}

/** A fix module for `codes`, whose fix function receives the data of those codes only. */
export function problemFix<C extends ProblemCode>(codes: readonly C[], fixes: FixFunction<C>): ProblemFix {
  return {
    codes,
    fixes: async (data, target, workspace) => {
      if (!hasCode(data, codes)) return [];
      return fixes('data' in data ? (data.data as FixDataOf<C> | undefined) : undefined, target, workspace);
    },
  };
}

export function singleEdit(uri: string, range: LspRange, newText: string): WorkspaceEdit {
  return { changes: { [uri]: [TextEdit.replace(range, newText)] } };
}

export function quickFix(title: string, diagnostic: Diagnostic | undefined, edit: WorkspaceEdit, preferred = false): CodeAction {
  const action: CodeAction = { title, kind: CodeActionKind.QuickFix, edit };
  if (diagnostic) action.diagnostics = [diagnostic];
  if (preferred) action.isPreferred = true;
  return action;
}
