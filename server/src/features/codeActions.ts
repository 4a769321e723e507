import { CodeAction, Diagnostic, Range as LspRange } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { ProblemCode } from '../core/problems';
import { SourceRef } from '../core/sources';
import { XmlDocument } from '../core/xml';
import { Workspace } from '../workspace';
import { DIAGNOSTIC_SOURCE } from './diagnostics';
import { DiagnosticData, FixDocument, isDiagnosticData, missingKeysAction, PROBLEM_FIXES, ProblemFix } from './fixes';
import { ClientEdits, NO_CLIENT_EDITS, REFACTORINGS, refactoringTarget } from './refactorings';
import { currentDocument } from './schemaCompletion';

/** The fix module of each code (server/src/features/fixes/). */
const FIX_OF_CODE = new Map<ProblemCode, ProblemFix>();
for (const fix of PROBLEM_FIXES) {
  for (const code of fix.codes) {
    if (FIX_OF_CODE.has(code)) throw new Error(`two fix modules handle the problem code '${code}'`);
    FIX_OF_CODE.set(code, fix);
  }
}

function before(a: LspRange['start'], b: LspRange['start']): boolean {
  return a.line < b.line || (a.line === b.line && a.character < b.character);
}

/** Whether two ranges share a position (an empty range at either end of the other counts, as a cursor does in VS Code). */
function intersects(a: LspRange, b: LspRange): boolean {
  return !before(a.end, b.start) && !before(b.end, a.start);
}

/** Whether a client that asks only for actions of the `only` kinds wants one of `kind` (kinds are dotted hierarchies). */
function wanted(kind: string, only: readonly string[] | undefined): boolean {
  return !only || only.some((asked) => kind === asked || kind.startsWith(`${asked}.`));
}

/** The actions of every refactoring (server/src/features/refactorings/) at the range, of the kinds asked for. */
async function refactoringActions(
  workspace: Workspace,
  uri: string,
  ref: SourceRef,
  document: TextDocument,
  range: LspRange,
  only: readonly string[] | undefined,
  client: ClientEdits,
): Promise<CodeAction[]> {
  const asked = REFACTORINGS.filter((refactoring) => wanted(refactoring.kind, only));
  if (asked.length === 0) return [];
  const target = await refactoringTarget(
    workspace,
    uri,
    ref,
    document,
    document.offsetAt(range.start),
    document.offsetAt(range.end),
    client,
  );
  if (!target) return [];
  const actions: CodeAction[] = [];
  for (const refactoring of asked) actions.push(...(await refactoring.actions(target)));
  return actions;
}

/**
 * Quick fixes of the diagnostics the client sends (those of a known code with valid data), or, when it sends none
 * of this server's, of the server's `current` ones at the range; then the missing keys of the group at the range, then the
 * refactorings; `only`: the kinds the client asks for, as LSP's context.only; `client`: the edits it can apply.
 */
export async function codeActions(
  workspace: Workspace,
  uri: string,
  ref: SourceRef,
  document: TextDocument,
  range: LspRange,
  diagnostics: Diagnostic[],
  only?: readonly string[],
  client: ClientEdits = NO_CLIENT_EDITS,
  current?: () => Promise<Diagnostic[]>,
): Promise<CodeAction[]> {
  const fixable: { diagnostic: Diagnostic; data: DiagnosticData }[] = [];
  for (const diagnostic of diagnostics) if (isDiagnosticData(diagnostic.data)) fixable.push({ diagnostic, data: diagnostic.data });
  // Asked before the latest diagnostics reached the client (Ctrl+. right after an edit or opening): the server's own, as they are now.
  if (current && !diagnostics.some((diagnostic) => diagnostic.source === DIAGNOSTIC_SOURCE))
    for (const diagnostic of await current())
      if (intersects(diagnostic.range, range) && isDiagnosticData(diagnostic.data)) fixable.push({ diagnostic, data: diagnostic.data });
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
  actions.push(...(await refactoringActions(workspace, uri, ref, document, range, only, client)));
  return actions;
}
