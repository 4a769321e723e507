import * as fs from 'node:fs';
import { DEFAULT_LIMITS } from './limits';

export type FileKind = 'file' | 'directory' | undefined;

export interface FileSystemHost {
  /**
   * The file's bytes, or undefined when it does not exist. Throws FileReadError for what is not a
   * regular file (a folder, a FIFO, a device) or holds more than `maxBytes`.
   */
  readFile(filePath: string, maxBytes?: number): Promise<Uint8Array | undefined>;
  kind(filePath: string): Promise<FileKind>;
  /** The names in a directory, or undefined when it cannot be listed (catalog directories need it). */
  listDirectory?(directoryPath: string): Promise<string[] | undefined>;
  /** Set by a host that remembers kinds itself: a store then shares that cache instead of keeping a second one. */
  readonly kinds?: KindCache;
}

/** Whether paths are files or folders, each asked once of a host and remembered until cleared. */
export class KindCache {
  private readonly known = new Map<string, Promise<FileKind>>();
  /** Grows with each `clear`: what was derived from the kinds of an older generation is stale. */
  generation = 0;

  constructor(private readonly host: Pick<FileSystemHost, 'kind'>) {}

  kind(filePath: string): Promise<FileKind> {
    let pending = this.known.get(filePath);
    if (!pending) {
      pending = this.host.kind(filePath);
      this.known.set(filePath, pending);
    }
    return pending;
  }

  /** Forgets every kind: a creation or deletion changes the kinds of folders too. */
  clear(): void {
    this.known.clear();
    this.generation++;
  }
}

export class FileReadError extends Error {}

export function describeKind(stat: fs.Stats): string {
  if (stat.isDirectory()) return 'a folder';
  if (stat.isFIFO()) return 'a FIFO';
  if (stat.isCharacterDevice()) return 'a character device';
  if (stat.isBlockDevice()) return 'a block device';
  if (stat.isSocket()) return 'a socket';
  return 'not a regular file';
}

/** The error opening a file for reading gives, or undefined where the file does not exist. */
export function openError(filePath: string, error: unknown): FileReadError | undefined {
  const code = (error as NodeJS.ErrnoException).code;
  if (code === 'ENOENT' || code === 'ENOTDIR') return undefined;
  return new FileReadError(`cannot read ${filePath} (${code ?? (error as Error).message})`);
}

/** A buffer for reading the opened file: one byte past the bound, in case it grows while it is read; refuses what is not a regular file or is too large. */
export function readBufferFor(filePath: string, stat: fs.Stats, maxBytes: number): Buffer {
  if (!stat.isFile()) throw new FileReadError(`${filePath} is ${describeKind(stat)}, not a file; only regular files are read`);
  if (stat.size > maxBytes)
    throw new FileReadError(`${filePath} is too large to read (${stat.size} bytes; the limit is ${maxBytes}, raised with --max-file-size)`);
  return Buffer.alloc(Math.min(stat.size, maxBytes) + 1);
}

/** The bytes read, refused when the file grew past the bound while it was read. */
export function boundedBytes(filePath: string, buffer: Buffer, length: number, maxBytes: number): Uint8Array {
  if (length > maxBytes)
    throw new FileReadError(`${filePath} is too large to read (more than ${maxBytes} bytes, raised with --max-file-size)`);
  return buffer.subarray(0, length);
}

export const nodeFileSystem: FileSystemHost = {
  async readFile(filePath, maxBytes = DEFAULT_LIMITS.maxEntryBytes) {
    let handle: fs.promises.FileHandle;
    try {
      // Non-blocking, so that opening a FIFO returns at once instead of waiting for a writer.
      handle = await fs.promises.open(filePath, fs.constants.O_RDONLY | fs.constants.O_NONBLOCK);
    } catch (error) {
      const refusal = openError(filePath, error);
      if (!refusal) return undefined;
      throw refusal;
    }
    try {
      const buffer = readBufferFor(filePath, await handle.stat(), maxBytes);
      let length = 0;
      for (;;) {
        const { bytesRead } = await handle.read(buffer, length, buffer.length - length, null);
        if (bytesRead === 0) break;
        length += bytesRead;
        if (length === buffer.length) break;
      }
      return boundedBytes(filePath, buffer, length, maxBytes);
    } finally {
      await handle.close();
    }
  },
  async kind(filePath) {
    try {
      const stat = await fs.promises.stat(filePath);
      return stat.isFile() ? 'file' : stat.isDirectory() ? 'directory' : undefined;
    } catch {
      return undefined;
    }
  },
  async listDirectory(directoryPath) {
    try {
      return await fs.promises.readdir(directoryPath);
    } catch {
      return undefined;
    }
  },
};
