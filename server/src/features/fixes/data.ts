import { DefinedCode, DIAGNOSTICS, isOptionalString, isRecord, isString, isSuggestion } from '../../core/diagnostics';
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

/** One check per code that carries data and has no module in core/diagnostics/ (whose modules check their own). */
const OTHER_GUARDS: { [C in Exclude<ProblemCodeWithData, DefinedCode>]: (value: unknown) => value is ProblemDataByCode[C] } = {
  'undeclared-parameter': (value): value is ProblemDataByCode['undeclared-parameter'] => isRecord(value) && isString(value.parameter),
  'undeclared-catalog-parameter': (value): value is ProblemDataByCode['undeclared-catalog-parameter'] =>
    isRecord(value) && isString(value.parameter),
  'undeclared-entity': (value): value is ProblemDataByCode['undeclared-entity'] => isRecord(value) && isString(value.entity),
  'undeclared-variable': (value): value is ProblemDataByCode['undeclared-variable'] =>
    isRecord(value) && isString(value.variable) && isOptionalString(value.entry),
  'unknown-catalog-entry': isSuggestion,
  'unknown-assigned-parameter': isSuggestion,
  'unknown-storyboard-element': isSuggestion,
  'lenient-value': (value): value is ProblemDataByCode['lenient-value'] =>
    isSuggestion(value) || (isRecord(value) && isString(value.relatedReplacement)),
  'renamed-reference': isSuggestion,
};

const PROBLEM_CODES: ReadonlySet<string> = new Set(PROBLEM_CODE_LIST);

function isProblemCode(value: unknown): value is ProblemCode {
  return isString(value) && PROBLEM_CODES.has(value);
}

/** The check of each code's data: its module's, else the one here. */
const DATA_GUARDS: ReadonlyMap<ProblemCode, (value: unknown) => boolean> = new Map([
  ...Object.entries<(value: unknown) => boolean>(OTHER_GUARDS).map(([code, guard]) => [code as ProblemCode, guard] as const),
  ...DIAGNOSTICS.flatMap((definition) => (definition.isData ? [[definition.code, definition.isData] as const] : [])),
]);

/** Whether a diagnostic's data (as a client sent it back) is a known code with the data that code names, or none. */
export function isDiagnosticData(value: unknown): value is DiagnosticData {
  if (!isRecord(value) || !isProblemCode(value.code)) return false;
  if (value.data === undefined) return true;
  return DATA_GUARDS.get(value.code)?.(value.data) ?? false;
}
