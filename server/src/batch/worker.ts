import { setMaxListeners } from 'node:events';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Job, Worker } from 'bullmq';
import { CatalogLoader } from '../core/semantics/catalogs';
import { nodeFileSystem, ScenarioStore } from '../core/sources';
import { rebasedConcreteText } from '../core/variations';
import { controllerFilesFrom } from '../esmini/controllerFiles';
import { withoutRunFolder } from '../esmini/messages';
import { makeRunFolder, removeRunFolderAt, sharedRunsFolder } from '../esmini/process';
import { connect, connectionOf, fileKey, LOCK_DURATION_MS, QUEUE_NAME, resultsKey, RunJob, STALLED_INTERVAL_MS } from './queue';
import { BatchOutput, runLine } from './progress';
import type { BatchRow } from './row';
import { runConcrete } from './runConcrete';

/** How long a stopping worker waits for its runs in flight and for Redis. */
const CLOSE_WAIT_MS = 10_000;

export interface WorkerOptions {
  jobs: number;
  esminiPath?: string;
  /** Seconds with nothing to do after which the worker stops; undefined: it runs until interrupted. */
  idleExit?: number;
  quiet: boolean;
  io: BatchOutput;
}

/** Placed files stay out of the folder they are copied from: a job's layout nests the scenario's folder `depth` levels down. */
function depthOf(relative: string[]): number {
  const leadingUps = (each: string) => {
    const parts = each.split('/');
    const first = parts.findIndex((part) => part !== '..');
    return first < 0 ? parts.length : first;
  };
  return Math.max(0, ...relative.map(leadingUps));
}

/**
 * A worker's row with the paths into its job's folder `layout` (where the files lie around `jobScenarioFolder`) said as the
 * files they stand for around `userScenarioFolder`, the scenario's folder where the batch was started.
 */
function saidFrom(row: BatchRow, layout: string, jobScenarioFolder: string, userScenarioFolder: string): BatchRow {
  const said = (text: string) => withoutRunFolder(text, layout, userScenarioFolder, new Map(), () => false, jobScenarioFolder);
  return {
    ...row,
    message: said(row.message),
    ...(row.reason === undefined ? {} : { reason: said(row.reason) }),
    messages: row.messages.map((message) => ({ ...message, text: said(message.text) })),
  };
}

/**
 * `modular2simple worker`: runs a queue's jobs, `jobs` at a time, until SIGINT or SIGTERM (or `idleExit`
 * seconds with nothing to do). Each job's files are fetched once per machine, by their hash, and laid out
 * as they were around the scenario's folder; each row goes to its batch's list in Redis.
 */
