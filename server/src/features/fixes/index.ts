import { ProblemFix } from './fix';
import { lenientValueFix } from './lenientValue';
import { noDefaultFix } from './noDefault';
import { schemaMissingAttributeFix } from './schemaMissingAttribute';
import { schemaMissingElementFix } from './schemaMissingElement';
import { schemaSuggestionFix } from './schemaSuggestion';
import { schemaUnknownElementFix } from './schemaUnknownElement';
import { undeclaredParameterFix } from './undeclaredParameter';
import { unknownGroupFix } from './unknownGroup';
import { unknownKeyFix } from './unknownKey';
import { unknownParameterAttributeFix } from './unknownParameterAttribute';
import { missingFileFix, xoscFallbackFix } from './xoscFallback';

export type { DiagnosticData } from './data';
export { diagnosticDataOf, isDiagnosticData } from './data';
export type { FixDocument, ProblemFix } from './fix';
export { missingKeysAction } from './missingKeys';

/** Every fix module; a code is handled by at most one of them. */
export const PROBLEM_FIXES: readonly ProblemFix[] = [
  unknownKeyFix,
  xoscFallbackFix,
  missingFileFix,
  unknownGroupFix,
  unknownParameterAttributeFix,
  noDefaultFix,
  undeclaredParameterFix,
  lenientValueFix,
  schemaSuggestionFix,
  schemaUnknownElementFix,
  schemaMissingAttributeFix,
  schemaMissingElementFix,
];
