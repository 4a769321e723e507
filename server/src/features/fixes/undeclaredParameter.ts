import { CodeAction, CodeActionKind, Diagnostic, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { FlatSource } from '../../core/flatten';
import { Declaration, DocumentSemantics, scopeAt } from '../../core/semantics';
import { displayRef } from '../../core/sources';
import { indentationAt } from '../../core/text';
import { escapeAttributeValue, XmlElement } from '../../core/xml';
import { problemFix } from './fix';

/**
 * Quick fix for an undeclared parameter: declare it in the nearest enclosing ParameterDeclarations
 * (one is created at the root when no enclosing scope has any), with the value of a same-named
 * declaration of a source the file imports, or of this file's other scopes, where one exists.
 */

interface Template {
  type: string;
  value: string;
  from: string | undefined;
}

function templateOf(declaration: Declaration, from: string): Template {
  return { type: declaration.writtenType ?? 'string', value: declaration.value, from };
}

/** The source's declaration of a name: a simple scenario the file imports, else another scope of the file. */
function sourceTemplate(source: FlatSource, semantics: DocumentSemantics, name: string, folder: string | undefined): Template | undefined {
  for (const link of source.links) {
    const declaration = link.source?.semantics?.model.root?.byName.get(name);
    if (declaration && link.source) return templateOf(declaration, displayRef(link.source.ref, folder));
  }
  const elsewhere = semantics.model.declarations.find((declaration) => declaration.name === name && declaration.kind === 'parameter');
  return elsewhere
    ? templateOf(elsewhere, `line ${semantics.model.document.lines.positionAt(elsewhere.element.start).line + 1}`)
    : undefined;
}

function declarationsChild(element: XmlElement): XmlElement | undefined {
  return element.children.find((child) => child.name === 'ParameterDeclarations');
}

function unitOf(text: string): string {
  return /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ';
}

function declareParameterFix(
  uri: string,
  document: TextDocument,
  source: FlatSource,
  semantics: DocumentSemantics,
  diagnostic: Diagnostic,
  name: string,
  folder: string | undefined,
): CodeAction | undefined {
  const text = document.getText();
  const offset = document.offsetAt(diagnostic.range.start);
  const template = sourceTemplate(source, semantics, name, folder);
  const line = `<ParameterDeclaration name="${name}" parameterType="${escapeAttributeValue(template?.type ?? 'string')}" value="${escapeAttributeValue(template?.value ?? '')}"/>`;
  const eol = text.includes('\r\n') ? '\r\n' : '\n';
  const unit = unitOf(text);
  let scope = scopeAt(semantics, offset);
  while (scope && !declarationsChild(scope.element)) scope = scope.parent;
  const holder = scope ? declarationsChild(scope.element) : undefined;
  let edit: TextEdit;
  if (holder && !holder.selfClosing && holder.closed) {
    const close = text.lastIndexOf('</', holder.end - 1);
    const closeLineStart = text.lastIndexOf('\n', close - 1) + 1;
    const outer = indentationAt(text, holder.start);
    const onOwnLine = /^[ \t]*$/.test(text.slice(closeLineStart, close));
    edit = onOwnLine
      ? TextEdit.insert(document.positionAt(closeLineStart), `${outer}${unit}${line}${eol}`)
      : TextEdit.insert(document.positionAt(close), `${eol}${outer}${unit}${line}${eol}${outer}`);
  } else if (holder) {
    const outer = indentationAt(text, holder.start);
    edit = TextEdit.replace(
      { start: document.positionAt(holder.start), end: document.positionAt(holder.end) },
      `<ParameterDeclarations>${eol}${outer}${unit}${line}${eol}${outer}</ParameterDeclarations>`,
    );
  } else {
    const root = semantics.model.root?.element;
    if (!root) return undefined;
    // The standard's order puts ParameterDeclarations right after the FileHeader.
    const header = root.children.find((child) => child.name === 'FileHeader');
    const anchor = header ? header.end : root.startTagEnd;
    const outer = header ? indentationAt(text, header.start) : indentationAt(text, root.start) + unit;
    edit = TextEdit.insert(
      document.positionAt(anchor),
      `${eol}${outer}<ParameterDeclarations>${eol}${outer}${unit}${line}${eol}${outer}</ParameterDeclarations>`,
    );
  }
  const title = template?.from
    ? `Declare parameter '${name}' (value ${template.value} from ${template.from})`
    : `Declare parameter '${name}'`;
  return { title, kind: CodeActionKind.QuickFix, diagnostics: [diagnostic], isPreferred: true, edit: { changes: { [uri]: [edit] } } };
}

export const undeclaredParameterFix = problemFix(
  ['undeclared-parameter', 'undeclared-catalog-parameter'],
  async (data, { uri, ref, document, diagnostic }, workspace) => {
    const source = await workspace.source(ref);
    const fix =
      data?.parameter && source.semantics
        ? declareParameterFix(uri, document, source, source.semantics, diagnostic, data.parameter, workspace.folders[0])
        : undefined;
    return fix ? [fix] : [];
  },
);
