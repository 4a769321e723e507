import { spawn, spawnSync } from 'node:child_process';
import * as path from 'node:path';
import * as zlib from 'node:zlib';
import { crc32 } from '../../server/src/core/zip';
import { CliRun, withoutSchema } from './fixtures';
import { cliPath, repoRoot } from './paths';

/**
 * Runs the CLI in a child process bounded by the test itself: killed after `timeoutMs` (a watchdog)
 * and limited to `heapMb` of V8 heap, so that a regression fails the test instead of the machine.
 */
export function runBounded(
  args: string[],
  options: { cwd?: string; env?: Record<string, string | undefined>; timeoutMs?: number; heapMb?: number } = {},
): CliRun & { timedOut: boolean; ms: number } {
  const started = Date.now();
  const result = spawnSync(process.execPath, [`--max-old-space-size=${options.heapMb ?? 256}`, cliPath, ...withoutSchema(args)], {
    cwd: options.cwd,
    env: { ...process.env, SCENARIO_PATH: '', ...options.env },
    encoding: 'utf8',
    timeout: options.timeoutMs ?? 20_000,
    killSignal: 'SIGKILL',
    maxBuffer: 64 * 1024 * 1024,
  });
  const timedOut = (result.error as NodeJS.ErrnoException | undefined)?.code === 'ETIMEDOUT';
  return { status: result.status ?? -1, stdout: result.stdout ?? '', stderr: result.stderr ?? '', timedOut, ms: Date.now() - started };
}

/** A script run by node with the project's TypeScript loader, bounded the same way. */
export function runScript(
  script: string,
  args: string[],
  options: { timeoutMs?: number; heapMb?: number; cwd?: string; nodeArgs?: string[] } = {},
): CliRun & { timedOut: boolean } {
  const nodeArgs = [`--max-old-space-size=${options.heapMb ?? 512}`, ...(options.nodeArgs ?? []), '--import', 'tsx'];
  const result = spawnSync(process.execPath, [...nodeArgs, script, ...args], {
    cwd: options.cwd ?? repoRoot,
    encoding: 'utf8',
    timeout: options.timeoutMs ?? 60_000,
    killSignal: 'SIGKILL',
  });
  const timedOut = (result.error as NodeJS.ErrnoException | undefined)?.code === 'ETIMEDOUT';
  return { status: result.status ?? -1, stdout: result.stdout ?? '', stderr: result.stderr ?? '', timedOut };
}

/** Starts a script without waiting; for tests that signal it. */
export function startScript(script: string, args: string[], cwd = repoRoot) {
  return spawn(process.execPath, ['--import', 'tsx', script, ...args], { cwd, stdio: ['ignore', 'pipe', 'pipe'] });
}

export const scalingScript = path.join(repoRoot, 'test', 'support', 'scaling.ts');

/**
 * The ratio of the CPU time an operation takes at 4x its size to the time at 1x, each the best of three
 * runs in a child process: about 4 for a linear operation, 16 for a quadratic one.
 */
export function scalingRatio(kind: string, small: number, factor = 4): { ratio: number; smallMs: number; largeMs: number } {
  const time = (size: number): number => {
    const run = runScript(scalingScript, [kind, String(size)], { timeoutMs: 120_000 });
    if (run.status !== 0) throw new Error(`${kind} at ${size}: ${run.timedOut ? 'timed out' : run.stderr}`);
    return Number(run.stdout.trim());
  };
  const smallMs = Math.max(1, time(small));
  const largeMs = time(small * factor);
  return { ratio: largeMs / smallMs, smallMs, largeMs };
}

/** What each check of a document takes at `small` and at `factor` times its size (CPU milliseconds, best of three; see scaling.ts `checkTimes`). */
export function checkScalingTimes(small: number, factor = 4): { name: string; smallMs: number; largeMs: number }[] {
  const times = (size: number): Record<string, number> => {
    const run = runScript(scalingScript, ['checks', String(size)], { timeoutMs: 180_000, heapMb: 1024, nodeArgs: ['--expose-gc'] });
    if (run.status !== 0) throw new Error(`checks at ${size}: ${run.timedOut ? 'timed out' : run.stderr}`);
    return JSON.parse(run.stdout) as Record<string, number>;
  };
  const smallTimes = times(small);
  const largeTimes = times(small * factor);
  return Object.keys(largeTimes).map((name) => ({ name, smallMs: smallTimes[name], largeMs: largeTimes[name] }));
}

export interface RawEntry {
  name: string;
  data: Uint8Array | string;
  /** Deflate the data (the default stores it). */
  deflate?: boolean;
}

/**
 * Writes a ZIP archive byte by byte, so that tests can build what no ZIP library writes: the same
 * name twice, or central-directory records that share one local entry (`aliases`).
 */
export function rawZip(entries: RawEntry[], aliases: { name: string; of: number }[] = []): Uint8Array {
  const locals: Buffer[] = [];
  const central: Buffer[] = [];
  let offset = 0;
  const records: { name: Buffer; method: number; crc: number; compressed: number; size: number; offset: number }[] = [];
  for (const entry of entries) {
    const data = Buffer.from(entry.data);
    const stored = entry.deflate ? zlib.deflateRawSync(data) : data;
    const name = Buffer.from(entry.name, 'utf8');
    const header = Buffer.alloc(30);
    header.writeUInt32LE(0x04034b50, 0);
    header.writeUInt16LE(20, 4);
    header.writeUInt16LE(0x800, 6);
    header.writeUInt16LE(entry.deflate ? 8 : 0, 8);
    header.writeUInt32LE(crc32(data), 14);
    header.writeUInt32LE(stored.length, 18);
    header.writeUInt32LE(data.length, 22);
    header.writeUInt16LE(name.length, 26);
    locals.push(header, name, stored);
    records.push({ name, method: entry.deflate ? 8 : 0, crc: crc32(data), compressed: stored.length, size: data.length, offset });
    offset += 30 + name.length + stored.length;
  }
  for (const alias of aliases) records.push({ ...records[alias.of], name: Buffer.from(alias.name, 'utf8') });
  for (const record of records) {
    const header = Buffer.alloc(46);
    header.writeUInt32LE(0x02014b50, 0);
    header.writeUInt16LE(20, 4);
    header.writeUInt16LE(20, 6);
    header.writeUInt16LE(0x800, 8);
    header.writeUInt16LE(record.method, 10);
    header.writeUInt32LE(record.crc, 16);
    header.writeUInt32LE(record.compressed, 20);
    header.writeUInt32LE(record.size, 24);
    header.writeUInt16LE(record.name.length, 28);
    header.writeUInt32LE(record.offset, 42);
    central.push(header, record.name);
  }
  const centralBytes = Buffer.concat(central);
  const end = Buffer.alloc(22);
  end.writeUInt32LE(0x06054b50, 0);
  end.writeUInt16LE(records.length, 8);
  end.writeUInt16LE(records.length, 10);
  end.writeUInt32LE(centralBytes.length, 12);
  end.writeUInt32LE(offset, 16);
  return new Uint8Array(Buffer.concat([...locals, centralBytes, end]));
}

/** Whether this process may make a private mount namespace (to give a test its own /dev). */
export function canUnshareMounts(): boolean {
  const probe = spawnSync('unshare', ['-m', '--propagation', 'private', 'true'], { encoding: 'utf8' });
  return probe.status === 0;
}
