import { ProblemDataByCode } from '../problems';
import { SchemaFactsByCode } from '../schema/facts';
import { indexFor, typeByElementName, typeOfElement } from '../schema/query';
import { elementSkeleton, placeholderValue, skeletonText } from '../schema/skeleton';
import { Range } from '../text';
import {
  childrenInsertion,
  defineDiagnostic,
  elementAtRange,
  indentOfLine,
  isOptionalString,
  isRecord,
  isString,
  isStringList,
  layoutOf,
  Words,
} from './definition';

/** Element names as the schema's messages write them: `<A>, <B>`. */
export function elementList(names: readonly string[]): string {
  return names.map((name) => `<${name}>`).join(', ');
}

export function schemaMissingElementWording({ parent, missing, before }: SchemaFactsByCode['schema-missing-element']): Words {
  return {
    message: `<${parent}> lacks the required element${missing.length > 1 ? 's' : ''} ${elementList(missing)}${before !== undefined ? ` before <${before}>` : ''}`,
  };
}
import { QC } from './qcRules';

/** Required elements the element lacks: each inserted as a minimal valid skeleton, before the element they must precede or at the end. */
export const SCHEMA_MISSING_ELEMENT = defineDiagnostic({
  code: 'schema-missing-element',
  rule: { description: 'Every element the ASAM schema requires is present.', qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-missing-element'] =>
    isRecord(value) && isStringList(value.missing) && isString(value.parent) && isOptionalString(value.insertAt),
  fixes: async ({ data, document, range, parsed, schemaVersion }) => {
    const tree = await parsed();
    const text = document.getText();
    const start = document.offsetAt(range.start);
    const index = indexFor(tree, schemaVersion);
    if (!index || !data || data.missing.length === 0) return [];
    const names = data.missing;
    const anchor = elementAtRange(tree, start);
    const parent = data.insertAt !== undefined ? anchor?.parent : anchor;
    if (!parent) return [];
    const parentType = typeOfElement(index, parent) ?? typeByElementName(index, parent.name);
    const { eol, unit } = layoutOf(text);
    // Each missing element as a minimal valid skeleton: its required attributes and children, recursively.
    const blocksAt = (indent: string, lineBreak: string) =>
      names.map((name) => {
        const particle = parentType ? index.childParticle(parentType, name, true) : undefined;
        const skeleton = particle ? elementSkeleton(index, particle) : { name, type: '', attributes: [], children: [] };
        return skeletonText(skeleton, { indent, unit, eol: lineBreak }, (declaration) => placeholderValue(index, declaration.type));
      });
    let edit: { range: Range; newText: string };
    if (data.insertAt !== undefined) {
      const offset = Number(data.insertAt);
      edit = {
        range: { start: document.positionAt(offset), end: document.positionAt(offset) },
        newText: blocksAt(indentOfLine(text, offset), eol)
          .map((block) => `${block}${eol}${indentOfLine(text, offset)}`)
          .join(''),
      };
    } else {
      const inserted = childrenInsertion(text, parent, blocksAt);
      if (!inserted) return [];
      edit = { range: { start: document.positionAt(inserted.start), end: document.positionAt(inserted.end) }, newText: inserted.newText };
    }
    return [{ title: `Insert ${names.map((name) => `<${name}>`).join(', ')}`, edits: [{ place: 'document', ...edit }], preferred: true }];
  },
});
