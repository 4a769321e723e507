import { packagedPathTakenMessage } from '../diagnostics/filePath';
import type { FileSystemHost } from '../sources/host';
import type { PackagedFile } from './types';

// Apart from rebase.ts: the CLI's writer imports it for every command, and rebase.ts loads the semantic checks.

function sameBytes(a: Uint8Array, b: Uint8Array): boolean {
  return a.length === b.length && a.every((byte, index) => byte === b[index]);
}

/**
 * Of the files a flattening returns, those a writer may write where they are to go (`at`: their path there, by default
 * their own): a copy named through a `$parameter` (`PackagedFile.namedBy`) is left out where another file already lies,
 * never replaced, with a warning saying the output reaches that file instead.
 */
export async function besideOutputWritable<File extends PackagedFile>(
  files: readonly File[],
  host: Pick<FileSystemHost, 'kind' | 'readFile'>,
  at: (file: File) => string = (file) => file.path,
): Promise<{ files: File[]; warnings: string[] }> {
  const writable: File[] = [];
  const warnings: string[] = [];
  for (const file of files) {
    const target = at(file);
    if (file.namedBy !== undefined && (await host.kind(target)) !== undefined) {
      const there = await host.readFile(target, file.bytes.length + 1).catch(() => undefined);
      if (!there || !sameBytes(there, file.bytes)) {
        warnings.push(packagedPathTakenMessage(file.namedBy, target));
        continue;
      }
    }
    writable.push(file);
  }
  return { files: writable, warnings };
}
