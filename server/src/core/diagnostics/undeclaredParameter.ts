import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRecord, isString, ProblemWording } from './definition';

/** The hint of an undeclared parameter: a declaration to write, and where. */
export function declareParameterHint(name: string, where: string): string {
  return `declare <ParameterDeclaration name="${name}" parameterType="..." value="..."/> in the ParameterDeclarations of ${where}`;
}

/**
 * A `$name` no declaration in scope resolves; or (`entry`) a parameter the catalog entry a CatalogReference
 * names uses, which neither the entry nor the referencing file declares.
 */
export function undeclaredParameterWording(name: string, entry?: string): ProblemWording<'undeclared-parameter'> {
  return entry === undefined
    ? {
        severity: 'error',
        code: 'undeclared-parameter',
        message: `parameter '${name}' is not declared in this scope`,
        hint: declareParameterHint(name, 'the file or of an enclosing element'),
      }
    : {
        severity: 'error',
        code: 'undeclared-parameter',
        message: `catalog entry '${entry}' uses parameter '${name}', which neither the entry nor this file declares`,
        hint: `declare '${name}' in this file, or in the entry's ParameterDeclarations`,
      };
}

/** A `$name` naming no declared parameter. Its quick fix (declare it, with the value of a source's declaration) needs the file's analysis: features/fixes/undeclaredParameter.ts. */
export const UNDECLARED_PARAMETER = defineDiagnostic({
  code: 'undeclared-parameter',
  rule: { description: 'A $name names a declared parameter.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-parameter'] => isRecord(value) && isString(value.parameter),
});
