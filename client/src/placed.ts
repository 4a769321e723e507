import type { ProblemSummary } from '../../common/src/protocol';
import { fileName } from './anyway';

/*
 * Messages about a scenario placed on its source lines: the loss report of *Export for CARLA…* and what
 * ScenarioRunner said in *Check in CARLA ScenarioRunner*. No VS Code here, so that it is tested without an editor.
 */

export interface PlacedMessage {
  /** Zero-based, as LSP. */
  start: { line: number; character: number };
  /** Where it ends; undefined: to the end of the start's line. */
  end: { line: number; character: number } | undefined;
  severity: ProblemSummary['severity'];
  message: string;
  code: string | undefined;
}

/** The problems grouped by the file they are in (a simple scenario's losses land in the simple scenario), in the order given. */
export function placedByUri(problems: readonly ProblemSummary[]): Map<string, PlacedMessage[]> {
  const byUri = new Map<string, PlacedMessage[]>();
  for (const problem of problems) {
    const list = byUri.get(problem.uri) ?? [];
    list.push({
      start: { line: problem.line, character: problem.character },
      end: problem.end,
      severity: problem.severity,
      message: problem.hint ? `${problem.message} (${problem.hint})` : problem.message,
      code: problem.code,
    });
    byUri.set(problem.uri, list);
  }
  return byUri;
}

/** One line for the Output channel: `file:line:column: severity: message`. */
export function problemLine(problem: ProblemSummary): string {
  return `${fileName(problem.uri)}:${problem.line + 1}:${problem.character + 1}: ${problem.severity}: ${problem.message}${problem.hint ? ` (${problem.hint})` : ''}  [${problem.uri}]`;
}

/** What an export wrote or refused, in a sentence: how many losses and where the first is. */
export function exportSummary(written: string | null, problems: readonly ProblemSummary[]): string {
  const losses = problems.filter((problem) => problem.code?.startsWith('carla-export-'));
  const files = new Set(losses.map((problem) => fileName(problem.uri)));
  const count = `${losses.length} loss${losses.length === 1 ? '' : 'es'}`;
  const where = losses.length === 0 ? '' : ` in ${[...files].join(', ')} (see Problems)`;
  return written === null ? `refused; ${count}${where}` : `wrote ${fileName(written)}; ${count}${where}`;
}
