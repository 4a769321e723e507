import * as v8 from 'node:v8';

/**
 * How much the old generation may grow past what the last full collection found live before the next one.
 * V8's default on a large machine is up to 300 %: every edit of a 15,000-line file leaves its previous
 * analysis as garbage there, and the server peaked past 500 MB after a burst of such edits. At 50 % it
 * stays near 300 MB for a few more full collections, which V8 marks concurrently.
 */
export const HEAP_GROWING_PERCENT = 50;

/**
 * Sets the language server process's heap growth, unless the command line or NODE_OPTIONS chose one.
 * It is no limit: the heap still grows to whatever a large workspace keeps live, it is only collected sooner.
 */
export function tuneServerHeap(
  execArgv: readonly string[] = process.execArgv,
  nodeOptions: string | undefined = process.env.NODE_OPTIONS,
): boolean {
  const chosen = (text: string) => /--heap[-_]growing[-_]percent/.test(text);
  if (execArgv.some(chosen) || chosen(nodeOptions ?? '')) return false;
  v8.setFlagsFromString(`--heap-growing-percent=${HEAP_GROWING_PERCENT}`);
  return true;
}
