import { elementAt, parseXml } from '../xml';
import { attributeInsertOffset, CoreFix, defineDiagnostic, isSuggestion, ProblemWording } from './definition';

/** A name in `parameterAttributes` of `element` that names none of its `attributes`; `suggestion`: the closest one. */
export function unknownParameterAttributeWording(
  name: string,
  element: string,
  attributes: readonly string[],
  suggestion: string | undefined,
): ProblemWording<'unknown-parameter-attribute'> {
  return {
    severity: 'warning',
    code: 'unknown-parameter-attribute',
    message:
      `'${name}' names no attribute of <${element}>, so no default value exists and no key can override it` +
      (attributes.length ? ` (its attributes: ${attributes.join(', ')})` : ''),
    hint: suggestion ? `write '${suggestion}'` : `add ${name}="..." to <${element}> as its default`,
  };
}

/** A listed name that is no attribute of its element: the closest attribute, or the attribute added with an empty default. */
export const UNKNOWN_PARAMETER_ATTRIBUTE = defineDiagnostic({
  code: 'unknown-parameter-attribute',
  rule: { description: 'A parameterAttributes entry names an attribute of its element.' },
  severity: 'warning',
  skippedByForce: true,
  isData: isSuggestion,
  fixes: ({ data, document, range }) => {
    const text = document.getText();
    const fixes: CoreFix[] = [];
    const listedName = text.slice(document.offsetAt(range.start), document.offsetAt(range.end));
    if (data?.suggestion)
      fixes.push({
        title: `List '${data.suggestion}' instead`,
        edits: [{ place: 'document', range, newText: data.suggestion }],
        preferred: true,
      });
    const element = elementAt(parseXml(text), document.offsetAt(range.start));
    if (element && /^[A-Za-z_][-\w]*$/.test(listedName)) {
      const at = document.positionAt(attributeInsertOffset(element));
      fixes.push({
        title: `Add a default value for '${listedName}'`,
        edits: [{ place: 'document', range: { start: at, end: at }, newText: ` ${listedName}=""` }],
      });
    }
    return fixes;
  },
});
