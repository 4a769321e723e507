import * as path from 'node:path';

/**
 * Disk paths in Windows form: a drive letter (`C:\scenarios`, `C:/scenarios`) or a UNC share
 * (`\\server\share`). They follow Windows rules on any platform, so that the same paths (and their
 * tests) mean the same thing wherever the code runs.
 */
export function isWindowsPath(diskPath: string): boolean {
  return /^[a-zA-Z]:[\\/]/.test(diskPath) || /^\\\\[^\\]/.test(diskPath);
}

/** The path operations that fit a disk path: win32 for Windows forms, else the platform's own. */
export function pathsFor(diskPath: string): path.PlatformPath {
  return isWindowsPath(diskPath) ? path.win32 : path;
}

/**
 * A disk path split into its root (`/`, `C:\`, `\\server\share\`) and its names. Windows paths split
 * on both separators; POSIX paths only on `/` (a backslash is an ordinary character there).
 */
export function splitDiskPath(diskPath: string): { root: string; names: string[] } {
  const paths = pathsFor(diskPath);
  const resolved = paths.resolve(diskPath);
  const root = paths.parse(resolved).root;
  const separators = paths.sep === '\\' ? /[\\/]/ : /\//;
  return { root, names: resolved.slice(root.length).split(separators).filter((name) => name.length > 0) };
}
