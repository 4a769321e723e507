import * as fs from 'node:fs';
import { boundedBytes, DEFAULT_LIMITS, FileSystemHost, openError, readBufferFor } from '../core/sources';

/**
 * The CLI's files, read with blocking calls: a command does one thing at a time, and each call of the
 * editor's host (core/sources/host.ts, asynchronous so that the server keeps answering) waits for a turn
 * of libuv's thread pool, which was a tenth of a short flatten's time. What it reads and refuses is that
 * host's, message for message.
 */
export const cliFileSystem: FileSystemHost = {
  readFile(filePath, maxBytes = DEFAULT_LIMITS.maxEntryBytes) {
    let descriptor: number;
    try {
      // Non-blocking, so that opening a FIFO returns at once instead of waiting for a writer.
      descriptor = fs.openSync(filePath, fs.constants.O_RDONLY | fs.constants.O_NONBLOCK);
    } catch (error) {
      const refusal = openError(filePath, error);
      return refusal ? Promise.reject(refusal) : Promise.resolve(undefined);
    }
    try {
      const buffer = readBufferFor(filePath, fs.fstatSync(descriptor), maxBytes);
      let length = 0;
      for (;;) {
        const bytesRead = fs.readSync(descriptor, buffer, length, buffer.length - length, null);
        if (bytesRead === 0) break;
        length += bytesRead;
        if (length === buffer.length) break;
      }
      return Promise.resolve(boundedBytes(filePath, buffer, length, maxBytes));
    } catch (error) {
      return Promise.reject(error as Error);
    } finally {
      fs.closeSync(descriptor);
    }
  },
  kind(filePath) {
    try {
      // No entry is the common answer while candidates are searched: undefined, not an error with a stack trace.
      const stat = fs.statSync(filePath, { throwIfNoEntry: false });
      return Promise.resolve(stat?.isFile() ? 'file' : stat?.isDirectory() ? 'directory' : undefined);
    } catch {
      return Promise.resolve(undefined);
    }
  },
  listDirectory(directoryPath) {
    try {
      return Promise.resolve(fs.readdirSync(directoryPath));
    } catch {
      return Promise.resolve(undefined);
    }
  },
};

/** Reads a file as UTF-8 with its byte order mark kept, so that a concrete scenario is byte for byte the original but for its values. */
export async function readUtf8Exactly(file: string): Promise<string> {
  // The CLI's reader, so that a FIFO or a device named like a scenario is refused instead of read without end.
  const bytes = await cliFileSystem.readFile(file);
  if (bytes === undefined) throw Object.assign(new Error('no such file'), { code: 'ENOENT' });
  try {
    return new TextDecoder('utf-8', { fatal: true, ignoreBOM: true }).decode(bytes);
  } catch {
    throw new Error('not UTF-8 text');
  }
}
