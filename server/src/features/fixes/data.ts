import { DIAGNOSTICS, isRecord, isString } from '../../core/diagnostics';
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

const PROBLEM_CODES: ReadonlySet<string> = new Set(PROBLEM_CODE_LIST);

function isProblemCode(value: unknown): value is ProblemCode {
  return isString(value) && PROBLEM_CODES.has(value);
}

/** The check of each code's data: its module's (core/diagnostics/). */
const DATA_GUARDS: ReadonlyMap<ProblemCode, (value: unknown) => boolean> = new Map(
  DIAGNOSTICS.flatMap((definition) => (definition.isData ? [[definition.code, definition.isData] as const] : [])),
);

/** Whether a diagnostic's data (as a client sent it back) is a known code with the data that code names, or none. */
export function isDiagnosticData(value: unknown): value is DiagnosticData {
  if (!isRecord(value) || !isProblemCode(value.code)) return false;
  if (value.data === undefined) return true;
  return DATA_GUARDS.get(value.code)?.(value.data) ?? false;
}
