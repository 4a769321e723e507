import { DIAGNOSTICS } from '../../core/diagnostics';
import { definitionFix } from './definitionFix';
import { ProblemFix } from './fix';
import { lenientValueFix } from './lenientValue';
import { schemaMissingAttributeFix } from './schemaMissingAttribute';
import { schemaMissingElementFix } from './schemaMissingElement';
import { schemaSuggestionFix } from './schemaSuggestion';
import { schemaUnknownElementFix } from './schemaUnknownElement';
import { undeclaredParameterFix } from './undeclaredParameter';

export type { DiagnosticData } from './data';
export { diagnosticDataOf, isDiagnosticData } from './data';
export type { FixDocument, ProblemFix } from './fix';
export { missingKeysAction } from './missingKeys';

/** Every fix: those of the diagnostics' modules (core/diagnostics/), then the fix modules here; a code is handled by at most one of them. */
export const PROBLEM_FIXES: readonly ProblemFix[] = [
  ...DIAGNOSTICS.filter((definition) => definition.fixes).map(definitionFix),
  undeclaredParameterFix,
  lenientValueFix,
  schemaSuggestionFix,
  schemaUnknownElementFix,
  schemaMissingAttributeFix,
  schemaMissingElementFix,
];
