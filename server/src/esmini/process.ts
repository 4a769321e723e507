import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';

/** How a run of esmini ended. */
export type EsminiEnd =
  /** It ended by itself: a StopTrigger (the scenario's or the added time limit) fired, or it quit on an error. */
  | 'exited'
  /** SIGINT after its CSV passed the time limit or the size limit (a clean quit in esmini). */
  | 'interrupted'
  /** SIGKILL after it made no progress for `stallMs`, or when it ignored SIGINT. */
  | 'killed'
  /** It could not be started. */
  | 'not-started'
  /** The caller cancelled the run. */
  | 'cancelled';

export interface EsminiProcessOptions {
  program: string;
  /** The scenario handed to esmini (absolute). */
  scenarioFile: string;
  /** Where esmini runs and writes; its files are relative to nothing else. */
  workDir: string;
  csvFile: string;
  /** `--path` folders, searched in order for roads and catalogs. */
  searchPath: string[];
  timeStep: number;
  seed: number;
  /** Adds `--collision`: esmini's global collision detection. */
  collision?: boolean;
  /** Simulated seconds after which the run is stopped by SIGINT if it has not stopped itself. */
  duration: number;
  /** Wall-clock milliseconds in which its CSV neither grows nor advances (or, before it has one, since the start) before SIGKILL: a hang. */
  stallMs: number;
  /** SIGINT when the CSV grows beyond this many bytes. */
  maxCsvBytes: number;
  /** Output kept in memory beyond this many characters is dropped (counted in `droppedOutput`). */
  maxOutputChars: number;
  onOutput?: (text: string) => void;
  cancel?: AbortSignal;
}

export interface EsminiProcessResult {
  args: string[];
  end: EsminiEnd;
  exitCode: number | null;
  signal: string | null;
  /** esmini's stdout and stderr as they came; beyond maxOutputChars, its head and tail. */
  output: string;
  droppedOutput: number;
  wallMs: number;
  /** Why the process was stopped from outside, or why it did not start. */
  reason?: string;
  /** What stopped it from outside: its simulated time passed the limit, its CSV the size limit, or it made no progress. */
  stoppedBy?: 'time' | 'size' | 'stall';
}

export function esminiArguments(
  options: Pick<EsminiProcessOptions, 'scenarioFile' | 'csvFile' | 'searchPath' | 'timeStep' | 'seed' | 'collision'>,
): string[] {
  const args = [
    '--headless',
    '--osc',
    options.scenarioFile,
    '--fixed_timestep',
    String(options.timeStep),
    '--seed',
    String(options.seed),
    '--csv_logger',
    options.csvFile,
    '--disable_log',
  ];
  if (options.collision) args.push('--collision');
  // esmini 3.6 gives the last --path priority (CommonMini.cpp SE_Options::SetOptionValue inserts each value first): reversed, it searches ours in order.
  for (const folder of [...options.searchPath].reverse()) args.push('--path', folder);
  return args;
}

/** esmini's CSV with its 'Scenario File Name' header naming `scenario`: a run's private copy is removed or moved after the run. */
export function csvNamingScenario(text: string, scenario: string): string {
  return text.replace(/^(Scenario File Name: ).*?(\r?)$/m, (_line, label: string, end: string) => `${label}${scenario}${end}`);
}

/** The TimeStamp of the last complete row of esmini's CSV (its second column), read from the file's tail. */
export function lastCsvTime(csvFile: string): number | undefined {
  let handle: number | undefined;
  try {
    handle = fs.openSync(csvFile, 'r');
    const size = fs.fstatSync(handle).size;
    const length = Math.min(size, 16384);
    const buffer = Buffer.alloc(length);
    fs.readSync(handle, buffer, 0, length, size - length);
    const lines = buffer.toString('latin1').split('\n');
    lines.pop(); // an incomplete last line, or the empty string after the final newline
    for (let i = lines.length - 1; i >= 0; i--) {
      const time = Number(lines[i].split(',')[1]);
      if (Number.isFinite(time) && /^\s*\d/.test(lines[i])) return time;
    }
    return undefined;
  } catch {
    return undefined;
  } finally {
    if (handle !== undefined) fs.closeSync(handle);
  }
}

/** The lines of a file read in chunks, so that a reader stopping early never reads the rest (an esmini CSV may be 200 MB). */
export function* fileLines(file: string, chunkBytes = 1 << 20): Generator<string> {
  const handle = fs.openSync(file, 'r');
  try {
    const buffer = Buffer.alloc(chunkBytes);
    let rest = '';
    for (;;) {
      const read = fs.readSync(handle, buffer, 0, chunkBytes, null);
      if (read === 0) break;
      const lines = (rest + buffer.toString('latin1', 0, read)).split('\n');
      rest = lines.pop() ?? '';
      yield* lines;
    }
    if (rest) yield rest;
  } finally {
    fs.closeSync(handle);
  }
}

const POLL_MS = 25;
const GRACE_AFTER_SIGINT_MS = 5000;

