import { PROBLEM_CODE_LIST, Problem, ProblemCode, ProblemCodeWithData, ProblemDataByCode } from '../../core/problems';

/**
 * What a diagnostic carries for its quick fixes: its problem code and the data that code names.
 * A discriminated union by `code`; a client sends it back as it likes, so it is read with `isDiagnosticData`.
 */
export type DiagnosticData = {
  [C in ProblemCode]: C extends ProblemCodeWithData ? { code: C; data?: ProblemDataByCode[C] } : { code: C };
}[ProblemCode];

/** The diagnostic data of one code. */
export type DiagnosticDataOf<C extends ProblemCode> = Extract<DiagnosticData, { code: C }>;

/** The diagnostic's data of a problem (the producers attach the shape its code names; `isDiagnosticData` checks it on the way back). */
export function diagnosticDataOf(problem: Problem): { code: ProblemCode; data?: Problem['data'] } {
  return problem.data ? { code: problem.code, data: problem.data } : { code: problem.code };
}

function isRecord(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

function isString(value: unknown): value is string {
  return typeof value === 'string';
}

function isOptionalString(value: unknown): value is string | undefined {
  return value === undefined || isString(value);
}

function isStringList(value: unknown): value is string[] {
  return Array.isArray(value) && value.every(isString);
}

function isSuggestion(value: unknown): value is ProblemDataByCode['schema-value'] {
  return isRecord(value) && isString(value.suggestion);
}

function isMissingAttributes(value: unknown): value is ProblemDataByCode['schema-missing-attribute'] {
  return isRecord(value) && isStringList(value.missing);
}

/** One check per code that carries data: that the value has the shape `ProblemDataByCode` names. */
const DATA_GUARDS: { [C in ProblemCodeWithData]: (value: unknown) => value is ProblemDataByCode[C] } = {
  'unknown-key': (value): value is ProblemDataByCode['unknown-key'] =>
    isSuggestion(value) || (isRecord(value) && isString(value.relatedReplacement)),
  'xosc-fallback': (value): value is ProblemDataByCode['xosc-fallback'] => isRecord(value) && isString(value.replacement),
  'missing-file': isSuggestion,
  'unknown-group': (value): value is ProblemDataByCode['unknown-group'] =>
    isRecord(value) && isOptionalString(value.suggestion) && isStringList(value.groups),
  'unknown-parameter-attribute': isSuggestion,
  'undeclared-parameter': (value): value is ProblemDataByCode['undeclared-parameter'] => isRecord(value) && isString(value.parameter),
  'undeclared-catalog-parameter': (value): value is ProblemDataByCode['undeclared-catalog-parameter'] =>
    isRecord(value) && isString(value.parameter),
  'undeclared-entity': (value): value is ProblemDataByCode['undeclared-entity'] => isRecord(value) && isString(value.entity),
  'undeclared-variable': (value): value is ProblemDataByCode['undeclared-variable'] =>
    isRecord(value) && isString(value.variable) && isOptionalString(value.entry),
  'unknown-catalog-entry': isSuggestion,
  'unknown-assigned-parameter': isSuggestion,
  'unknown-storyboard-element': isSuggestion,
  'unknown-distribution-parameter': isSuggestion,
  'lenient-value': (value): value is ProblemDataByCode['lenient-value'] =>
    isSuggestion(value) || (isRecord(value) && isString(value.relatedReplacement)),
  'renamed-reference': isSuggestion,
  'catalog-location-conflict': (value): value is ProblemDataByCode['catalog-location-conflict'] => isRecord(value) && isString(value.key),
  'schema-unknown-element': isSuggestion,
  'schema-unknown-attribute': isSuggestion,
  'schema-value': isSuggestion,
  'schema-deprecated': isSuggestion,
  'schema-version': isSuggestion,
  'schema-missing-attribute': isMissingAttributes,
  'schema-missing-element': (value): value is ProblemDataByCode['schema-missing-element'] =>
    isRecord(value) && isStringList(value.missing) && isString(value.parent) && isOptionalString(value.insertAt),
};

const PROBLEM_CODES: ReadonlySet<string> = new Set(PROBLEM_CODE_LIST);

function isProblemCode(value: unknown): value is ProblemCode {
  return isString(value) && PROBLEM_CODES.has(value);
}

function carriesData(code: ProblemCode): code is ProblemCodeWithData {
  return Object.prototype.hasOwnProperty.call(DATA_GUARDS, code);
}

/** Whether a diagnostic's data (as a client sent it back) is a known code with the data that code names, or none. */
export function isDiagnosticData(value: unknown): value is DiagnosticData {
  if (!isRecord(value) || !isProblemCode(value.code)) return false;
  if (value.data === undefined) return true;
  return carriesData(value.code) && DATA_GUARDS[value.code](value.data);
}
