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
