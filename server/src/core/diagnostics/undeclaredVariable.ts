import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isOptionalString, isRecord, isString } from './definition';
import { QC } from './qcRules';

/** A variableRef naming no declared variable; in a catalog entry, noted for each scenario that references the entry (features/diagnostics.ts adds them). */
export const UNDECLARED_VARIABLE = defineDiagnostic({
  code: 'undeclared-variable',
  rule: {
    description:
      'A variableRef names a declared variable (or a parameter, as ASAM QC accepts); a variable of a catalog entry is declared by each scenario that references the entry.',
    qcRule: QC.variableReference,
  },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-variable'] =>
    isRecord(value) && isString(value.variable) && isOptionalString(value.entry),
});
