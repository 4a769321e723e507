/**
 * How long a test waits for the language server's answer or notification before failing: a stall, not
 * slowness, must fail the test, and on a 2-core machine at load 25 a 1-second analysis takes half a minute.
 */
export const SERVER_WAIT_MS = 60_000;

/** Resolves once `condition` holds, checking every `intervalMs`; rejects after `timeoutMs`, naming `what`. */
export async function waitUntil(condition: () => boolean, what: string, timeoutMs: number, intervalMs = 20): Promise<void> {
  const deadline = Date.now() + timeoutMs;
  while (!condition()) {
    if (Date.now() > deadline) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((resolve) => setTimeout(resolve, intervalMs));
  }
}
