import { TextEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { attribute, elementAt, escapeAttributeValue, parseXml } from '../../core/xml';
import { attributeInsertOffset, problemFix, quickFix } from './fix';

/** A key whose attribute has no default: the key's value becomes the default, in the simple scenario (the related location is the listed name). */
export const noDefaultFix = problemFix(['no-default'], async (_data, { document, diagnostic }, workspace) => {
  const related = diagnostic.relatedInformation?.[0];
  if (!related) return [];
  const targetRef = await workspace.uris.toRef(related.location.uri);
  if (!targetRef || (targetRef.entries.length > 0 && !workspace.editablePackages)) return [];
  const targetText = await workspace.text(targetRef);
  if (targetText === undefined) return [];
  const targetDocument = TextDocument.create(related.location.uri, 'xml', 0, targetText);
  const listedName = targetText.slice(
    targetDocument.offsetAt(related.location.range.start),
    targetDocument.offsetAt(related.location.range.end),
  );
  const element = elementAt(parseXml(targetText), targetDocument.offsetAt(related.location.range.start));
  if (!element || !/^[A-Za-z_][-\w]*$/.test(listedName)) return [];
  const parameter = elementAt(parseXml(document.getText()), document.offsetAt(diagnostic.range.start));
  const value = (parameter && attribute(parameter, 'value')?.value) ?? '';
  const at = targetDocument.positionAt(attributeInsertOffset(element));
  return [
    quickFix(
      `Add default ${listedName}="${value}" to <${element.name}>`,
      diagnostic,
      { changes: { [workspace.uriOf(targetRef)]: [TextEdit.insert(at, ` ${listedName}="${escapeAttributeValue(value)}"`)] } },
      true,
    ),
  ];
});
