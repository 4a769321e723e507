/** Resolves once `condition` holds, checking every `intervalMs`; rejects after `timeoutMs`, naming `what`. */
export async function waitUntil(condition: () => boolean, what: string, timeoutMs: number, intervalMs = 20): Promise<void> {
  const deadline = Date.now() + timeoutMs;
  while (!condition()) {
    if (Date.now() > deadline) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((resolve) => setTimeout(resolve, intervalMs));
  }
}
