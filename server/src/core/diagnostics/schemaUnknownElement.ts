import { ProblemDataByCode } from '../problems';
import { SchemaFactsByCode } from '../schema/facts';
import { CoreFix, defineDiagnostic, elementAtRange, FixEdit, isSuggestion, Words } from './definition';
import { QC } from './qcRules';
import { otherVersionsWords } from './schemaVersion';

export function schemaUnknownElementWording(facts: SchemaFactsByCode['schema-unknown-element']): Words {
  if (facts.kind === 'root') return { message: `the root element must be <${facts.expected}>, not <${facts.found}>` };
  const { parent, child, version, introducedIn, suggestion, children } = facts;
  const orMeant = suggestion ? `; or did you mean <${suggestion}>?` : '';
  return {
    message: facts.holdsNoElements
      ? `<${parent}> holds no elements in OpenSCENARIO ${version}, yet <${child}> stands in it`
      : `<${parent}> has no child <${child}> in OpenSCENARIO ${version}`,
    hint: introducedIn
      ? otherVersionsWords(`<${child}>`, introducedIn) + orMeant
      : suggestion
        ? `did you mean <${suggestion}>?`
        : children.length > 0
          ? `its children: ${children.map((other) => `<${other}>`).join(', ')}`
          : undefined,
  };
}

/** An element the schema does not know here: the closest name, in the start tag and the end tag. */
export const SCHEMA_UNKNOWN_ELEMENT = defineDiagnostic({
  code: 'schema-unknown-element',
  rule: { description: 'Every element is one the ASAM schema allows there.', qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-unknown-element'] => isSuggestion(value),
  fixes: async ({ data, document, range, parsed }): Promise<CoreFix[]> => {
    const text = document.getText();
    const element = elementAtRange(await parsed(), document.offsetAt(range.start));
    if (!data?.suggestion || !element) return [];
    const edits: FixEdit[] = [{ place: 'document', range, newText: data.suggestion }];
    const closing = element.selfClosing || !element.closed ? -1 : text.lastIndexOf(`</${element.name}`, element.end);
    if (closing > element.start)
      edits.push({
        place: 'document',
        range: { start: document.positionAt(closing + 2), end: document.positionAt(closing + 2 + element.name.length) },
        newText: data.suggestion,
      });
    return [{ title: `Change to <${data.suggestion}>`, edits, preferred: true }];
  },
});
