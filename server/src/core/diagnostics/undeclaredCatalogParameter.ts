import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRecord, isString, ProblemWording } from './definition';
import { declareParameterFixes, declareParameterHint } from './undeclaredParameter';
import { QC } from './qcRules';

/** A parameter a catalog entry uses without declaring it: a warning where esmini runs it (taking the value from the referencing scenario, SPEC 12). */
export function undeclaredCatalogParameterWording(name: string, esmini: boolean): ProblemWording<'undeclared-catalog-parameter'> {
  return {
    severity: esmini ? 'warning' : 'error',
    code: 'undeclared-catalog-parameter',
    message: `parameter '${name}' is not declared in this catalog entry: the standard wants an entry to declare every parameter it uses (esmini takes an undeclared one from the scenario that references the entry)`,
    hint: declareParameterHint(name, 'the entry'),
  };
}

/** A parameter a catalog entry uses without declaring it. Its quick fix is undeclared-parameter's: declare it in the entry. */
export const UNDECLARED_CATALOG_PARAMETER = defineDiagnostic({
  code: 'undeclared-catalog-parameter',
  rule: { description: 'A catalog entry declares every parameter it uses.', qcRule: QC.catalogParameters },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-catalog-parameter'] => isRecord(value) && isString(value.parameter),
  fixes: declareParameterFixes,
});
