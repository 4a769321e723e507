import { Range } from './text';
import { displayRef, SourceRef } from './sources';
import { coreMemo } from './memos';

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

/** Every problem code; the type guard of a fix's data checks a code a client sends back against it. */
export const PROBLEM_CODE_LIST = [
  'xml',
  'io',
  'bad-package',
  'missing-file',
  'invalid-reference',
  'xosc-fallback',
  'unknown-group',
  'ambiguous-group',
  'duplicate-group',
  'unknown-key',
  'no-default',
  'unknown-parameter-attribute',
  'missing-attribute',
  'no-entity-ref',
  'reference-outside-group',
  'cycle',
  'undeclared-entity',
  'source-errors',
  ...SCHEMA_PROBLEM_CODE_LIST,
  'too-large',
  'too-deep',
  'undeclared-parameter',
  'unused-parameter',
  'duplicate-parameter',
  'expression-syntax',
  'type-mismatch',
  'division-by-zero',
  'nonstandard-expression',
  'lenient-value',
  'simulator-value',
  'overflow',
  'catalog-directory',
  'unknown-catalog',
  'unknown-catalog-entry',
  'unknown-assigned-parameter',
  'unknown-storyboard-element',
  'ambiguous-reference',
  'undeclared-variable',
  'undeclared-catalog-parameter',
  'duplicate-name',
  'duplicate-catalog-entry',
  'value-constraint',
  'key-mixed-defaults',
  'parameter-conflict',
  'catalog-location-conflict',
  'renamed-reference',
  'simulator',
  'file-path',
  'road-file',
  'unknown-traffic-signal',
  'unknown-traffic-signal-controller',
  'no-actor',
  'negative-transition-time',
  'non-positive-phase-duration',
  'out-of-range',
  'distribution',
  'unknown-distribution-parameter',
] as const;

export type ProblemCode = (typeof PROBLEM_CODE_LIST)[number];

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
  /** Data a quick fix needs (for example the suggested key), never shown; its shape is the one `ProblemDataByCode` names for the code. */
  data?: ProblemData;
  /** What the problem is about, where the rule it breaks depends on that (core/rules.ts `ruleOf`); the schema's findings name it. */
  subject?: ProblemSubject;
  /** Of a `source-errors` problem: the error its chain of first errors ends in, for whoever must tell what stands behind it. */
  cause?: ProblemCause;
}

/** The first error of a referenced file, followed through the files it references in turn, and how many errors its own file has. */
export interface ProblemCause {
  code: ProblemCode;
  among: number;
}

/** The element (and attribute) a problem is about, by name. */
export interface ProblemSubject {
  element: string;
  attribute?: string;
  /** Set when the element is the document's root. */
  root?: true;
  /** Of the children a schema-missing-element problem names, those the element has none of (the others stand out of order). */
  absent?: string[];
  /** Of an expression-syntax problem: the operator, function or character the standard's expressions do not have. */
  token?: string;
  /** Of a type-mismatch problem: a catalog entry's parameter declared with an empty value, which gives it no default. */
  noCatalogDefault?: true;
}

/** The name or value to write instead of the one written. */
export interface SuggestionData {
  suggestion: string;
}

/** Replaces the text at the problem's first related location: the mistake lives in the file it points to. */
export interface RelatedReplacementData {
  relatedReplacement: string;
}

/** The flattened package to name instead of the `.xosc` that does not exist. */
export interface FallbackData {
  replacement: string;
}

/** The closest group name, and every group name of the referenced file. */
export interface UnknownGroupData {
  suggestion?: string;
  groups: string[];
}

export interface UndeclaredParameterData {
  parameter: string;
}

/** A variable a catalog entry uses: the scenarios that reference the entry declare it. */
export interface UndeclaredVariableData {
  variable: string;
  entry?: string;
}

export interface UndeclaredEntityData {
  entity: string;
}

/** One conflict is reported per catalog kind: the key says which. */
export interface LocationConflictData {
  key: string;
}

export interface MissingAttributesData {
  missing: string[];
}

/** The missing children of `parent`, inserted before the offset `insertAt` (decimal, in the checked text) where one is given. */
export interface MissingElementsData {
  missing: string[];
  parent: string;
  insertAt?: string;
}

/**
 * What answers a simulator finding: the text to write at its range where one edit does it, a catalog file
 * to rename (absolute paths), whether the export for CARLA maps it, and the actor an Actors lacks.
 */
