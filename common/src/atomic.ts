import * as fs from 'node:fs';
import * as path from 'node:path';

export type OutputData = string | Uint8Array | AsyncIterable<Uint8Array>;

export class OutputError extends Error {}

/** Temporary files being written, removed if the process is interrupted. */
const liveTemporaries = new Set<string>();

function removeTemporariesAndExit(signal: NodeJS.Signals): void {
  for (const temporary of liveTemporaries) {
    try {
      fs.rmSync(temporary, { force: true });
    } catch {
      // Nothing more can be done while the process ends.
    }
  }
  liveTemporaries.clear();
  process.removeListener('SIGINT', removeTemporariesAndExit);
  process.removeListener('SIGTERM', removeTemporariesAndExit);
  process.kill(process.pid, signal);
}

function track(temporary: string): void {
  if (liveTemporaries.size === 0) {
    process.on('SIGINT', removeTemporariesAndExit);
    process.on('SIGTERM', removeTemporariesAndExit);
  }
  liveTemporaries.add(temporary);
}

function untrack(temporary: string): void {
  liveTemporaries.delete(temporary);
  if (liveTemporaries.size === 0) {
    process.removeListener('SIGINT', removeTemporariesAndExit);
    process.removeListener('SIGTERM', removeTemporariesAndExit);
  }
}

/** An output prepared beside its target: either a temporary file to rename, or a device written directly. */
export interface PreparedOutput {
  target: string;
  /** Renames the temporary file over the target (nothing to do for a device). */
  commit(): Promise<void>;
  /** Removes the temporary file. */
  abort(): Promise<void>;
}

function stat(target: string): fs.Stats | undefined {
  try {
    return fs.statSync(target);
  } catch (error) {
    if ((error as NodeJS.ErrnoException).code === 'ENOENT') return undefined;
    throw new OutputError(`cannot inspect ${target} (${(error as NodeJS.ErrnoException).code})`);
  }
}

/** Where and how an output is written: in place (a device) or through a temporary file beside it. */
type OutputPlan = { device: true; resolved: string } | { device: false; real: string; temporary: string; existing: fs.Stats | undefined };

/**
 * Decides how a target is written, refusing a folder or a read-only file. A target that is not a
 * regular file (a device, a FIFO, /dev/stdout) is written directly: renaming over it would replace
 * the device. A link is followed, so that the file it names is replaced and the link kept; the
 * temporary name is short, so that any name the target may have works.
 */
function planOutput(target: string): OutputPlan {
  const resolved = path.resolve(target);
  const existing = stat(resolved);
  if (existing?.isDirectory()) throw new OutputError(`${target} is a folder`);
  if (existing && !existing.isFile()) return { device: true, resolved };
  const real = existing ? fs.realpathSync(resolved) : resolved;
  if (existing) {
    const ownerCanWrite = (existing.mode & 0o200) !== 0;
    let accessible = true;
    try {
      fs.accessSync(real, fs.constants.W_OK);
    } catch {
      accessible = false;
    }
    if (!ownerCanWrite || !accessible) throw new OutputError(`${target} is read-only; make it writable or choose another output`);
  }
  const temporary = path.join(path.dirname(real), `.m2s-${process.pid}-${Math.random().toString(36).slice(2, 10)}.tmp`);
  return { device: false, real, temporary, existing };
}

/**
 * Writes the data beside the target without touching the target yet (a device is written directly
 * when committed). A read-only target is refused, as a shell redirection would refuse it; the mode of
 * an existing target is kept.
 */
export async function prepareOutput(target: string, data: OutputData): Promise<PreparedOutput> {
  const plan = planOutput(target);
  if (plan.device) {
    // A device or pipe: written in place when committed, since there is nothing to replace atomically.
    return {
      target,
      commit: async () => {
        const handle = await fs.promises.open(plan.resolved, fs.constants.O_WRONLY | fs.constants.O_APPEND);
        try {
          if (typeof data === 'string' || data instanceof Uint8Array) await handle.writeFile(data);
          else for await (const chunk of data) await handle.write(chunk);
        } finally {
          await handle.close();
        }
      },
      abort: async () => undefined,
    };
  }
  const { real, temporary, existing } = plan;
  track(temporary);
  try {
    await fs.promises.writeFile(temporary, data, { flag: 'wx', mode: existing ? existing.mode & 0o7777 : 0o666 });
    if (existing) {
      await fs.promises.chmod(temporary, existing.mode & 0o7777);
      // Keeping the owner needs privileges; without them the file belongs to whoever writes it, as with any editor.
      if (process.getuid?.() === 0) await fs.promises.chown(temporary, existing.uid, existing.gid).catch(() => undefined);
    }
  } catch (error) {
    await fs.promises.rm(temporary, { force: true }).catch(() => undefined);
    untrack(temporary);
    throw error;
  }
  return {
    target,
    commit: async () => {
      try {
        await fs.promises.rename(temporary, real);
      } finally {
        await fs.promises.rm(temporary, { force: true }).catch(() => undefined);
        untrack(temporary);
      }
    },
    abort: async () => {
      await fs.promises.rm(temporary, { force: true }).catch(() => undefined);
      untrack(temporary);
    },
  };
}

/** An output prepared with blocking calls (prepareOutputSync). */
export interface PreparedOutputSync {
  target: string;
  commit(): void;
  abort(): void;
}

function removeQuietly(temporary: string): void {
  try {
    // The temporary is a file this process made: unlink is rm for it, without loading rm's folder walker.
    fs.unlinkSync(temporary);
  } catch {
    // Already gone (renamed), or best effort, as the asynchronous path's rm().catch().
  }
}

