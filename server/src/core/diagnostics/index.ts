import { ProblemCode } from '../problems';
import { RegisteredDiagnostic } from './definition';
import { AMBIGUOUS_GROUP } from './ambiguousGroup';
import { DUPLICATE_GROUP } from './duplicateGroup';
import { KEY_MIXED_DEFAULTS } from './keyMixedDefaults';
import { NO_ENTITY_REF } from './noEntityRef';
import { REFERENCE_OUTSIDE_GROUP } from './referenceOutsideGroup';
import { TOO_DEEP } from './tooDeep';
import { CYCLE } from './cycle';
import { DISTRIBUTION } from './distribution';
import { MISSING_FILE } from './missingFile';
import { NO_DEFAULT } from './noDefault';
import { SOURCE_ERRORS } from './sourceErrors';
import { UNKNOWN_DISTRIBUTION_PARAMETER } from './unknownDistributionParameter';
import { UNKNOWN_GROUP } from './unknownGroup';
import { UNKNOWN_KEY } from './unknownKey';
import { UNKNOWN_PARAMETER_ATTRIBUTE } from './unknownParameterAttribute';
import { SIMULATOR } from './simulator';
import { XOSC_FALLBACK } from './xoscFallback';
import { CATALOG_DIRECTORY } from './catalogDirectory';
import { CATALOG_LOCATION_CONFLICT } from './catalogLocationConflict';
import { PARAMETER_CONFLICT } from './parameterConflict';
import { TOO_LARGE } from './tooLarge';
import { ROAD_FILE } from './roadFile';
import { UNKNOWN_TRAFFIC_SIGNAL } from './unknownTrafficSignal';
import { UNKNOWN_TRAFFIC_SIGNAL_CONTROLLER } from './unknownTrafficSignalController';
import { NO_ACTOR } from './noActor';
import { NEGATIVE_TRANSITION_TIME } from './negativeTransitionTime';
import { NON_POSITIVE_PHASE_DURATION } from './nonPositivePhaseDuration';
import { OUT_OF_RANGE } from './outOfRange';
import { XML } from './xml';
import { IO } from './io';
import { BAD_PACKAGE } from './badPackage';
import { INVALID_REFERENCE } from './invalidReference';
import { MISSING_ATTRIBUTE } from './missingAttribute';
import { FILE_PATH } from './filePath';
import { SCHEMA_UNKNOWN_ELEMENT } from './schemaUnknownElement';
import { SCHEMA_UNKNOWN_ATTRIBUTE } from './schemaUnknownAttribute';
import { SCHEMA_MISSING_ELEMENT } from './schemaMissingElement';
import { SCHEMA_MISSING_ATTRIBUTE } from './schemaMissingAttribute';
import { SCHEMA_ORDER } from './schemaOrder';
import { SCHEMA_CARDINALITY } from './schemaCardinality';
import { SCHEMA_VALUE } from './schemaValue';
import { SCHEMA_DEPRECATED } from './schemaDeprecated';
import { SCHEMA_VERSION } from './schemaVersion';
import { UNDECLARED_ENTITY } from './undeclaredEntity';
import { UNDECLARED_PARAMETER } from './undeclaredParameter';
import { UNUSED_PARAMETER } from './unusedParameter';
import { DUPLICATE_PARAMETER } from './duplicateParameter';
import { EXPRESSION_SYNTAX } from './expressionSyntax';
import { TYPE_MISMATCH } from './typeMismatch';
import { DIVISION_BY_ZERO } from './divisionByZero';
import { NONSTANDARD_EXPRESSION } from './nonstandardExpression';
import { UNKNOWN_CATALOG } from './unknownCatalog';
import { UNKNOWN_CATALOG_ENTRY } from './unknownCatalogEntry';
import { UNKNOWN_ASSIGNED_PARAMETER } from './unknownAssignedParameter';
import { UNKNOWN_STORYBOARD_ELEMENT } from './unknownStoryboardElement';
import { AMBIGUOUS_REFERENCE } from './ambiguousReference';
import { UNDECLARED_VARIABLE } from './undeclaredVariable';
import { UNDECLARED_CATALOG_PARAMETER } from './undeclaredCatalogParameter';
import { DUPLICATE_NAME } from './duplicateName';
import { DUPLICATE_CATALOG_ENTRY } from './duplicateCatalogEntry';
import { VALUE_CONSTRAINT } from './valueConstraint';
import { RENAMED_REFERENCE } from './renamedReference';
import { LENIENT_VALUE } from './lenientValue';
import { SIMULATOR_VALUE } from './simulatorValue';
import { OVERFLOW } from './overflow';

