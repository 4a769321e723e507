import { createHash } from 'node:crypto';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Queue } from 'bullmq';
import { Redis } from 'ioredis';
import { nodeFileSystem } from '../core/sources';
import { controllerFilesNamed } from '../esmini/controllerFiles';
import { BatchPlanView, concreteRun, filesNamed, namedPaths } from './plan';
import { BatchOutput, Progress, Tally } from './progress';
import type { Criterion } from './criteria';
import { BatchIdentity, BatchRow, ResultsFolder } from './results';
import type { RunSettings } from './runConcrete';

/** The BullMQ queue every batch and worker use; a job's id names its batch, so batches can share it. */
export const QUEUE_NAME = 'modular2simple-runs';
/** A key prefix of our own beside BullMQ's. */
const PREFIX = 'modular2simple';
/** Files a run needs, content-addressed: each sent once, kept a week. */
export const fileKey = (sha256: string): string => `${PREFIX}:file:${sha256}`;
/** The rows of one batch, in the order workers finished them; read from the start on every resume. */
export const resultsKey = (batchId: string): string => `${PREFIX}:results:${batchId}`;
const FILE_TTL_SECONDS = 7 * 24 * 3600;
/** A job's lock: a worker renews it every half; a worker that dies lets it lapse and the job runs elsewhere. */
export const LOCK_DURATION_MS = 6000;
export const STALLED_INTERVAL_MS = 3000;
/** Tries of a job whose worker failed (not of a run that failed: that is a row with status error). */
const ATTEMPTS = 3;

/** A file a job needs: where it lies relative to the scenario's folder, and its content's hash. */
export interface JobFile {
  relative: string;
  sha256: string;
}

/** Everything a worker needs for one run, on a machine that shares no file system with the batch. */
export interface RunJob {
  batchId: string;
  index: string;
  text: string;
  parameters: Record<string, string>;
  files: JobFile[];
  /** The search folders, relative to the scenario's folder. */
  searchPath: string[];
  /**
   * The scenario's folder where the batch was started, as its user names it: a row's words are said from there, not from
   * the worker's private folders (absent from an older batch).
   */
  scenarioFolder?: string;
  /** The limit the user set; null: the scenario's own end. */
  duration: number | null;
  /** Where the user sets the limit, as the rows' reasons name it (RunSettings.durationSetBy); absent from an older batch. */
  durationSetBy?: string;
  seed: number;
}

export class RedisUnreachableError extends Error {
  constructor(
    message: string,
    /** Redis went away after the batch reached it: the rows that arrived are written. */
    readonly lostAfterStart = false,
  ) {
    super(message);
  }
}

