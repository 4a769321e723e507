import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRecord, isString } from './definition';
import { QC } from './qcRules';

/** An entity reference naming no declared entity. */
export const UNDECLARED_ENTITY = defineDiagnostic({
  code: 'undeclared-entity',
  rule: { description: 'An entity reference names a declared entity.', qcRule: QC.entityReferences },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-entity'] => isRecord(value) && isString(value.entity),
});
