import { TextEdit } from 'vscode-languageserver/node';
import { indexFor, typeByElementName, typeOfElement } from '../../core/schema/query';
import { elementSkeleton, placeholderValue, skeletonText } from '../../core/schema/skeleton';
import { indentOfLine } from '../../core/diagnostics';
import { problemFix, quickFix } from './fix';
import { elementAtRange } from './schema';

/** Required elements the element lacks: each inserted as a minimal valid skeleton, before the element they must precede or at the end. */
export const schemaMissingElementFix = problemFix(
  ['schema-missing-element'],
  async (data, { uri, document: textDocument, diagnostic, parsed }, workspace) => {
    const tree = await parsed();
    const text = textDocument.getText();
    const start = textDocument.offsetAt(diagnostic.range.start);
    const index = indexFor(tree, workspace.settings.schemaVersion);
    if (!index || !data || data.missing.length === 0) return [];
    const names = data.missing;
    const anchor = elementAtRange(tree, start);
    const parent = data.insertAt !== undefined ? anchor?.parent : anchor;
    if (!parent) return [];
    const parentType = typeOfElement(index, parent) ?? typeByElementName(index, parent.name);
    const eol = text.includes('\r\n') ? '\r\n' : '\n';
    const unit = /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ';
    const childIndent = indentOfLine(text, parent.start) + unit;
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
      edit = TextEdit.insert(
        textDocument.positionAt(at),
        blocksAt(indentOfLine(text, at), eol)
          .map((block) => `${block}${eol}${indentOfLine(text, at)}`)
          .join(''),
      );
    } else if (parent.selfClosing) {
      // `<Parent/>` becomes `<Parent>…</Parent>`.
      const slash = text.lastIndexOf('/', parent.end - 1);
      edit = TextEdit.replace(
        { start: textDocument.positionAt(slash), end: textDocument.positionAt(parent.end) },
        `>${blocksAt(childIndent, eol)
          .map((block) => `${eol}${childIndent}${block}`)
          .join('')}${eol}${indentOfLine(text, parent.start)}</${parent.name}>`,
      );
    } else {
      const closing = text.lastIndexOf(`</${parent.name}`, parent.end);
      if (closing < 0) return [];
      const lineStart = text.lastIndexOf('\n', closing - 1) + 1;
      const onOwnLine = /^[ \t]*$/.test(text.slice(lineStart, closing));
      edit = onOwnLine
        ? TextEdit.insert(
            textDocument.positionAt(lineStart),
            blocksAt(childIndent, eol)
              .map((block) => `${childIndent}${block}${eol}`)
              .join(''),
          )
        : TextEdit.insert(textDocument.positionAt(closing), blocksAt('', '').join(''));
    }
    return [quickFix(`Insert ${names.map((name) => `<${name}>`).join(', ')}`, diagnostic, { changes: { [uri]: [edit] } }, true)];
  },
);