export async function runWorker(url: URL, options: WorkerOptions): Promise<number> {
  const client = await connect(url);
  const home = makeRunFolder(sharedRunsFolder('worker'), 'worker-');
  const cache = path.join(home, 'files');
  fs.mkdirSync(cache, { recursive: true });
  const fetching = new Map<string, Promise<string>>();
  const fetchFile = (hash: string): Promise<string> => {
    let pending = fetching.get(hash);
    if (!pending) {
      pending = (async () => {
        const bytes = await client.getBuffer(fileKey(hash));
        if (!bytes) throw new Error(`the file ${hash} is not in Redis (sent more than a week ago?)`);
        const target = path.join(cache, hash);
        await fs.promises.writeFile(target, bytes);
        return target;
      })();
      pending.catch(() => fetching.delete(hash));
      fetching.set(hash, pending);
    }
    return pending;
  };
  const stopping = new AbortController();
  // Each run in flight listens for the stop (as in a local batch): past node's default of 10 it warned of a leak.
  setMaxListeners(options.jobs + 1, stopping.signal);
  let active = 0;
  let lastActivity = Date.now();
  const runJob = async (job: Job<RunJob>): Promise<string> => {
    active++;
    lastActivity = Date.now();
    const data = job.data;
    const layout = makeRunFolder(home, 'job-');
    try {
      const depth = depthOf([...data.files.map((file) => file.relative), ...data.searchPath]);
      const scenarioFolder = path.join(layout, ...Array.from({ length: depth }, (_, level) => `d${level}`));
      fs.mkdirSync(scenarioFolder, { recursive: true });
      for (const file of data.files) {
        const target = path.resolve(scenarioFolder, file.relative);
        if (!target.startsWith(layout + path.sep)) throw new Error(`the file ${file.relative} lies outside the job's folder`);
        await fs.promises.mkdir(path.dirname(target), { recursive: true });
        const cached = await fetchFile(file.sha256);
        // A hard link costs nothing per run; a copy where links are not possible.
        await fs.promises.link(cached, target).catch(() => fs.promises.copyFile(cached, target));
      }
      const searchPath = [
        ...new Set([
          scenarioFolder,
          ...data.searchPath.map((folder) => path.resolve(scenarioFolder, folder)),
          ...data.files.map((file) => path.dirname(path.resolve(scenarioFolder, file.relative))),
        ]),
      ];
      // As a local batch runs it: the paths it names made absolute from where its files now lie.
      const text = (await rebasedConcreteText(data.text, scenarioFolder, undefined, (file) => nodeFileSystem.kind(file))).text;
      // Its controller Files, sent beside the scenario, handed as a local batch hands them (its catalogs are laid out too).
      const catalogs = new CatalogLoader(new ScenarioStore({ root: layout, scenarioPath: [] }));
      const controllerFiles = await controllerFilesFrom(data.text, scenarioFolder, catalogs);
      const ran = await runConcrete(
        {
          index: data.index,
          text,
          parameters: data.parameters,
          searchPath,
          scenarioFolder: data.scenarioFolder,
          controllerFilesFrom: controllerFiles,
        },
        {
          duration: data.duration ?? undefined,
          durationSetBy: data.durationSetBy,
          seed: data.seed,
          esminiPath: options.esminiPath,
          runsFolder: layout,
        },
        stopping.signal,
      );
      // The paths made absolute into this job's folder are said from the batch's scenario folder, as a local batch says them.
      const row = ran && data.scenarioFolder !== undefined ? saidFrom(ran, layout, scenarioFolder, data.scenarioFolder) : ran;
      // Ctrl-C on a terminal reaches esmini too, which then ends early as if by itself: the job runs again elsewhere.
      if (!row || stopping.signal.aborted) throw new Error('the worker was stopped during the run');
      // Reported before the job completes: a worker that dies between the two has its job run again, and the batch keeps the first row.
      await client.rpush(resultsKey(data.batchId), JSON.stringify(row));
      if (!options.quiet) options.io.err(`${data.batchId.slice(0, 8)} ${runLine(row)}`);
      return row.status;
    } finally {
      fs.rmSync(layout, { recursive: true, force: true });
      active--;
      lastActivity = Date.now();
    }
  };
  const worker = new Worker<RunJob>(QUEUE_NAME, runJob, {
    connection: connectionOf(url),
    concurrency: options.jobs,
    lockDuration: LOCK_DURATION_MS,
    stalledInterval: STALLED_INTERVAL_MS,
    maxStalledCount: 3,
  });
  let connectionError: Error | undefined;
  worker.on('error', (error) => {
    connectionError = error;
  });
  if (!options.quiet) options.io.err(`worker: running up to ${options.jobs} at a time from ${QUEUE_NAME} at ${url.host}`);
  await new Promise<void>((resolve) => {
    const stop = () => {
      stopping.abort();
      resolve();
    };
    process.once('SIGINT', stop);
    process.once('SIGTERM', stop);
    if (options.idleExit !== undefined) {
      const idle = options.idleExit * 1000;
      const timer = setInterval(() => {
        if (active === 0 && Date.now() - lastActivity > idle) {
          clearInterval(timer);
          resolve();
        }
      }, 100);
    }
  });
  // Waits for the runs in flight; with Redis gone that could last for ever, so after a while it stops waiting.
  const closed = await Promise.race([
    worker.close().then(() => true),
    new Promise<boolean>((resolve) => setTimeout(() => resolve(false), CLOSE_WAIT_MS).unref()),
  ]);
  if (!closed) {
    options.io.err(
      `worker: Redis did not answer within ${CLOSE_WAIT_MS / 1000} s of stopping; the jobs in flight go back to the queue when their locks lapse`,
    );
    await Promise.race([worker.disconnect(), new Promise((resolve) => setTimeout(resolve, 1000).unref())]);
  }
  client.disconnect();
  removeRunFolderAt(home);
  if (connectionError && !options.quiet) options.io.err(`worker: the last Redis error was: ${connectionError.message}`);
  if (closed) return 0;
  // The Redis client's reconnection timers would keep the process alive: it ends once its output is written.
  setTimeout(() => process.exit(3), 1000).unref();
  return 3;
}
