import * as fs from 'node:fs';
import * as path from 'node:path';

/** Scenario files: what `check` and the workspace index collect. */
export const SCENARIO_FILE = /\.(xosc|mosc)$/i;

/**
 * How a walk differs between its users. Folders whose name starts with '.' are never entered.
 * The CLI walks the folders a user named and reports what it cannot read; the workspace index walks a
 * whole editor workspace (build output, test runner caches) and must never fail, hence its options.
 */
export interface WalkOptions {
  /** The file names collected. */
  files: RegExp;
  /** Folder names not entered (besides those starting with '.'). */
  skipFolders: ReadonlySet<string>;
  /** Whether files whose name starts with '.' are skipped too (the CLI's rule; the index keeps them). */
  skipDotFiles: boolean;
  /** Whether only regular files count; otherwise any entry that is not a folder (a link to a file) does. */
  regularFilesOnly: boolean;
  /** An unreadable folder: 'throw' reports it, 'skip' goes on without it. */
  unreadable: 'throw' | 'skip';
  /** Whether the list is sorted; otherwise it is in the order the folders were read. */
  sorted: boolean;
  /** At most this many files. */
  limit?: number;
}

/** The files below `folders` (depth first, a folder's entries in the order the system lists them). */
export async function walkFiles(folders: string[], options: WalkOptions): Promise<string[]> {
  const found: string[] = [];
  const limit = options.limit ?? Infinity;
  const visit = async (folder: string): Promise<void> => {
    let entries: fs.Dirent[];
    try {
      entries = await fs.promises.readdir(folder, { withFileTypes: true });
    } catch (error) {
      if (options.unreadable === 'throw') throw error;
      return;
    }
    for (const entry of entries) {
      if (found.length >= limit) return;
      const full = path.join(folder, entry.name);
      if (entry.isDirectory()) {
        if (!entry.name.startsWith('.') && !options.skipFolders.has(entry.name)) await visit(full);
      } else if (
        (options.skipDotFiles ? !entry.name.startsWith('.') : true) &&
        (options.regularFilesOnly ? entry.isFile() : true) &&
        options.files.test(entry.name)
      ) {
        found.push(full);
      }
    }
  };
  for (const folder of folders) {
    if (found.length >= limit) break;
    await visit(folder);
  }
  return options.sorted ? found.sort() : found;
}
