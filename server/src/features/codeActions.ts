import { CodeAction, Diagnostic, Range as LspRange } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { ProblemCode } from '../core/problems';
import { SourceRef } from '../core/sources';
import { XmlDocument } from '../core/xml';
import { Workspace } from '../workspace';
import { DiagnosticData, FixDocument, isDiagnosticData, missingKeysAction, PROBLEM_FIXES, ProblemFix } from './fixes';
import { currentDocument } from './schemaCompletion';

/** The fix module of each code (server/src/features/fixes/). */
const FIX_OF_CODE = new Map<ProblemCode, ProblemFix>();
for (const fix of PROBLEM_FIXES) {
  for (const code of fix.codes) {
    if (FIX_OF_CODE.has(code)) throw new Error(`two fix modules handle the problem code '${code}'`);
    FIX_OF_CODE.set(code, fix);
  }
}

/**
 * Quick fixes of the diagnostics the client sends (those of a known code with valid data), then the
 * missing keys of the group at the range; `only`: the kinds the client asks for, as LSP's context.only.
 */
export async function codeActions(
  workspace: Workspace,
  uri: string,
  ref: SourceRef,
  document: TextDocument,
  range: LspRange,
  diagnostics: Diagnostic[],
  only?: readonly string[],
): Promise<CodeAction[]> {
  const fixable: { diagnostic: Diagnostic; data: DiagnosticData }[] = [];
  for (const diagnostic of diagnostics) if (isDiagnosticData(diagnostic.data)) fixable.push({ diagnostic, data: diagnostic.data });
  // The schema's fixes come after the others', in the order of their diagnostics.
  const isSchema = (entry: { data: DiagnosticData }) => entry.data.code.startsWith('schema-');
  const ordered = [...fixable.filter((entry) => !isSchema(entry)), ...fixable.filter(isSchema)];
  let parsed: Promise<XmlDocument> | undefined;
  const actions: CodeAction[] = [];
  for (const { diagnostic, data } of ordered) {
    const fix = FIX_OF_CODE.get(data.code);
    if (!fix) continue;
    const target: FixDocument = { uri, ref, document, diagnostic, parsed: () => (parsed ??= currentDocument(workspace, ref, document)) };
    actions.push(...(await fix.fixes(data, target, workspace)));
  }
  const missing = await missingKeysAction(workspace, uri, ref, document, range, diagnostics, only);
  if (missing) actions.push(missing);
  return actions;
}
