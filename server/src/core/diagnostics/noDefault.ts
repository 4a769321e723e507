import { attribute, elementAt, escapeAttributeValue, parseXml } from '../xml';
import { attributeInsertOffset, defineDiagnostic, ProblemWording } from './definition';

/** The related location's note: the listed name without a default. */
export const NO_DEFAULT_LISTED_NOTE = 'listed here without a default value';

/** A key that sets an attribute `element` lists in parameterAttributes but does not write (in `file`). */
export function noDefaultWording(element: string, attributeName: string, file: string): ProblemWording<'no-default'> {
  return {
    severity: 'error',
    code: 'no-default',
    message: `no default value: <${element}> lists '${attributeName}' in parameterAttributes but has no such attribute`,
    hint: `add ${attributeName}="..." to <${element}> in ${file}`,
  };
}

/** A key whose attribute has no default: the key's value becomes the default, in the simple scenario (the related location is the listed name). */
export const NO_DEFAULT = defineDiagnostic({
  code: 'no-default',
  rule: { description: 'An attribute listed in parameterAttributes has a default value.' },
  severity: 'error',
  skippedByForce: true,
  fixes: async ({ document, range, related }) => {
    const target = related && (await related.text());
    if (!related || !target) return [];
    const targetText = target.getText();
    const listedName = targetText.slice(target.offsetAt(related.range.start), target.offsetAt(related.range.end));
    const element = elementAt(parseXml(targetText), target.offsetAt(related.range.start));
    if (!element || !/^[A-Za-z_][-\w]*$/.test(listedName)) return [];
    const parameter = elementAt(parseXml(document.getText()), document.offsetAt(range.start));
    const value = (parameter && attribute(parameter, 'value')?.value) ?? '';
    const at = target.positionAt(attributeInsertOffset(element));
    return [
      {
        title: `Add default ${listedName}="${value}" to <${element.name}>`,
        edits: [{ place: 'related', range: { start: at, end: at }, newText: ` ${listedName}="${escapeAttributeValue(value)}"` }],
        preferred: true,
      },
    ];
  },
});