export * from './definition';
export { QC, QC_RULE_DESCRIPTIONS } from './qcRules';
export type { QcRuleUid, Rule } from './qcRules';

/**
 * Every diagnostic, each in its own module (server/src/core/diagnostics/<code>.ts): one entry per code of
 * problems.ts (core/rules.ts does not compile while a code has none).
 */
export const DIAGNOSTICS = [
  MISSING_FILE,
  XOSC_FALLBACK,
  UNKNOWN_GROUP,
  UNKNOWN_KEY,
  NO_DEFAULT,
  UNKNOWN_PARAMETER_ATTRIBUTE,
  DISTRIBUTION,
  UNKNOWN_DISTRIBUTION_PARAMETER,
  CYCLE,
  SOURCE_ERRORS,
  SIMULATOR,
  AMBIGUOUS_GROUP,
  DUPLICATE_GROUP,
  KEY_MIXED_DEFAULTS,
  NO_ENTITY_REF,
  REFERENCE_OUTSIDE_GROUP,
  TOO_DEEP,
  TOO_LARGE,
  CATALOG_DIRECTORY,
  CATALOG_LOCATION_CONFLICT,
  PARAMETER_CONFLICT,
  ROAD_FILE,
  UNKNOWN_TRAFFIC_SIGNAL,
  UNKNOWN_TRAFFIC_SIGNAL_CONTROLLER,
  NO_ACTOR,
  NEGATIVE_TRANSITION_TIME,
  NON_POSITIVE_PHASE_DURATION,
  OUT_OF_RANGE,
  XML,
  IO,
  BAD_PACKAGE,
  INVALID_REFERENCE,
  MISSING_ATTRIBUTE,
  FILE_PATH,
  SCHEMA_UNKNOWN_ELEMENT,
  SCHEMA_UNKNOWN_ATTRIBUTE,
  SCHEMA_MISSING_ELEMENT,
  SCHEMA_MISSING_ATTRIBUTE,
  SCHEMA_ORDER,
  SCHEMA_CARDINALITY,
  SCHEMA_VALUE,
  SCHEMA_DEPRECATED,
  SCHEMA_VERSION,
  UNDECLARED_ENTITY,
  UNDECLARED_PARAMETER,
  UNUSED_PARAMETER,
  DUPLICATE_PARAMETER,
  EXPRESSION_SYNTAX,
  TYPE_MISMATCH,
  DIVISION_BY_ZERO,
  NONSTANDARD_EXPRESSION,
  UNKNOWN_CATALOG,
  UNKNOWN_CATALOG_ENTRY,
  UNKNOWN_ASSIGNED_PARAMETER,
  UNKNOWN_STORYBOARD_ELEMENT,
  AMBIGUOUS_REFERENCE,
  UNDECLARED_VARIABLE,
  UNDECLARED_CATALOG_PARAMETER,
  DUPLICATE_NAME,
  DUPLICATE_CATALOG_ENTRY,
  VALUE_CONSTRAINT,
  RENAMED_REFERENCE,
  LENIENT_VALUE,
  SIMULATOR_VALUE,
  OVERFLOW,
] as const;

/** The codes whose diagnostic has its own module. */
export type DefinedCode = (typeof DIAGNOSTICS)[number]['code'];

const BY_CODE: ReadonlyMap<ProblemCode, RegisteredDiagnostic> = new Map(DIAGNOSTICS.map((definition) => [definition.code, definition]));

/** The module of a code, where it has one. */
export function diagnosticOf(code: ProblemCode): RegisteredDiagnostic | undefined {
  return BY_CODE.get(code);
}

/** The codes `flatten --force` skips. */
export const SKIPPED_BY_FORCE: ReadonlySet<ProblemCode> = new Set(
  DIAGNOSTICS.filter((definition) => definition.skippedByForce).map((definition) => definition.code),
);
