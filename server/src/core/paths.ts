import { pathsFor } from '../../../common/src/paths';

export { isWindowsPath, pathsFor } from '../../../common/src/paths';

/**
 * A disk path split into its root (`/`, `C:\`, `\\server\share\`) and its names. Windows paths split
 * on both separators; POSIX paths only on `/` (a backslash is an ordinary character there).
 */
export function splitDiskPath(diskPath: string): { root: string; names: string[] } {
  const paths = pathsFor(diskPath);
  const resolved = paths.resolve(diskPath);
  const root = paths.parse(resolved).root;
  const separators = paths.sep === '\\' ? /[\\/]/ : /\//;
  return {
    root,
    names: resolved
      .slice(root.length)
      .split(separators)
      .filter((name) => name.length > 0),
  };
}