/**
 * prepareOutput with blocking calls, for data already in memory: the same checks, temporary file and
 * rename. The CLI writes so, as a thread-pool turn per call was a noticeable part of a short run.
 */
export function prepareOutputSync(target: string, data: string | Uint8Array): PreparedOutputSync {
  const plan = planOutput(target);
  if (plan.device) {
    return {
      target,
      commit: () => {
        const descriptor = fs.openSync(plan.resolved, fs.constants.O_WRONLY | fs.constants.O_APPEND);
        try {
          fs.writeFileSync(descriptor, data);
        } finally {
          fs.closeSync(descriptor);
        }
      },
      abort: () => undefined,
    };
  }
  const { real, temporary, existing } = plan;
  track(temporary);
  try {
    fs.writeFileSync(temporary, data, { flag: 'wx', mode: existing ? existing.mode & 0o7777 : 0o666 });
    if (existing) {
      fs.chmodSync(temporary, existing.mode & 0o7777);
      if (process.getuid?.() === 0) {
        try {
          fs.chownSync(temporary, existing.uid, existing.gid);
        } catch {
          // Keeping the owner needs privileges; without them the file belongs to whoever writes it.
        }
      }
    }
  } catch (error) {
    removeQuietly(temporary);
    untrack(temporary);
    throw error;
  }
  return {
    target,
    commit: () => {
      try {
        fs.renameSync(temporary, real);
      } finally {
        removeQuietly(temporary);
        untrack(temporary);
      }
    },
    abort: () => {
      removeQuietly(temporary);
      untrack(temporary);
    },
  };
}

/**
 * Writes a file atomically: the data goes to a temporary file beside the target, which is then
 * renamed over it. On any failure the temporary file is removed and an existing target is untouched.
 */
export async function writeFileAtomic(target: string, data: OutputData): Promise<void> {
  const prepared = await prepareOutput(target, data);
  await prepared.commit();
}

/** The folders `mkdir -p` of `folder` would create, the outermost first. */
export function missingFolders(folder: string): string[] {
  const missing: string[] = [];
  for (let current = path.resolve(folder); !fs.existsSync(current); current = path.dirname(current)) {
    missing.unshift(current);
    if (path.dirname(current) === current) break;
  }
  return missing;
}

/**
 * writeFileAtomic into a folder that may not exist yet, for an output the user chose in the editor's save dialog (which
 * offers to create a missing folder, and leaves the creating to whoever writes, as VS Code's own Save As does): the
 * missing folders are made first and removed again when the file cannot be written, so nothing is left behind.
 */
export async function writeFileAtomicMakingFolders(target: string, data: OutputData): Promise<void> {
  const made = missingFolders(path.dirname(path.resolve(target)));
  const innermost = made.at(-1);
  if (innermost !== undefined)
    await fs.promises.mkdir(innermost, { recursive: true }).catch((error: unknown) => {
      throw new OutputError(`cannot create the folder ${innermost} for ${target} (${(error as NodeJS.ErrnoException).code ?? error})`);
    });
  try {
    await writeFileAtomic(target, data);
  } catch (error) {
    // Innermost first, and only when empty: a folder that holds anything else is not ours to remove.
    for (const folder of made.reverse()) await fs.promises.rmdir(folder).catch(() => undefined);
    throw error;
  }
}

export interface WriteAllResult {
  /** Targets written, in order. */
  written: string[];
  /** The target that failed and why; undefined when all were written. */
  failed?: { target: string; error: Error };
}

/**
 * Writes several outputs all or none: every one is prepared first, and only when all are ready are
 * they renamed into place. Should a rename itself fail, the result says exactly which were written.
 */
export async function writeFilesAtomic(outputs: { target: string; data: OutputData }[]): Promise<WriteAllResult> {
  const prepared: PreparedOutput[] = [];
  for (const output of outputs) {
    try {
      prepared.push(await prepareOutput(output.target, output.data));
    } catch (error) {
      for (const done of prepared) await done.abort();
      return { written: [], failed: { target: output.target, error: error as Error } };
    }
  }
  const written: string[] = [];
  for (let i = 0; i < prepared.length; i++) {
    try {
      await prepared[i].commit();
      written.push(prepared[i].target);
    } catch (error) {
      for (const rest of prepared.slice(i + 1)) await rest.abort();
      return { written, failed: { target: prepared[i].target, error: error as Error } };
    }
  }
  return { written };
}

/** writeFilesAtomic with blocking calls, for data already in memory: every output or none. */
export function writeFilesAtomicSync(outputs: { target: string; data: string | Uint8Array }[]): WriteAllResult {
  const prepared: PreparedOutputSync[] = [];
  for (const output of outputs) {
    try {
      prepared.push(prepareOutputSync(output.target, output.data));
    } catch (error) {
      for (const done of prepared) done.abort();
      return { written: [], failed: { target: output.target, error: error as Error } };
    }
  }
  const written: string[] = [];
  for (let i = 0; i < prepared.length; i++) {
    try {
      prepared[i].commit();
      written.push(prepared[i].target);
    } catch (error) {
      for (const rest of prepared.slice(i + 1)) rest.abort();
      return { written, failed: { target: prepared[i].target, error: error as Error } };
    }
  }
  return { written };
}

/** True when both paths name the same existing file (through links too). */
export function isSameFile(a: string, b: string): boolean {
  try {
    const left = fs.statSync(a);
    const right = fs.statSync(b);
    return left.dev === right.dev && left.ino === right.ino;
  } catch {
    return path.resolve(a) === path.resolve(b);
  }
}
