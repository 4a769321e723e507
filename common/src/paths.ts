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
 * Whether `child` is `folder` or lies under it, by the rules of `folder`'s own path form (case-insensitive for
 * Windows paths, where the editor writes `c:` and Node `C:`). Both are absolute.
 */
export function isInsideFolder(child: string, folder: string): boolean {
  const paths = pathsFor(folder);
  const relative = paths.relative(folder, child);
  return relative === '' || (relative !== '..' && !relative.startsWith('..' + paths.sep) && !paths.isAbsolute(relative));
}

/** Whether `child` is one of `folders` or lies under one of them. */
export function insideFolders(child: string, folders: readonly string[]): boolean {
  return folders.some((folder) => isInsideFolder(child, folder));
}

/**
 * The Python that modular2simple.carla.python names, for *Check in CARLA ScenarioRunner* and *Run in CARLA*: a
 * name (`python3`) is looked up on PATH when it starts; a path written relative (`venv/bin/python`) is one in
 * ScenarioRunner's folder, made absolute here so that neither the language server's working directory nor how
 * VS Code starts a task's program decides which file runs.
 */
export function carlaPython(written: string | undefined, scenarioRunner: string): string {
  const python = written?.trim() || 'python3';
  const isPath = python.includes('/') || python.includes(path.sep);
  return isPath && !path.isAbsolute(python) && scenarioRunner ? path.resolve(scenarioRunner, python) : python;
}
