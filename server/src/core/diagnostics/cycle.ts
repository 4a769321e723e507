import { defineDiagnostic, ProblemWording } from './definition';

/** The message of a chain of references back to its start, each file as the report names it. */
export function cycleMessage(files: readonly string[]): string {
  return `reference cycle: ${files.join(' -> ')}`;
}

/** A related location's note: one step of the cycle, from a file to the file it references. */
export function cycleStepNote(from: string, to: string): string {
  return `${from} references ${to}`;
}

/** A reference that closes a chain of references back to a file on it. */
export function cycleWording(files: readonly string[]): ProblemWording<'cycle'> {
  return { severity: 'error', code: 'cycle', message: cycleMessage(files), hint: 'remove one reference of the cycle' };
}

/** Pack: a folder that holds itself through the folders it references (`folders` as the report names them). */
export function packageCycleWording(folders: readonly string[]): ProblemWording<'cycle'> {
  return { severity: 'error', code: 'cycle', message: `package cycle: ${folders.join(' -> ')}`, hint: undefined };
}

/** References that lead back to a file on their chain: the editor shows each step as a related location. */
export const CYCLE = defineDiagnostic({
  code: 'cycle',
  rule: { description: 'References do not form a cycle.' },
  severity: 'error',
});
