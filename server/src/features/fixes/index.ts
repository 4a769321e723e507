import { DIAGNOSTICS } from '../../core/diagnostics';
import { definitionFix } from './definitionFix';
import { ProblemFix } from './fix';

export type { DiagnosticData } from './data';
export { diagnosticDataOf, isDiagnosticData } from './data';
export type { FixDocument, ProblemFix } from './fix';
export { missingKeysAction } from './missingKeys';

/** Every fix: those of the diagnostics' modules (core/diagnostics/), each made code actions by one adapter. */
export const PROBLEM_FIXES: readonly ProblemFix[] = DIAGNOSTICS.filter((definition) => definition.fixes).map(definitionFix);
