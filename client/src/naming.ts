import * as fs from 'node:fs';
import * as path from 'node:path';
import type * as vscode from 'vscode';
import { missingFolders } from '../../common/src/atomic';

/**
 * One naming convention for what flattening makes, used by Flatten to .xosc and by the preview
 * alike: `<package>.flattened.xosc`, where the package is the `.mosc`, or the folder of a
 * `main.xosc`; any other scenario keeps its own name. The suffix keeps the output from ever
 * taking the name of a scenario that `<package>.xosc` could already be.
 */
export const FLATTENED_SUFFIX = '.flattened.xosc';

/** The name of the package (or scenario) a target stands for: a folder, a `.mosc`, a `main.xosc` in either, or a plain `.xosc`. */
export function packageNameOf(target: vscode.Uri, isFolder = false): string {
  const base = path.posix.basename(target.path);
  if (isFolder) return base;
  if (/\.mosc$/i.test(base)) return base.slice(0, -'.mosc'.length);
  if (base.toLowerCase() === 'main.xosc') {
    const parent = path.posix.basename(path.posix.dirname(target.path));
    if (parent) return parent.replace(/\.mosc$/i, '');
  }
  return base.replace(/\.xosc$/i, '');
}

export function flattenedName(target: vscode.Uri, isFolder = false): string {
  return `${packageNameOf(target, isFolder)}${FLATTENED_SUFFIX}`;
}

/** `main.xosc`, or `main-2.xosc`… when taken: a name that is free in the folder (`base` instead of `main` when given). */
export function freeScenarioName(folder: string, exists: (file: string) => boolean = fs.existsSync, base = 'main'): string {
  for (let number = 1; ; number++) {
    const name = number === 1 ? `${base}.xosc` : `${base}-${number}.xosc`;
    if (!exists(path.join(folder, name))) return name;
  }
}

/** The file name a user typed, `.xosc` added when it has no extension at all (`encounter` for encounter.xosc). */
export function scenarioFileName(typed: string): string {
  const trimmed = typed.trim();
  return trimmed && !/[\\/]/.test(trimmed) && path.extname(trimmed) === '' && !trimmed.startsWith('.') ? `${trimmed}.xosc` : trimmed;
}

/** Why a file name (as scenarioFileName reads it) will not do in the folder, or undefined when it will. */
export function fileNameProblem(folder: string, name: string, exists: (file: string) => boolean = fs.existsSync): string | undefined {
  const trimmed = scenarioFileName(name);
  if (/[\\/]/.test(trimmed) || trimmed === '.' || trimmed === '..') return 'A file name, without folders';
  if (!trimmed.toLowerCase().endsWith('.xosc') || trimmed.length <= '.xosc'.length) return 'The name must end in .xosc';
  if (exists(path.join(folder, trimmed))) return `${trimmed} exists already; choose another name`;
  return undefined;
}

/** A file a command writes anew: its absolute path and its text. */
export interface NewFile {
  path: string;
  text: string;
}

/**
 * Writes new files, making their folders, never over a file ('wx': not even one that appeared since its name was
 * checked). When one cannot be written, the files and folders written before it are removed again, so the disk is
 * left as it was, and the error names the file.
 */
export async function writeNewFiles(files: NewFile[]): Promise<string[]> {
  const written: string[] = [];
  const madeFolders: string[] = [];
  let current: NewFile | undefined;
  let writing = false;
  try {
    for (const file of files) {
      current = file;
      writing = false;
      const folders = missingFolders(path.dirname(file.path));
      await fs.promises.mkdir(path.dirname(file.path), { recursive: true });
      madeFolders.push(...folders);
      writing = true;
      await fs.promises.writeFile(file.path, file.text, { encoding: 'utf8', flag: 'wx' });
      written.push(file.path);
    }
    return written;
  } catch (error) {
    const leftBehind: string[] = [];
    for (const file of written) await fs.promises.rm(file, { force: true }).catch(() => leftBehind.push(file));
    // Innermost first, and only when empty: a folder that holds anything else is not ours to remove.
    for (const folder of madeFolders.reverse()) await fs.promises.rmdir(folder).catch(() => leftBehind.push(folder));
    const name = current?.path ?? '';
    const exists = writing && (error as NodeJS.ErrnoException).code === 'EEXIST';
    const why = exists ? `${name} exists already and is left as it was` : `could not write ${name}: ${(error as Error).message}`;
    const undone =
      written.length === 0
        ? ''
        : leftBehind.length === 0
          ? `; removed again: ${written.join(', ')}`
          : `; could not remove ${leftBehind.join(', ')}`;
    throw new Error(why + undone, { cause: error });
  }
}
