import type { BatchRow, Verdict } from './row';
export type { Verdict } from './row';

/** The measures of a row that a criterion may compare: the numeric columns of results.csv. */
export const CRITERION_METRICS = ['min_ttc_s', 'min_distance_m', 'end_time_s'] as const;
type Metric = (typeof CRITERION_METRICS)[number];
const OPERATORS = ['<=', '>=', '==', '!=', '<', '>'] as const;
type Operator = (typeof OPERATORS)[number];

/** A condition under which a run fails (`--fail-if`): a collision, or a measure compared with a number. */
export type Criterion =
  { kind: 'collision'; text: string } | { kind: 'compare'; text: string; metric: Metric; operator: Operator; value: number };

export class CriterionError extends Error {}

/** `batch`'s exit code when a run fails its --fail-if criteria: apart from 1 (the input has errors, nothing ran). */
export const CRITERIA_FAILED_EXIT = 5;

/** `collision` or `METRIC OP NUMBER` (`min_ttc_s < 1.5`); a CriterionError that says what is accepted otherwise. */
export function parseCriterion(text: string): Criterion {
  const trimmed = text.trim();
  if (trimmed === 'collision') return { kind: 'collision', text: trimmed };
  const match = /^([a-z_]+)\s*(<=|>=|==|!=|<|>)\s*(\S+)$/.exec(trimmed);
  const metric = match?.[1] as Metric | undefined;
  const value = Number(match?.[3]);
  if (!match || !CRITERION_METRICS.includes(metric as Metric) || !Number.isFinite(value) || match[3].trim() === '')
    throw new CriterionError(
      `--fail-if takes 'collision' or 'METRIC OP NUMBER' with METRIC one of ${CRITERION_METRICS.join(', ')} and OP one of ${OPERATORS.join(' ')} (such as 'min_ttc_s < 1.5'), not '${text}'`,
    );
  return { kind: 'compare', text: `${metric} ${match[2]} ${match[3]}`, metric: metric as Metric, operator: match[2] as Operator, value };
}

function holds(operator: Operator, left: number, right: number): boolean {
  switch (operator) {
    case '<':
      return left < right;
    case '<=':
      return left <= right;
    case '>':
      return left > right;
    case '>=':
      return left >= right;
    case '==':
      return left === right;
    case '!=':
      return left !== right;
  }
}

/** `pass`, `fail`, or empty where no verdict applies (no criteria given; a discarded combination, which did not run). */

/**
 * A row's verdict against the criteria, and why it fails: each criterion that holds (with the measured value), or a
 * run that did not complete (status error or timeout: its measures say nothing). A measure the run does not have
 * (no time to collision when the gap never closes) meets no comparison.
 */
export function judge(
  row: Pick<BatchRow, 'status' | 'collision' | Metric>,
  criteria: Criterion[],
): { verdict: Verdict; reasons: string[] } {
  if (criteria.length === 0 || row.status === 'discarded') return { verdict: '', reasons: [] };
  if (row.status === 'error' || row.status === 'timeout')
    return { verdict: 'fail', reasons: [`the run did not complete (status ${row.status})`] };
  const reasons: string[] = [];
  for (const criterion of criteria) {
    if (criterion.kind === 'collision') {
      if (row.collision) reasons.push('collision');
      continue;
    }
    const measured = row[criterion.metric];
    if (measured !== null && holds(criterion.operator, measured, criterion.value))
      reasons.push(`${criterion.text} (${criterion.metric} = ${Number(measured.toFixed(3))})`);
  }
  return { verdict: reasons.length > 0 ? 'fail' : 'pass', reasons };
}
