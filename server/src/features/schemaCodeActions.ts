import { CodeAction, CodeActionKind, Diagnostic, TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { indexFor, typeByElementName, typeOfElement } from '../core/schema/query';
import { elementSkeleton, placeholderValue, skeletonText } from '../core/schema/skeleton';
import { elementAt, XmlDocument, XmlElement } from '../core/xml';
import { DiagnosticData } from './diagnostics';

function fix(title: string, diagnostic: Diagnostic, uri: string, edits: TextEdit[], preferred: boolean): CodeAction {
  return { title, kind: CodeActionKind.QuickFix, diagnostics: [diagnostic], edit: { changes: { [uri]: edits } }, isPreferred: preferred };
}

function indentOf(text: string, offset: number): string {
  const lineStart = text.lastIndexOf('\n', offset - 1) + 1;
  return /^[ \t]*/.exec(text.slice(lineStart))?.[0] ?? '';
}

function elementAtRange(document: XmlDocument, offset: number): XmlElement | undefined {
  const found = elementAt(document, offset);
  return found && found.start + 1 <= offset && offset <= found.nameEnd ? found : undefined;
}

/** Quick fixes for the schema's diagnostics: rename to the closest name or value, insert what is missing. */
export function schemaFixes(uri: string, textDocument: TextDocument, parsed: XmlDocument, setting: Parameters<typeof indexFor>[1], diagnostic: Diagnostic): CodeAction[] {
  const data = diagnostic.data as DiagnosticData | undefined;
  if (!data || typeof data.code !== 'string' || !data.code.startsWith('schema-')) return [];
  const text = textDocument.getText();
  const start = textDocument.offsetAt(diagnostic.range.start);
  switch (data.code) {
    case 'schema-unknown-attribute':
    case 'schema-value':
      return data.suggestion ? [fix(`Change to '${data.suggestion}'`, diagnostic, uri, [TextEdit.replace(diagnostic.range, data.suggestion)], true)] : [];
    case 'schema-unknown-element': {
      const element = elementAtRange(parsed, start);
      if (!data.suggestion || !element) return [];
      const edits = [TextEdit.replace(diagnostic.range, data.suggestion)];
      const closing = element.selfClosing || !element.closed ? -1 : text.lastIndexOf(`</${element.name}`, element.end);
      if (closing > element.start) edits.push(TextEdit.replace({ start: textDocument.positionAt(closing + 2), end: textDocument.positionAt(closing + 2 + element.name.length) }, data.suggestion));
      return [fix(`Change to <${data.suggestion}>`, diagnostic, uri, edits, true)];
    }
    case 'schema-missing-attribute': {
      const index = indexFor(parsed, setting);
      const element = elementAtRange(parsed, start);
      const typeName = index && element ? typeOfElement(index, element) : undefined;
      if (!index || !element || !typeName || !data.missing) return [];
      const names = data.missing.split(',');
      const inserted = names.map((name) => ` ${name}="${placeholderValue(index, index.attribute(typeName, name)?.type ?? '')}"`).join('');
      const last = element.attributes[element.attributes.length - 1];
      const at = last ? last.valueEnd + 1 : element.nameEnd;
      return [fix(`Add ${names.map((name) => `'${name}'`).join(', ')}`, diagnostic, uri, [TextEdit.insert(textDocument.positionAt(at), inserted)], true)];
    }
    case 'schema-missing-element': {
      const index = indexFor(parsed, setting);
      if (!index || !data.missing) return [];
      const names = data.missing.split(',');
      const anchor = elementAtRange(parsed, start);
      const parent = data.insertAt !== undefined ? anchor?.parent : anchor;
      if (!parent) return [];
      const parentType = typeOfElement(index, parent) ?? typeByElementName(index, parent.name);
      const eol = text.includes('\r\n') ? '\r\n' : '\n';
      const unit = /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ';
      const childIndent = indentOf(text, parent.start) + unit;
      // Each missing element as a minimal valid skeleton: its required attributes and children, recursively.
      const blocksAt = (indent: string, lineBreak: string) =>
        names.map((name) => {
          const particle = parentType ? index.childParticle(parentType, name, true) : undefined;
          const skeleton = particle ? elementSkeleton(index, particle) : { name, type: '', attributes: [], children: [] };
          return skeletonText(skeleton, { indent, unit, eol: lineBreak }, (declaration) => placeholderValue(index, declaration.type));
        });
      let edit: TextEdit;
      if (data.insertAt !== undefined) {
        const at = Number(data.insertAt);
        edit = TextEdit.insert(textDocument.positionAt(at), blocksAt(indentOf(text, at), eol).map((block) => `${block}${eol}${indentOf(text, at)}`).join(''));
      } else if (parent.selfClosing) {
        // `<Parent/>` becomes `<Parent>…</Parent>`.
        const slash = text.lastIndexOf('/', parent.end - 1);
        edit = TextEdit.replace(
          { start: textDocument.positionAt(slash), end: textDocument.positionAt(parent.end) },
          `>${blocksAt(childIndent, eol).map((block) => `${eol}${childIndent}${block}`).join('')}${eol}${indentOf(text, parent.start)}</${parent.name}>`,
        );
      } else {
        const closing = text.lastIndexOf(`</${parent.name}`, parent.end);
        if (closing < 0) return [];
        const lineStart = text.lastIndexOf('\n', closing - 1) + 1;
        const onOwnLine = /^[ \t]*$/.test(text.slice(lineStart, closing));
        edit = onOwnLine
          ? TextEdit.insert(textDocument.positionAt(lineStart), blocksAt(childIndent, eol).map((block) => `${childIndent}${block}${eol}`).join(''))
          : TextEdit.insert(textDocument.positionAt(closing), blocksAt('', '').join(''));
      }
      return [fix(`Insert ${names.map((name) => `<${name}>`).join(', ')}`, diagnostic, uri, [edit], true)];
    }
    default:
      return [];
  }
}
