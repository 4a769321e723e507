import { Range } from './text';
import { displayRef, SourceRef } from './sources';

/** `hint` is shown faded in the editor (an unused parameter) and left out of the CLI's text report. */
export type Severity = 'error' | 'warning' | 'information' | 'hint';

/** What the ASAM schema check reports (core/schema/validate.ts). */
export const SCHEMA_PROBLEM_CODE_LIST = [
  'schema-unknown-element',
  'schema-unknown-attribute',
  'schema-missing-element',
  'schema-missing-attribute',
  'schema-order',
  'schema-cardinality',
  'schema-value',
  'schema-deprecated',
  'schema-version',
] as const;

export type SchemaProblemCode = (typeof SCHEMA_PROBLEM_CODE_LIST)[number];

export type ProblemCode =
  | 'xml'
  | 'io'
  | 'bad-package'
  | 'missing-file'
  | 'invalid-reference'
  | 'xosc-fallback'
  | 'unknown-group'
  | 'ambiguous-group'
  | 'duplicate-group'
  | 'unknown-key'
  | 'no-default'
  | 'unknown-parameter-attribute'
  | 'missing-attribute'
  | 'no-entity-ref'
  | 'reference-outside-group'
  | 'cycle'
  | 'undeclared-entity'
  | 'source-errors'
  | SchemaProblemCode
  | 'too-large'
  | 'too-deep'
  | 'undeclared-parameter'
  | 'unused-parameter'
  | 'duplicate-parameter'
  | 'expression-syntax'
  | 'type-mismatch'
  | 'division-by-zero'
  | 'nonstandard-expression'
  | 'catalog-directory'
  | 'unknown-catalog'
  | 'unknown-catalog-entry'
  | 'unknown-assigned-parameter'
  | 'unknown-storyboard-element'
  | 'ambiguous-reference'
  | 'undeclared-variable'
  | 'key-mixed-defaults'
  | 'parameter-conflict'
  | 'catalog-location-conflict'
  | 'renamed-reference'
  | 'simulator';

export interface RelatedProblemLocation {
  source: SourceRef;
  range: Range;
  message: string;
}

/** A problem found in a scenario, with its file, its precise range and, where one helps, a hint. */
export interface Problem {
  source: SourceRef;
  range: Range;
  severity: Severity;
  code: ProblemCode;
  message: string;
  hint?: string;
  related?: RelatedProblemLocation[];
  /** Data a quick fix needs (for example the suggested key), never shown. */
  data?: Record<string, string>;
}

export const ZERO_RANGE: Range = { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } };

/** `file:line:col: error: message (hint)`, as compilers print, with 1-based line and column. */
export function formatProblem(problem: Problem, base?: string): string {
  const where = `${displayRef(problem.source, base)}:${problem.range.start.line + 1}:${problem.range.start.character + 1}`;
  const hint = problem.hint ? `\n  hint: ${problem.hint}` : '';
  const related = (problem.related ?? [])
    .map((item) => `\n  ${displayRef(item.source, base)}:${item.range.start.line + 1}:${item.range.start.character + 1}: note: ${item.message}`)
    .join('');
  return `${where}: ${problem.severity === 'information' || problem.severity === 'hint' ? 'note' : problem.severity}: ${problem.message}${hint}${related}`;
}

export function hasErrors(problems: Problem[]): boolean {
  return problems.some((problem) => problem.severity === 'error');
}

export function problemKey(problem: Problem): string {
  const { start } = problem.range;
  return `${displayRef(problem.source, '/')}:${start.line}:${start.character}:${problem.code}:${problem.message}`;
}

/** Sorts problems by file and position and drops repeats (a source used twice reports once). */
export function uniqueProblems(problems: Problem[]): Problem[] {
  const seen = new Set<string>();
  const result: Problem[] = [];
  for (const problem of problems) {
    const key = problemKey(problem);
    if (seen.has(key)) continue;
    seen.add(key);
    result.push(problem);
  }
  return result;
}