/** Connection options for BullMQ from redis://HOST:PORT[/DB]. */
export function connectionOf(url: URL): {
  host: string;
  port: number;
  db: number;
  username?: string;
  password?: string;
  maxRetriesPerRequest: null;
} {
  const db = Number(url.pathname.replace(/^\//, '') || 0);
  return {
    host: url.hostname,
    port: Number(url.port || 6379),
    db: Number.isInteger(db) ? db : 0,
    ...(url.username ? { username: decodeURIComponent(url.username) } : {}),
    ...(url.password ? { password: decodeURIComponent(url.password) } : {}),
    maxRetriesPerRequest: null,
  };
}

/** A client that fails at once when Redis cannot be reached, instead of retrying for ever: RedisUnreachableError. */
export async function connect(url: URL): Promise<Redis> {
  const client = new Redis({
    ...connectionOf(url),
    lazyConnect: true,
    connectTimeout: 3000,
    maxRetriesPerRequest: 1,
    retryStrategy: () => null,
    enableOfflineQueue: false,
  });
  // The socket's own error (ECONNREFUSED, ENOTFOUND) says more than the closed connection the command then meets.
  let socketError: Error | undefined;
  client.on('error', (error: Error) => (socketError ??= error));
  try {
    await client.connect();
    await client.ping();
    return client;
  } catch (error) {
    client.disconnect();
    throw new RedisUnreachableError(
      `cannot reach Redis at ${url.protocol}//${url.host}: ${(socketError ?? (error as Error)).message || 'connection refused'}`,
    );
  }
}

function sha256(data: Buffer | string): string {
  return createHash('sha256').update(data).digest('hex');
}

/** A path relative to the scenario's folder, with '/' on every system. */
function relativeTo(folder: string, file: string): string {
  return path.relative(folder, file).split(path.sep).join('/');
}

/** How a queued batch ended: its rows all written (`done`), interrupted, or runs the workers failed on every try. */
export type QueuedBatchEnd =
  { ended: 'done'; results: ResultsFolder; summary: string } | { ended: 'interrupted' } | { ended: 'workers-failed' };

/**
 * `batch --queue`: sends the files and the runs that results.csv lacks, then writes the rows the workers
 * report as they come. Jobs are named by batch and index, so a run again adds nothing twice; rows are
 * read back from the start, so none reported while the batch was away is lost.
 */
export async function queueBatch(
  url: URL,
  plan: BatchPlanView,
  identity: BatchIdentity,
  resultsFolder: string,
  options: { quiet: boolean; io: BatchOutput; settings: RunSettings; criteria?: Criterion[]; junitFile?: string },
): Promise<QueuedBatchEnd> {
  const { io, quiet, settings } = options;
  const client = await connect(url);
  let queue: Queue | undefined;
  const stop = new AbortController();
  const onSignal = () => stop.abort();
  process.on('SIGINT', onSignal);
  process.on('SIGTERM', onSignal);
  let results: ResultsFolder | undefined;
  try {
    results = await ResultsFolder.open(path.resolve(resultsFolder), plan.parameterNames, identity, options.criteria, options.junitFile);
    const batchId = sha256(JSON.stringify(identity)).slice(0, 24);
    const already = plan.chosen.filter((index) => results!.done.has(index.toString())).length;
    const todo = plan.chosen.filter((index) => !results!.done.has(index.toString()));

    // Each file once, by its content; each job lists every file its run names (its road may be a varied parameter).
    const sent = new Map<string, Promise<JobFile>>();
    const send = (relative: string, read: () => Promise<Uint8Array>): Promise<JobFile> => {
      let pending = sent.get(relative);
      if (!pending) {
        pending = (async () => {
          const bytes = Buffer.from(await read());
          const hash = sha256(bytes);
          await client.set(fileKey(hash), bytes, 'EX', FILE_TTL_SECONDS, 'NX');
          return { relative, sha256: hash };
        })();
        sent.set(relative, pending);
      }
      return pending;
    };
    // The roads and catalogs a self-contained package ScenarioFile holds go with every job, where its flattened text names them.
    const packaged = await Promise.all(
      plan.packagedFiles.map((file) => send(relativeTo(plan.scenarioFolder, file.path), () => Promise.resolve(file.bytes))),
    );
    const filesByPaths = new Map<string, Promise<JobFile[]>>();
    const filesOf = (text: string): Promise<JobFile[]> => {
      const named = namedPaths(text);
      const key = JSON.stringify(named);
      let files = filesByPaths.get(key);
      if (!files) {
        const onDisk = filesNamed(named, plan.scenarioFolder, plan.searchPath);
        files = (async () => {
          // The package's own files first (a varied `$Road` may name another of them), then what the text names on disk.
          const named = await Promise.all(
            ((await plan.packagedOf?.(text)) ?? []).map((file) =>
              send(relativeTo(plan.scenarioFolder, file.path), () => Promise.resolve(file.bytes)),
            ),
          );
          const own = [...packaged, ...named.filter((file) => !packaged.some((each) => each.relative === file.relative))];
          const found = await Promise.all(onDisk.map((file) => send(relativeTo(plan.scenarioFolder, file), () => readJobFile(file))));
          return [...own, ...found.filter((file) => !own.some((each) => each.relative === file.relative))];
        })();
        filesByPaths.set(key, files);
      }
      return files;
    };
    const searchPath = plan.searchPath.map((folder) => relativeTo(plan.scenarioFolder, folder) || '.');
    // With them, the controller Files a run names from the scenario's folder (their values may vary), as a local batch hands them.
    const jobFilesOf = async (text: string): Promise<JobFile[]> => {
      const named = await filesOf(text);
      const from = await plan.controllerFilesOf?.(text);
      const controllers = from ? controllerFilesNamed(text, from, (file) => fs.existsSync(file) && fs.statSync(file).isFile()) : [];
      const sentControllers = await Promise.all(
        controllers.map((file) => send(relativeTo(plan.scenarioFolder, file), () => readJobFile(file))),
      );
      return [...named, ...sentControllers.filter((file) => !named.some((each) => each.relative === file.relative))];
    };

    queue = new Queue(QUEUE_NAME, { connection: connectionOf(url) });
    queue.on('error', () => undefined);
    // Jobs of this batch that failed on every try in an earlier attempt at it are tried again.
    for (const job of await queue.getFailed(0, -1)) if ((job.data as RunJob).batchId === batchId && job.id) await queue.remove(job.id);
    const pending = new Set<string>();
    const tally = new Tally();
    const jobs: {
      name: string;
      data: RunJob;
      opts: { jobId: string; attempts: number; removeOnComplete: boolean; removeOnFail: boolean };
    }[] = [];
    for (const index of todo) {
      const run = concreteRun(plan.variations, index, plan.parameterNames, []);
      if ('discarded' in run) {
        await results.append(run.discarded);
        tally.add(run.discarded);
        continue;
      }
      const jobId = `${batchId}-${run.index}`;
      pending.add(run.index);
      jobs.push({
        name: 'run',
        data: {
          batchId,
          index: run.index,
          text: run.text,
          parameters: run.parameters,
          files: await jobFilesOf(run.text),
          searchPath,
          scenarioFolder: plan.scenarioFolder,
          duration: settings.duration ?? null,
          ...(settings.durationSetBy ? { durationSetBy: settings.durationSetBy } : {}),
          seed: settings.seed,
        },
        opts: { jobId, attempts: ATTEMPTS, removeOnComplete: true, removeOnFail: false },
      });
      if (jobs.length >= 200) await queue.addBulk(jobs.splice(0));
    }
    if (jobs.length > 0) await queue.addBulk(jobs.splice(0));
    if (!quiet)
      io.err(
        `${pending.size} run${pending.size === 1 ? '' : 's'} on the queue ${QUEUE_NAME} at ${url.host}` +
          (already > 0 ? `; ${already} already in ${results.csvFile}` : ''),
      );

    const progress = new Progress(
      pending.size,
      quiet ? undefined : process.stderr.isTTY ? process.stderr : undefined,
      quiet ? () => undefined : io.err,
    );
    let cursor = 0;
    let lastFailedCheck = 0;
    const failed = new Map<string, string>();
    while (!stop.signal.aborted && pending.size > failed.size) {
      const rows = await client.lrange(resultsKey(batchId), cursor, cursor + 999);
      cursor += rows.length;
      for (const text of rows) {
        const row = JSON.parse(text) as BatchRow;
        if (!pending.has(row.index)) continue;
        pending.delete(row.index);
        failed.delete(row.index);
        await results.append(row);
        tally.add(row);
        progress.tick(row);
      }
      if (rows.length > 0) continue;
      if (Date.now() - lastFailedCheck > 1000) {
        lastFailedCheck = Date.now();
        for (const job of await queue.getFailed(0, 999)) {
          const data = job.data as RunJob;
          if (data.batchId === batchId && pending.has(data.index)) failed.set(data.index, job.failedReason ?? 'failed');
        }
      }
      await new Promise((resolve) => setTimeout(resolve, 50));
    }
    progress.end();
    const summary = tally.summary(already, results.csvFile);
    if (stop.signal.aborted) {
      io.err(`interrupted after ${summary}; the rest stay on the queue: run the same command again to collect them`);
      return { ended: 'interrupted' };
    }
    if (failed.size > 0) {
      const [index, reason] = [...failed][0];
      io.err(
        `modular2simple: error: ${failed.size} run${failed.size === 1 ? '' : 's'} failed on the workers ${ATTEMPTS} times (index ${index}: ${reason}); ${summary}; run the same command again to try them again`,
      );
      return { ended: 'workers-failed' };
    }
    await client.del(resultsKey(batchId));
    return { ended: 'done', results, summary };
  } catch (error) {
    // Redis went away after the batch reached it: what arrived is written; the rest waits in Redis for a run again.
    if (client.status === 'ready' || error instanceof RedisUnreachableError) throw error;
    throw new RedisUnreachableError(
      `lost Redis at ${url.protocol}//${url.host}: ${(error as Error).message}; the rows that arrived are in ${results?.csvFile ?? resultsFolder}: run the same command again to collect the rest`,
      true,
    );
  } finally {
    process.off('SIGINT', onSignal);
    process.off('SIGTERM', onSignal);
    await results?.finish();
    const closed = await Promise.race([
      (queue?.close() ?? Promise.resolve()).then(() => true),
      new Promise<boolean>((resolve) => setTimeout(() => resolve(false), 5000).unref()),
    ]);
    client.disconnect();
    // BullMQ's connection would try to reach a Redis that is gone for ever: the process ends once its output is written.
    if (!closed) setTimeout(() => process.exit(3), 1000).unref();
  }
}

/** A road or catalog a job carries, read within the bounds and with the refusals (FIFOs, devices, oversize) of every other read. */
async function readJobFile(file: string): Promise<Uint8Array> {
  const bytes = await nodeFileSystem.readFile(file);
  if (!bytes) throw new Error(`${file}: vanished before the batch could send it to the workers; run the batch again`);
  return bytes;
}
