import { CodeAction, CodeActionKind, Diagnostic, Range as LspRange, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { missingKeysInsertion } from '../../core/diagnostics/unknownKey';
import { keyMatches } from '../../core/keys';
import { SourceRef } from '../../core/sources';
import { elementAt } from '../../core/xml';
import { groupLinkOf, keyChoices, linkOf } from '../../analysis';
import { ancestor } from '../../core/cursor';
import { Workspace } from '../../workspace';
import { isDiagnosticData } from './data';

/** Whether a client that asks only for actions of the `only` kinds wants one of `kind` (kinds are dotted hierarchies). */
function wanted(kind: string, only: readonly string[] | undefined): boolean {
  return !only || only.some((asked) => kind === asked || kind.startsWith(`${asked}.`));
}

/**
 * Adds a ParameterReference with its default for every overridable attribute no key reaches yet. A
 * group that is complete is valid, so this is no quick fix on every line of it: a quick fix of the
 * `unknown-key` diagnostics of the group (a misspelt key usually means a missing one), otherwise a
 * rewrite offered on the `<ManeuverGroupReference ...>` tag itself.
 */
export async function missingKeysAction(
  workspace: Workspace,
  uri: string,
  ref: SourceRef,
  document: TextDocument,
  range: LspRange,
  diagnostics: readonly Diagnostic[],
  only: readonly string[] | undefined,
): Promise<CodeAction | undefined> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return undefined;
  const groupReference = ancestor(elementAt(model.document, document.offsetAt(range.start)), 'ManeuverGroupReference');
  const reference = ancestor(groupReference?.parent, 'ScenarioReference');
  const link = reference ? linkOf(source, reference) : undefined;
  const linked = link && groupReference ? groupLinkOf(link, groupReference) : undefined;
  if (!groupReference || !linked?.target || groupReference.selfClosing || !groupReference.closed) return undefined;
  const inGroup = (at: LspRange) => document.offsetAt(at.start) >= groupReference.start && document.offsetAt(at.end) <= groupReference.end;
  const askedBy = diagnostics.filter(
    (diagnostic) => isDiagnosticData(diagnostic.data) && diagnostic.data.code === 'unknown-key' && inGroup(diagnostic.range),
  );
  const onTag = document.offsetAt(range.start) >= groupReference.start && document.offsetAt(range.end) <= groupReference.startTagEnd;
  const kind = askedBy.length > 0 ? CodeActionKind.QuickFix : CodeActionKind.RefactorRewrite;
  if ((askedBy.length === 0 && !onTag) || !wanted(kind, only)) return undefined;
  const given = linked.info.parameters.map((parameter) => parameter.key);
  const missing = keyChoices(linked.overridable).filter(
    (choice) =>
      choice.forms.length > 0 &&
      choice.targets[0].defaultValue !== undefined &&
      !choice.targets.some((target) => given.some((key) => keyMatches(key, target))),
  );
  if (missing.length === 0) return undefined;
  const lastParameter = linked.info.parameters[linked.info.parameters.length - 1];
  const insertion = missingKeysInsertion(
    document.getText(),
    groupReference.start,
    groupReference.end,
    lastParameter?.element.start,
    missing.map((choice) => ({ key: choice.forms[0], defaultValue: choice.targets[0].defaultValue ?? '' })),
  );
  return {
    title: insertion.title,
    kind,
    edit: { changes: { [uri]: [TextEdit.insert(document.positionAt(insertion.offset), insertion.newText)] } },
  };
}
