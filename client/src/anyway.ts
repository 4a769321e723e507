import type { ProblemSummary, RunEsminiResult } from '../../common/src/protocol';

/*
 * The words of *Write Anyway* and *Run Anyway* (SPEC 12: forced, whatever can be produced is written or
 * run, and what was wrong is listed). No VS Code here, so that the wording is tested without an editor.
 */

/** The last segment of a URI, decoded. */
export function fileName(uri: string): string {
  const last = uri.slice(uri.lastIndexOf('/') + 1);
  try {
    return decodeURIComponent(last);
  } catch {
    return last;
  }
}

function plural(count: number, word: string): string {
  return `${count} ${word}${count === 1 ? '' : 's'}`;
}

/** A problem in a few words, with the file and line it is at. */
export function problemPlace(problem: ProblemSummary): string {
  return `${problem.message} (${fileName(problem.uri)}:${problem.line + 1})`;
}

/** The first errors in a few words each, with the file and line they are at. */
export function namedErrors(problems: ProblemSummary[], shown = 3): string {
  const errors = problems.filter((problem) => problem.severity === 'error');
  const named = errors.slice(0, shown).map(problemPlace).join('; ');
  return errors.length > shown ? `${named}; and ${errors.length - shown} more` : named;
}

export function errorCount(problems: ProblemSummary[]): number {
  return problems.filter((problem) => problem.severity === 'error').length;
}

/** The question after a refused Flatten whose output a forced flatten can write. */
export function writeAnywayQuestion(action: string, problems: ProblemSummary[]): string {
  return `${action}: nothing was written, because of ${plural(errorCount(problems), 'error')}: ${namedErrors(problems)}. Write anyway, skipping the overrides that cannot apply (as --force does)?`;
}

/** What Flatten says once it wrote anyway. */
export function writtenAnywayNote(problems: ProblemSummary[]): string {
  return ` (written anyway despite ${plural(errorCount(problems), 'error')})`;
}

/** The question after a refused run that *Run Anyway* would start; undefined when forcing cannot help. */
export function runAnywayQuestion(result: RunEsminiResult): string | undefined {
  if (result.outcome !== 'not-flattened' || !result.forcible) return undefined;
  return `Run in esmini: ${result.message}: ${namedErrors(result.flattenProblems)}. Run anyway, as run --force does?`;
}

/** A diagnostic of the file as the Run CodeLenses read it: an error or not, where it came from, its code. */
export interface LensDiagnostic {
  isError: boolean;
  source?: string;
  code?: string | number | { value: string | number };
}

/** What a simulator profile reports (core/diagnostics/simulator*.ts): a run in esmini flattens for the standard alone and is never refused for these. */
const SIMULATOR_CODES: ReadonlySet<string> = new Set(['simulator', 'simulator-value']);

/** The file's errors that refuse a run in esmini until forced: not esmini's own messages from a run, nor what the selected simulator (CARLA, say) would refuse. */
export function runBlockingErrors(diagnostics: readonly LensDiagnostic[]): number {
  return diagnostics.filter((diagnostic) => {
    const code = typeof diagnostic.code === 'object' ? diagnostic.code.value : diagnostic.code;
    return diagnostic.isError && diagnostic.source !== 'esmini' && !SIMULATOR_CODES.has(String(code));
  }).length;
}

/** The titles of the Run CodeLenses of a file with `errors` errors of its own: *Run Anyway* joins *Run in esmini* when there are some. */
export function runLensTitles(errors: number): { title: string; force: boolean }[] {
  const lenses = [{ title: '▶ Run in esmini', force: false }];
  if (errors > 0) lenses.push({ title: `▶ Run Anyway (${plural(errors, 'error')})`, force: true });
  return lenses;
}
