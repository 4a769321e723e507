import { CodeAction, CodeActionKind, Range as LspRange, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { keyMatches } from '../../core/keys';
import { SourceRef } from '../../core/sources';
import { elementAt, escapeAttributeValue } from '../../core/xml';
import { groupLinkOf, keyChoices, linkOf } from '../../analysis';
import { ancestor } from '../../core/cursor';
import { Workspace } from '../../workspace';
import { indentOfLine } from './fix';

/** Adds a ParameterReference with its default for every overridable attribute no key reaches yet (an action at a range, of no diagnostic). */
export async function missingKeysAction(workspace: Workspace, uri: string, ref: SourceRef, document: TextDocument, range: LspRange): Promise<CodeAction | undefined> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return undefined;
  const groupReference = ancestor(elementAt(model.document, document.offsetAt(range.start)), 'ManeuverGroupReference');
  const reference = ancestor(groupReference?.parent, 'ScenarioReference');
  const link = reference ? linkOf(source, reference) : undefined;
  const linked = link && groupReference ? groupLinkOf(link, groupReference) : undefined;
  if (!groupReference || !linked?.target || groupReference.selfClosing || !groupReference.closed) return undefined;
  const given = linked.info.parameters.map((parameter) => parameter.key);
  const missing = keyChoices(linked.overridable).filter(
    (choice) => choice.forms.length > 0 && choice.targets[0].defaultValue !== undefined && !choice.targets.some((target) => given.some((key) => keyMatches(key, target))),
  );
  if (missing.length === 0) return undefined;
  const text = document.getText();
  const closeTag = text.lastIndexOf('</', groupReference.end - 1);
  const outerIndent = indentOfLine(text, groupReference.start);
  const lastParameter = linked.info.parameters[linked.info.parameters.length - 1];
  const unit = /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '    ';
  const indent = lastParameter ? indentOfLine(text, lastParameter.element.start) : outerIndent + unit;
  const eol = text.includes('\r\n') ? '\r\n' : '\n';
  const lines = missing.map((choice) => `${indent}<ParameterReference key="${choice.forms[0]}" value="${escapeAttributeValue(choice.targets[0].defaultValue ?? '')}"/>`);
  // Insert at the start of the closing tag's line, so that its indentation stays as written.
  const closeLineStart = text.lastIndexOf('\n', closeTag - 1) + 1;
  const onOwnLine = /^[ \t]*$/.test(text.slice(closeLineStart, closeTag));
  const insertAt = onOwnLine ? closeLineStart : closeTag;
  const newText = onOwnLine ? lines.join(eol) + eol : eol + lines.join(eol) + eol + outerIndent;
  return {
    title: `Add ${missing.length} missing key${missing.length === 1 ? '' : 's'} with their defaults`,
    kind: CodeActionKind.QuickFix,
    edit: { changes: { [uri]: [TextEdit.insert(document.positionAt(insertAt), newText)] } },
  };
}