/** Runs esmini once, following its CSV so that it never runs past the limits. Never throws. */
export function runEsminiProcess(options: EsminiProcessOptions): Promise<EsminiProcessResult> {
  const args = esminiArguments(options);
  const started = Date.now();
  return new Promise((resolve) => {
    let output = '';
    let droppedOutput = 0;
    let reason: string | undefined;
    let stoppedBy: EsminiProcessResult['stoppedBy'];
    let end: EsminiEnd = 'exited';
    let settled = false;
    const timers: NodeJS.Timeout[] = [];
    const finish = (result: Omit<EsminiProcessResult, 'args' | 'output' | 'droppedOutput' | 'wallMs'>) => {
      if (settled) return;
      settled = true;
      for (const timer of timers) clearTimeout(timer);
      clearInterval(poll);
      options.cancel?.removeEventListener('abort', onCancel);
      resolve({ args, output: fullOutput(), droppedOutput, wallMs: Date.now() - started, ...result });
    };
    const child = spawn(options.program, args, { cwd: options.workDir, stdio: ['ignore', 'pipe', 'pipe'] });
    // Past the limit the middle goes: the head has the loading messages, the tail how it ended.
    const half = Math.floor(options.maxOutputChars / 2);
    let tail = '';
    const collect = (chunk: Buffer) => {
      const text = chunk.toString('utf8');
      options.onOutput?.(text);
      if (output.length + text.length <= half) {
        output += text;
        return;
      }
      const room = Math.max(0, half - output.length);
      output += text.slice(0, room);
      tail += text.slice(room);
      if (tail.length > 2 * half) {
        droppedOutput += tail.length - half;
        tail = tail.slice(tail.length - half);
      }
    };
    const fullOutput = () => {
      if (tail.length > half) {
        droppedOutput += tail.length - half;
        tail = tail.slice(tail.length - half);
      }
      return droppedOutput > 0
        ? `${output}\n(${droppedOutput} characters of output left out here)\n${tail.slice(tail.indexOf('\n') + 1)}`
        : output + tail;
    };
    child.stdout.on('data', collect);
    child.stderr.on('data', collect);
    const interrupt = (why: string, by: 'time' | 'size') => {
      if (end !== 'exited') return;
      end = 'interrupted';
      reason = why;
      stoppedBy = by;
      child.kill('SIGINT');
      timers.push(
        setTimeout(() => {
          end = 'killed';
          reason = `${why}; it did not quit within ${GRACE_AFTER_SIGINT_MS / 1000} s of SIGINT`;
          child.kill('SIGKILL');
        }, GRACE_AFTER_SIGINT_MS),
      );
    };
    const onCancel = () => {
      end = 'cancelled';
      reason = 'cancelled';
      child.kill('SIGKILL');
    };
    options.cancel?.addEventListener('abort', onCancel);
    if (options.cancel?.aborted) onCancel();
    // Progress, not a fixed wall-clock time, tells a hang: a long scenario on a loaded machine takes its time.
    let lastProgress = Date.now();
    let lastSize = -1;
    let lastTime: number | undefined;
    const stall = () => {
      if (end !== 'exited' && end !== 'interrupted') return;
      end = 'killed';
      stoppedBy = 'stall';
      const at = lastTime === undefined ? 'before its first step' : `at ${lastTime} s simulated`;
      reason = `made no progress for ${options.stallMs / 1000} s of wall-clock time (${at}): it hung`;
      child.kill('SIGKILL');
    };
    const poll = setInterval(() => {
      let size = -1;
      try {
        size = fs.statSync(options.csvFile).size;
      } catch {
        // No CSV yet: esmini is loading.
      }
      const time = size >= 0 ? lastCsvTime(options.csvFile) : undefined;
      if (size !== lastSize || time !== lastTime) {
        lastProgress = Date.now();
        lastSize = size;
        lastTime = time;
      } else if (Date.now() - lastProgress > options.stallMs) stall();
      if (size > options.maxCsvBytes) interrupt(`its CSV passed ${Math.round(options.maxCsvBytes / 1e6)} MB`, 'size');
      // One step of slack: the added StopTrigger ends it at the first step past the limit by itself.
      if (time !== undefined && time > options.duration + 2 * options.timeStep)
        interrupt(`its simulated time passed the ${options.duration} s limit`, 'time');
    }, POLL_MS);
    child.on('error', (error) =>
      finish({ end: 'not-started', exitCode: null, signal: null, reason: `cannot start ${options.program}: ${error.message}` }),
    );
    child.on('close', (exitCode, signal) => finish({ end, exitCode, signal, reason, stoppedBy }));
  });
}

/** The folders in the temporary directory that the private folders of runs (and of `worker`s) share with every run on the machine. */
const SHARED_RUNS_FOLDERS = ['modular2simple-esmini', 'modular2simple-worker'] as const;

/** The folder in the temporary directory that holds the private folders of runs (`worker`: of workers), shared by every one on the machine. */
export function sharedRunsFolder(of: 'runs' | 'worker' = 'runs'): string {
  return path.join(os.tmpdir(), SHARED_RUNS_FOLDERS[of === 'runs' ? 0 : 1]);
}

/** A private folder for one run, outside every user folder. */
export function makeRunFolder(parent: string, prefix = 'esmini-run-'): string {
  for (let attempt = 1; ; attempt++) {
    fs.mkdirSync(parent, { recursive: true });
    try {
      return fs.mkdtempSync(path.join(parent, prefix));
    } catch (error) {
      // Another run that left the shared parent empty removed it between the two calls (removeRunFolderAt): made again.
      if ((error as NodeJS.ErrnoException).code !== 'ENOENT' || attempt >= 5) throw error;
    }
  }
}

/**
 * Removes a run's (or a worker's) private folder, and the shared parent (`sharedRunsFolder`) when that leaves it empty, so that a run
 * leaves nothing in the temporary directory: a concurrent run's folder keeps it (rmdir refuses a folder not empty).
 */
export function removeRunFolderAt(folder: string): void {
  fs.rmSync(folder, { recursive: true, force: true });
  const parent = path.dirname(folder);
  if (parent !== sharedRunsFolder() && parent !== sharedRunsFolder('worker')) return;
  try {
    fs.rmdirSync(parent);
  } catch (error) {
    // Not empty: another run's folder; gone: another run removed it first.
    if (!['ENOTEMPTY', 'EEXIST', 'ENOENT'].includes((error as NodeJS.ErrnoException).code ?? '')) throw error;
  }
}
