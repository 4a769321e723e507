import { ProblemDataByCode } from '../problems';
import { SchemaFactsByCode } from '../schema/facts';
import { indexFor, typeOfElement } from '../schema/query';
import { placeholderValue } from '../schema/skeleton';
import { defineDiagnostic, elementAtRange, isRecord, isStringList, Words } from './definition';

export function schemaMissingAttributeWording({ element, missing }: SchemaFactsByCode['schema-missing-attribute']): Words {
  return {
    message: `<${element}> lacks the required attribute${missing.length > 1 ? 's' : ''} ${missing.map((name) => `'${name}'`).join(', ')}`,
  };
}
import { QC } from './qcRules';

/** Required attributes the element lacks: added after its last attribute, each with a placeholder of its type. */
export const SCHEMA_MISSING_ATTRIBUTE = defineDiagnostic({
  code: 'schema-missing-attribute',
  rule: { description: 'Every attribute the ASAM schema requires is present.', qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-missing-attribute'] => isRecord(value) && isStringList(value.missing),
  fixes: async ({ data, document, range, parsed, schemaVersion }) => {
    const tree = await parsed();
    const index = indexFor(tree, schemaVersion);
    const element = elementAtRange(tree, document.offsetAt(range.start));
    const typeName = index && element ? typeOfElement(index, element) : undefined;
    if (!index || !element || !typeName || !data || data.missing.length === 0) return [];
    const names = data.missing;
    const inserted = names.map((name) => ` ${name}="${placeholderValue(index, index.attribute(typeName, name)?.type ?? '')}"`).join('');
    const last = element.attributes[element.attributes.length - 1];
    const at = document.positionAt(last ? last.valueEnd + 1 : element.nameEnd);
    return [
      {
        title: `Add ${names.map((name) => `'${name}'`).join(', ')}`,
        edits: [{ place: 'document', range: { start: at, end: at }, newText: inserted }],
        preferred: true,
      },
    ];
  },
});
