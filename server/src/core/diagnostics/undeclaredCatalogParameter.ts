import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRecord, isString } from './definition';
import { QC } from './qcRules';

/** A parameter a catalog entry uses without declaring it. Its quick fix is undeclared-parameter's (features/fixes/undeclaredParameter.ts). */
export const UNDECLARED_CATALOG_PARAMETER = defineDiagnostic({
  code: 'undeclared-catalog-parameter',
  rule: { description: 'A catalog entry declares every parameter it uses.', qcRule: QC.catalogParameters },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-catalog-parameter'] => isRecord(value) && isString(value.parameter),
});
