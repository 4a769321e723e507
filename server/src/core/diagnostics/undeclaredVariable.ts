import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isOptionalString, isRecord, isString, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A variableRef (`written` as the file writes it) naming no variable of this file's VariableDeclarations. */
export function undeclaredVariableWording(written: string): ProblemWording<'undeclared-variable'> {
  return {
    severity: 'error',
    code: 'undeclared-variable',
    message: `variable '${written}' is not declared in the VariableDeclarations of this file`,
  };
}

/** A variable catalog entry `entry` uses, in the catalog: a note, since each scenario that references the entry declares it. */
export function catalogEntryVariableWording(name: string, entry: string | undefined): ProblemWording<'undeclared-variable'> {
  return {
    severity: 'information',
    code: 'undeclared-variable',
    message: `variable '${name}' is declared by the scenarios that reference catalog entry '${entry ?? ''}' (a catalog declares no variables); each of them must declare it, and one that does not gets an error at its CatalogReference`,
  };
}

/** A variable the catalog entry a CatalogReference names uses, which the referencing file does not declare. */
export function undeclaredEntryVariableWording(entry: string, name: string): ProblemWording<'undeclared-variable'> {
  return {
    severity: 'error',
    code: 'undeclared-variable',
    message: `catalog entry '${entry}' uses variable '${name}', which this file does not declare (a catalog declares no variables: the scenario that references the entry does)`,
    hint: `declare <VariableDeclaration name="${name}" variableType="..." value="..."/> in the VariableDeclarations of this file`,
  };
}

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
