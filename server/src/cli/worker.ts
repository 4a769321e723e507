import { parseArgs } from 'node:util';
import { loadQueueModule, QueuePackagesMissingError } from '../batch/queuePackages';
import { locateEsmini } from '../esmini/locate';
import { BatchUsageError, jobsOption, queueOption } from './batch';
import type { CliOutput } from './common';

/** `modular2simple worker --queue redis://HOST:PORT [--jobs N]`: runs the concrete scenarios batches put on the queue. */
export async function workerCommand(argv: string[], io: CliOutput): Promise<number> {
  try {
    let parsed;
    try {
      parsed = parseArgs({
        args: argv,
        options: {
          queue: { type: 'string' },
          jobs: { type: 'string' },
          esmini: { type: 'string' },
          'idle-exit': { type: 'string' },
          quiet: { type: 'boolean', short: 'q', default: false },
          help: { type: 'boolean', short: 'h', default: false },
        },
      });
    } catch (error) {
      throw new BatchUsageError((error as Error).message);
    }
    const { values } = parsed;
    if (values.help) {
      const { WORKER_HELP } = await import('./batch');
      io.out(WORKER_HELP);
      return 0;
    }
    const url = queueOption(values.queue);
    if (!url) throw new BatchUsageError('worker needs --queue redis://HOST:PORT');
    const jobs = jobsOption(values.jobs);
    const idleExit = values['idle-exit'] === undefined ? undefined : Number(values['idle-exit']);
    if (idleExit !== undefined && !(idleExit >= 0)) throw new BatchUsageError(`--idle-exit takes seconds, not '${values['idle-exit']}'`);
    const location = locateEsmini(values.esmini);
    if (!location.found) {
      io.err(`modular2simple: error: ${location.message}`);
      return 3;
    }
    let queueModules;
    try {
      queueModules = await loadQueueModule(() => Promise.all([import('../batch/worker'), import('../batch/queue')]));
    } catch (error) {
      if (!(error instanceof QueuePackagesMissingError)) throw error;
      io.err(`modular2simple: error: ${error.message}`);
      return 3;
    }
    const [{ runWorker }, { RedisUnreachableError }] = queueModules;
    try {
      return await runWorker(url, { jobs, esminiPath: location.program, idleExit, quiet: values.quiet, io });
    } catch (error) {
      if (error instanceof RedisUnreachableError) {
        io.err(`modular2simple: error: ${error.message}`);
        return 3;
      }
      throw error;
    }
  } catch (error) {
    if (error instanceof BatchUsageError) {
      io.err(`modular2simple: ${error.message}\nRun 'modular2simple --help' for usage.`);
      return 2;
    }
    throw error;
  }
}
