import * as path from 'node:path';
import { FileKind, FileSystemHost, nodeFileSystem } from '../sources';

/**
 * The disk as it will be once `files` are written: those files are read from memory, every other
 * path from the disk below. What modularize verifies is exactly what it would write.
 */
export function memoryHost(files: ReadonlyMap<string, string>, below: FileSystemHost = nodeFileSystem): FileSystemHost {
  const encoder = new TextEncoder();
  const folders = new Set<string>();
  for (const file of files.keys()) {
    for (let folder = path.dirname(file); !folders.has(folder); folder = path.dirname(folder)) {
      folders.add(folder);
      if (folder === path.dirname(folder)) break;
    }
  }
  return {
    async readFile(filePath, maxBytes) {
      const text = files.get(path.resolve(filePath));
      return text === undefined ? below.readFile(filePath, maxBytes) : encoder.encode(text);
    },
    async kind(filePath): Promise<FileKind> {
      const resolved = path.resolve(filePath);
      if (files.has(resolved)) return 'file';
      if (folders.has(resolved)) return 'directory';
      return below.kind(filePath);
    },
    async listDirectory(directoryPath) {
      const resolved = path.resolve(directoryPath);
      const own = [...files.keys()].filter((file) => path.dirname(file) === resolved).map((file) => path.basename(file));
      const listed = (await below.listDirectory?.(directoryPath)) ?? (own.length > 0 ? [] : undefined);
      return listed === undefined ? undefined : [...new Set([...listed, ...own])];
    },
  };
}
