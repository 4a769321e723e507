import * as fs from 'node:fs';
import * as path from 'node:path';
import type * as vscode from 'vscode';

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

/** Why a file name will not do in the folder, or undefined when it will. */
export function fileNameProblem(folder: string, name: string, exists: (file: string) => boolean = fs.existsSync): string | undefined {
  const trimmed = name.trim();
  if (!trimmed.toLowerCase().endsWith('.xosc') || trimmed.length <= '.xosc'.length) return 'The name must end in .xosc';
  if (/[\\/]/.test(trimmed) || trimmed === '.' || trimmed === '..') return 'A file name, without folders';
  if (exists(path.join(folder, trimmed))) return `${trimmed} exists already; choose another name`;
  return undefined;
}
