import * as fs from 'node:fs';
import { DEFAULT_LIMITS, describeKind, FileReadError, FileSystemHost } from '../core/sources';

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
      const code = (error as NodeJS.ErrnoException).code;
      if (code === 'ENOENT' || code === 'ENOTDIR') return Promise.resolve(undefined);
      return Promise.reject(new FileReadError(`cannot read ${filePath} (${code ?? (error as Error).message})`));
    }
    try {
      const stat = fs.fstatSync(descriptor);
      if (!stat.isFile()) throw new FileReadError(`${filePath} is ${describeKind(stat)}, not a file; only regular files are read`);
      if (stat.size > maxBytes)
        throw new FileReadError(
          `${filePath} is too large to read (${stat.size} bytes; the limit is ${maxBytes}, raised with --max-file-size)`,
        );
      // Read at most one byte past the bound, in case the file grows while it is read.
      const buffer = Buffer.alloc(Math.min(stat.size, maxBytes) + 1);
      let length = 0;
      for (;;) {
        const bytesRead = fs.readSync(descriptor, buffer, length, buffer.length - length, null);
        if (bytesRead === 0) break;
        length += bytesRead;
        if (length === buffer.length) break;
      }
      if (length > maxBytes)
        throw new FileReadError(`${filePath} is too large to read (more than ${maxBytes} bytes, raised with --max-file-size)`);
      return Promise.resolve(buffer.subarray(0, length));
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
