import { SchemaFactsByCode } from '../schema/facts';
import { defineDiagnostic, Words } from './definition';
import { QC } from './qcRules';
import { elementList } from './schemaMissingElement';

export function schemaOrderWording(facts: SchemaFactsByCode['schema-order']): Words {
  const { element, parent } = facts;
  const what =
    facts.kind === 'before'
      ? `${elementList(facts.before)} must come before it`
      : facts.expected.length > 0
        ? `expected ${elementList(facts.expected)} here`
        : 'nothing more may follow here';
  return { message: `<${element}> is out of order in <${parent}>: ${what}` };
}

export const SCHEMA_ORDER = defineDiagnostic({
  code: 'schema-order',
  rule: { description: 'Child elements stand in the order the ASAM schema gives.', qcRule: QC.validSchema },
  severity: 'error',
});
