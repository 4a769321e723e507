import { rebasePaths } from '../flatten/rebase';
import { FileKind, nodeFileSystem } from '../sources';
import { RebasePaths } from './types';

/**
 * Rebases a scenario written in `fromDirectory` (flatten's own rebasing, SPEC 11.6) so that, written in
 * `toDirectory`, it reaches the same roads and catalogs: the edits of its attribute values. One rebaser serves one run: it looks at each
 * path on disk once, as every scenario of a library names the same roads and catalog folders.
 */
export function pathRebaser(): RebasePaths {
  const kinds = new Map<string, Promise<FileKind>>();
  const kindOf = (diskPath: string): Promise<FileKind> => {
    let known = kinds.get(diskPath);
    if (!known) {
      known = nodeFileSystem.kind(diskPath);
      kinds.set(diskPath, known);
    }
    return known;
  };
  return async (document, fromDirectory, toDirectory) => {
    if (fromDirectory === toDirectory) return [];
    return (await rebasePaths({ document, baseOf: () => fromDirectory, outputDirectory: toDirectory, kindOf })).edits;
  };
}
