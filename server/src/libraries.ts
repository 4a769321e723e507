import * as fs from 'node:fs';
import * as path from 'node:path';
import { splitScenarioPath } from '../../common/src/scenarioPath';
import { LibraryFolder } from './core/sources';

/**
 * `library/` of the project this program runs from (the nearest folder above it with a package.json: the
 * repository for `dist/` and for the sources, the extension's folder for the .vsix), the library shipped with it.
 */
export function builtInLibraryFolder(from: string = __dirname): string | undefined {
  for (let folder = from, level = 0; level < 4; folder = path.dirname(folder), level++) {
    if (fs.existsSync(path.join(folder, 'package.json'))) {
      const library = path.join(folder, 'library');
      return fs.existsSync(library) ? library : undefined;
    }
  }
  return undefined;
}

/**
 * The libraries `library:NAME` is looked up in, in order: the user's folders (as given, then SCENARIO_LIBRARY_PATH's),
 * then the built-in library; a module of the user's hides a built-in one of the same name.
 */
export function libraryFolders(
  userFolders: readonly string[],
  environment: Readonly<Record<string, string | undefined>> = process.env,
  builtIn: string | undefined = builtInLibraryFolder(),
): LibraryFolder[] {
  const user = [...userFolders.map((folder) => path.resolve(folder)), ...splitScenarioPath(environment.SCENARIO_LIBRARY_PATH)];
  const folders: LibraryFolder[] = [];
  for (const folder of user) if (!folders.some((known) => known.folder === folder)) folders.push({ folder, label: 'user' });
  if (builtIn && !folders.some((known) => known.folder === builtIn)) folders.push({ folder: builtIn, label: 'built-in' });
  return folders;
}
