import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, didYouMean, isRecord, isString, ProblemWording } from './definition';
import { QC } from './qcRules';

/** An entity reference whose value (`written` as the file writes it) names no entity of <Entities>. An error by SPEC 12 and ASAM QC alike: esmini stops at it ("Failed to find object"). */
export function undeclaredEntityWording(
  value: string,
  written: string,
  suggestion: string | undefined,
): ProblemWording<'undeclared-entity'> {
  return {
    severity: 'error',
    code: 'undeclared-entity',
    message: `entity '${value}'${value !== written ? ` (the value of ${written})` : ''} is not declared in <Entities>`,
    hint: didYouMean(suggestion) ?? `declare a ScenarioObject named '${value}'`,
  };
}

/** An entity the imported group `group` uses, which the main file does not declare. */
export function undeclaredImportedEntityWording(group: string, entity: string): ProblemWording<'undeclared-entity'> {
  return {
    severity: 'error',
    code: 'undeclared-entity',
    message: `the imported group '${group}' uses entity '${entity}', which this file does not declare in <Entities>`,
    hint: `declare a ScenarioObject named '${entity}', or override the key that sets it (for example 'entityRef')`,
  };
}

/** An entity reference naming no declared entity. */
export const UNDECLARED_ENTITY = defineDiagnostic({
  code: 'undeclared-entity',
  rule: { description: 'An entity reference names a declared entity.', qcRule: QC.entityReferences },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-entity'] => isRecord(value) && isString(value.entity),
});