export interface SimulatorFixData {
  suggestion?: string;
  rename?: { from: string; to: string };
  exportMaps?: boolean;
  /** The entity an EntityRef added to the Actors the problem stands on names (esmini takes actors only from EntityRefs). */
  actor?: string;
  /** The Orientation the problem stands on is moved before its InRoutePosition (esmini reads a RoutePosition's children in order). */
  orientationFirst?: boolean;
  /** The ScenarioObject whose Vehicle gets ScenarioRunner's ego Property (the one Export for CARLA marks). */
  ego?: string;
  /** A SimulationTimeCondition esmini never fires: 'edge' writes its Condition's conditionEdge none; 'after-zero' its rule greaterThan (and the edge none). */
  simulationTimeFix?: 'edge' | 'after-zero';
}

/** The data each problem code carries (where it carries any). */
export interface ProblemDataByCode {
  'unknown-key': SuggestionData | RelatedReplacementData;
  'xosc-fallback': FallbackData;
  'missing-file': SuggestionData;
  'unknown-group': UnknownGroupData;
  'unknown-parameter-attribute': SuggestionData;
  'undeclared-parameter': UndeclaredParameterData;
  'undeclared-catalog-parameter': UndeclaredParameterData;
  'undeclared-entity': UndeclaredEntityData;
  'undeclared-variable': UndeclaredVariableData;
  'unknown-catalog-entry': SuggestionData;
  'unknown-assigned-parameter': SuggestionData;
  'unknown-storyboard-element': SuggestionData;
  'unknown-distribution-parameter': SuggestionData;
  'lenient-value': SuggestionData | RelatedReplacementData;
  'renamed-reference': SuggestionData;
  'catalog-location-conflict': LocationConflictData;
  'schema-unknown-element': SuggestionData;
  'schema-unknown-attribute': SuggestionData;
  'schema-value': SuggestionData;
  'schema-deprecated': SuggestionData;
  'schema-version': SuggestionData;
  'schema-missing-attribute': MissingAttributesData;
  'schema-missing-element': MissingElementsData;
  simulator: SimulatorFixData;
}

export type ProblemCodeWithData = keyof ProblemDataByCode;

/**
 * The data of a schema finding as the schema check holds it: any schema code's shape, with `insertAt`
 * readable on all of them, since a re-check shifts or drops it without looking at the code.
 */
export type SchemaFindingData = Partial<SuggestionData & MissingElementsData>;

export type ProblemData = ProblemDataByCode[ProblemCodeWithData] | SchemaFindingData;

/** The problem's data when it has `code` (the producers attach the shape its code names). */
export function problemData<C extends ProblemCodeWithData>(problem: Problem, code: C): ProblemDataByCode[C] | undefined {
  return problem.code === code ? (problem.data as ProblemDataByCode[C] | undefined) : undefined;
}

export const ZERO_RANGE: Range = { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } };

/** `file:line:col: error: message (hint)`, as compilers print, with 1-based line and column; files relative to `base` when given. */
export function formatProblem(problem: Problem, base?: string): string {
  const where = `${displayRef(problem.source, base)}:${problem.range.start.line + 1}:${problem.range.start.character + 1}`;
  const hint = problem.hint ? `\n  hint: ${problem.hint}` : '';
  const related = (problem.related ?? [])
    .map(
      (item) =>
        `\n  ${displayRef(item.source, base)}:${item.range.start.line + 1}:${item.range.start.character + 1}: note: ${item.message}`,
    )
    .join('');
  return `${where}: ${problem.severity === 'information' || problem.severity === 'hint' ? 'note' : problem.severity}: ${problem.message}${hint}${related}`;
}

export function hasErrors(problems: Problem[]): boolean {
  return problems.some((problem) => problem.severity === 'error');
}

// Remembered per ref, as refIds are: the problems of one file share its ref, and a file can have thousands.
const refKeys = coreMemo<SourceRef, string>('problemRefKeys');

function refKey(ref: SourceRef): string {
  let key = refKeys.get(ref);
  if (key === undefined) {
    key = displayRef(ref, '/');
    refKeys.set(ref, key);
  }
  return key;
}

export function problemKey(problem: Problem): string {
  const { start } = problem.range;
  return `${refKey(problem.source)}:${start.line}:${start.character}:${problem.code}:${problem.message}`;
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
