/**
 * The Redis queue's client libraries, bullmq and ioredis (about 20 packages, one with a native binary), serve only
 * `batch --queue` and `worker`: they are optional peer dependencies, loaded only there and never bundled
 * (scripts/build.mjs), so a CLI or an extension without them runs everything else.
 */
export const QUEUE_PACKAGES = ['bullmq', 'ioredis'] as const;

export class QueuePackagesMissingError extends Error {}

function missingQueuePackage(error: unknown): string | undefined {
  const { code, message } = (error ?? {}) as { code?: unknown; message?: unknown };
  if (code !== 'MODULE_NOT_FOUND' && code !== 'ERR_MODULE_NOT_FOUND') return undefined;
  return QUEUE_PACKAGES.find((name) => typeof message === 'string' && message.includes(`'${name}'`));
}

/** Loads a module that imports the queue's libraries; their absence is a QueuePackagesMissingError that says what to install. */
export async function loadQueueModule<T>(load: () => Promise<T>): Promise<T> {
  try {
    return await load();
  } catch (error) {
    const missing = missingQueuePackage(error);
    if (missing === undefined) throw error;
    throw new QueuePackagesMissingError(
      `--queue needs the npm packages ${QUEUE_PACKAGES.join(' and ')}, and ${missing} is not installed: ` +
        `run 'npm install ${QUEUE_PACKAGES.map((name) => `${name}@6`).join(' ')}' in the folder that holds modular2simple (or one above it)`,
    );
  }
}
