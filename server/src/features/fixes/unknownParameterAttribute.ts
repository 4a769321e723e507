import { CodeAction, TextEdit } from 'vscode-languageserver/node';
import { elementAt, parseXml } from '../../core/xml';
import { attributeInsertOffset, problemFix, quickFix, singleEdit } from './fix';

/** A listed name that is no attribute of its element: the closest attribute, or the attribute added with an empty default. */
export const unknownParameterAttributeFix = problemFix(['unknown-parameter-attribute'], (data, { uri, document, diagnostic }) => {
  const text = document.getText();
  const actions: CodeAction[] = [];
  const listedName = text.slice(document.offsetAt(diagnostic.range.start), document.offsetAt(diagnostic.range.end));
  if (data?.suggestion)
    actions.push(quickFix(`List '${data.suggestion}' instead`, diagnostic, singleEdit(uri, diagnostic.range, data.suggestion), true));
  const element = elementAt(parseXml(text), document.offsetAt(diagnostic.range.start));
  if (element && /^[A-Za-z_][-\w]*$/.test(listedName)) {
    const at = document.positionAt(attributeInsertOffset(element));
    actions.push(
      quickFix(`Add a default value for '${listedName}'`, diagnostic, { changes: { [uri]: [TextEdit.insert(at, ` ${listedName}=""`)] } }),
    );
  }
  return actions;
});
