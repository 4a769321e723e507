import { SchemaFactsByCode } from '../schema/facts';
import { defineDiagnostic, Words } from './definition';
import { QC } from './qcRules';

export function schemaCardinalityWording({ element, parent, max }: SchemaFactsByCode['schema-cardinality']): Words {
  return { message: `too many <${element}> in <${parent}>: at most ${max}` };
}

export const SCHEMA_CARDINALITY = defineDiagnostic({
  code: 'schema-cardinality',
  rule: { description: 'Child elements occur as often as the ASAM schema allows.', qcRule: QC.validSchema },
  severity: 'error',
});
