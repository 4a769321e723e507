import { loadQueueModule, QueuePackagesMissingError } from '../batch/queuePackages';
import { locateEsmini } from '../esmini/locate';
import { jobsOption, queueOption } from './batch';
import { CliCommand, CliOutput, parseCommandLine, UnavailableError, UsageError } from './common';

export const WORKER_HELP = `Run a batch's concrete scenarios from a queue (modular2simple worker --queue redis://HOST:PORT ...):
  --jobs N                  runs at a time (default: the number of cores)
  --esmini PATH             the esmini program, or its folder (default: esmini on PATH, else the one npm start built)
  --idle-exit S             stop after S seconds with nothing to do (default: run until interrupted)
  -q, --quiet               print errors only
  Exit codes: 0 stopped (idle, or interrupted), 2 usage, 3 no esmini, no bullmq and ioredis, Redis unreachable or gone while stopping,
  4 internal error.`;

/** `modular2simple worker --queue redis://HOST:PORT [--jobs N]`: runs the concrete scenarios batches put on the queue. */
async function workerCommand(argv: string[], io: CliOutput): Promise<number> {
  const { values, positionals } = parseCommandLine(argv, {
    queue: { type: 'string' },
    jobs: { type: 'string' },
    esmini: { type: 'string' },
    'idle-exit': { type: 'string' },
    quiet: { type: 'boolean', short: 'q', default: false },
  });
  if (positionals.length > 0) throw new UsageError(`worker takes options only, not '${positionals[0]}'`);
  const url = queueOption(values.queue);
  if (!url) throw new UsageError('worker needs --queue redis://HOST:PORT');
  const jobs = jobsOption(values.jobs);
  const idleExit = values['idle-exit'] === undefined ? undefined : Number(values['idle-exit']);
  if (idleExit !== undefined && !(idleExit >= 0)) throw new UsageError(`--idle-exit takes seconds, not '${values['idle-exit']}'`);
  const location = locateEsmini(values.esmini);
  if (!location.found) throw new UnavailableError(location.message);
  let queueModules;
  try {
    queueModules = await loadQueueModule(() => Promise.all([import('../batch/worker'), import('../batch/queue')]));
  } catch (error) {
    if (error instanceof QueuePackagesMissingError) throw new UnavailableError(error.message);
    throw error;
  }
  const [{ runWorker }, { RedisUnreachableError }] = queueModules;
  try {
    return await runWorker(url, { jobs, esminiPath: location.program, idleExit, quiet: values.quiet, io });
  } catch (error) {
    if (error instanceof RedisUnreachableError) throw new UnavailableError(error.message);
    throw error;
  }
}

export const WORKER: CliCommand = { help: WORKER_HELP, run: workerCommand };
