import { CodeAction, CodeActionKind, Diagnostic, Range as LspRange, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { keyMatches } from '../core/keys';
import { PARAMETER_ATTRIBUTES } from '../core/model';
import { SourceRef } from '../core/sources';
import { attribute, elementAt, escapeAttributeValue, parseXml, XmlElement } from '../core/xml';
import { groupLinkOf, keyChoices, linkOf } from '../analysis';
import { ancestor } from '../core/cursor';
import { declareParameterFix } from './declareParameter';
import { DiagnosticData } from './diagnostics';
import { Workspace } from '../workspace';
import { schemaFixes } from './schemaCodeActions';
import { currentDocument } from './schemaCompletion';

/** A file with more groups than this offers only the first ones as fixes of an unknown group. */
const MAX_GROUP_FIXES = 20;

function singleEdit(uri: string, range: LspRange, newText: string): WorkspaceEdit {
  return { changes: { [uri]: [TextEdit.replace(range, newText)] } };
}

function quickFix(title: string, diagnostic: Diagnostic | undefined, edit: WorkspaceEdit, preferred = false): CodeAction {
  const action: CodeAction = { title, kind: CodeActionKind.QuickFix, edit };
  if (diagnostic) action.diagnostics = [diagnostic];
  if (preferred) action.isPreferred = true;
  return action;
}

/** The text offset where a new attribute goes: right after parameterAttributes, else after the element name. */
function attributeInsertOffset(element: XmlElement): number {
  const declaration = attribute(element, PARAMETER_ATTRIBUTES);
  return declaration ? declaration.valueEnd + 1 : element.nameEnd;
}

function indentOfLine(text: string, offset: number): string {
  const lineStart = text.lastIndexOf('\n', offset - 1) + 1;
  return /^[ \t]*/.exec(text.slice(lineStart))?.[0] ?? '';
}

async function fixesFor(workspace: Workspace, uri: string, ref: SourceRef, document: TextDocument, diagnostic: Diagnostic): Promise<CodeAction[]> {
  const data = diagnostic.data as DiagnosticData | undefined;
  if (!data || typeof data.code !== 'string') return [];
  const text = document.getText();
  switch (data.code) {
    case 'unknown-key': {
      if (data.suggestion) return [quickFix(`Change key to '${data.suggestion}'`, diagnostic, singleEdit(uri, diagnostic.range, data.suggestion), true)];
      const related = diagnostic.relatedInformation?.[0];
      if (!data.relatedReplacement || !related) return [];
      const targetRef = await workspace.uris.toRef(related.location.uri);
      if (!targetRef || (targetRef.entries.length > 0 && !workspace.editablePackages)) return [];
      const fileName = related.location.uri.slice(related.location.uri.lastIndexOf('/') + 1);
      return [quickFix(`List '${data.relatedReplacement}' in ${decodeURIComponent(fileName)} instead`, diagnostic, singleEdit(workspace.uriOf(targetRef), related.location.range, data.relatedReplacement), true)];
    }
    case 'xosc-fallback':
      return data.replacement ? [quickFix(`Change to '${data.replacement}'`, diagnostic, singleEdit(uri, diagnostic.range, data.replacement), true)] : [];
    case 'unknown-group': {
      // The closest name first (preferred), then every other group of the file.
      const names = [...new Set([...(data.suggestion ? [data.suggestion] : []), ...(data.groups ?? '').split('\n').filter((name) => name.length > 0)])];
      return names.slice(0, MAX_GROUP_FIXES).map((name) => quickFix(`Change to '${name}'`, diagnostic, singleEdit(uri, diagnostic.range, name), name === data.suggestion));
    }
    case 'unknown-parameter-attribute': {
      const actions: CodeAction[] = [];
      const listedName = text.slice(document.offsetAt(diagnostic.range.start), document.offsetAt(diagnostic.range.end));
      if (data.suggestion) actions.push(quickFix(`List '${data.suggestion}' instead`, diagnostic, singleEdit(uri, diagnostic.range, data.suggestion), true));
      const element = elementAt(parseXml(text), document.offsetAt(diagnostic.range.start));
      if (element && /^[A-Za-z_][-\w]*$/.test(listedName)) {
        const at = document.positionAt(attributeInsertOffset(element));
        actions.push(quickFix(`Add a default value for '${listedName}'`, diagnostic, { changes: { [uri]: [TextEdit.insert(at, ` ${listedName}=""`)] } }));
      }
      return actions;
    }
    case 'no-default': {
      // The related location is the listed name in the simple scenario; the key's value becomes the default.
      const related = diagnostic.relatedInformation?.[0];
      if (!related) return [];
      const targetRef = await workspace.uris.toRef(related.location.uri);
      if (!targetRef || (targetRef.entries.length > 0 && !workspace.editablePackages)) return [];
      const targetText = await workspace.text(targetRef);
      if (targetText === undefined) return [];
      const targetDocument = TextDocument.create(related.location.uri, 'xml', 0, targetText);
      const listedName = targetText.slice(targetDocument.offsetAt(related.location.range.start), targetDocument.offsetAt(related.location.range.end));
      const element = elementAt(parseXml(targetText), targetDocument.offsetAt(related.location.range.start));
      if (!element || !/^[A-Za-z_][-\w]*$/.test(listedName)) return [];
      const parameter = elementAt(parseXml(text), document.offsetAt(diagnostic.range.start));
      const value = (parameter && attribute(parameter, 'value')?.value) ?? '';
      const at = targetDocument.positionAt(attributeInsertOffset(element));
      return [quickFix(`Add default ${listedName}="${value}" to <${element.name}>`, diagnostic, { changes: { [workspace.uriOf(targetRef)]: [TextEdit.insert(at, ` ${listedName}="${escapeAttributeValue(value)}"`)] } }, true)];
    }
    case 'undeclared-parameter': {
      const source = await workspace.source(ref);
      const fix = data.parameter && source.semantics ? declareParameterFix(uri, document, source, source.semantics, diagnostic, data.parameter, workspace.folders[0]) : undefined;
      return fix ? [fix] : [];
    }
    default:
      return [];
  }
}

/** Adds a ParameterReference with its default for every overridable attribute no key reaches yet. */
async function missingKeysAction(workspace: Workspace, uri: string, ref: SourceRef, document: TextDocument, range: LspRange): Promise<CodeAction | undefined> {
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

export async function codeActions(workspace: Workspace, uri: string, ref: SourceRef, document: TextDocument, range: LspRange, diagnostics: Diagnostic[]): Promise<CodeAction[]> {
  const actions: CodeAction[] = [];
  for (const diagnostic of diagnostics) actions.push(...(await fixesFor(workspace, uri, ref, document, diagnostic)));
  if (diagnostics.some((diagnostic) => String(diagnostic.code).startsWith('schema-'))) {
    const parsed = await currentDocument(workspace, ref, document);
    for (const diagnostic of diagnostics) actions.push(...schemaFixes(uri, document, parsed, workspace.settings.schemaVersion, diagnostic));
  }
  const missing = await missingKeysAction(workspace, uri, ref, document, range);
  if (missing) actions.push(missing);
  return actions;
}
