import * as fs from 'node:fs';
import * as path from 'node:path';

export type EsminiLocation = { found: true; program: string } | { found: false; message: string };

/** What to tell a user who has no esmini: where it is looked for and how to get it. */
export const ESMINI_MISSING_HELP =
  'esmini was not found. It is looked for in the setting modular2simple.esmini.path (the CLI: --esmini PATH), then on PATH, ' +
  'then in .cache/esmini/bin of this project (where npm start builds it). ' +
  'Get it from https://github.com/esmini/esmini/releases (bin/esmini), or build it headless from the source package shipped ' +
  'beside this project: bash ../shared/esmini/build.sh .cache/esmini (npm start does this), or point modular2simple.esmini.path at an esmini.';

const PROGRAM_NAMES = process.platform === 'win32' ? ['esmini.exe', 'esmini'] : ['esmini'];

function isExecutableFile(candidate: string): boolean {
  try {
    if (!fs.statSync(candidate).isFile()) return false;
    if (process.platform !== 'win32') fs.accessSync(candidate, fs.constants.X_OK);
    return true;
  } catch {
    return false;
  }
}

/** The program in a configured path: the file itself, or `esmini` in that folder or in its `bin/`. */
function programAt(configured: string): string | undefined {
  const candidates = [
    configured,
    ...PROGRAM_NAMES.map((name) => path.join(configured, name)),
    ...PROGRAM_NAMES.map((name) => path.join(configured, 'bin', name)),
  ];
  return candidates.find(isExecutableFile);
}

/**
 * `.cache/esmini/bin` of the project this program runs from (the nearest folder above it with a package.json: the
 * repository for `dist/` and for the sources), where `npm start` and the test setup build esmini.
 */
export function projectEsminiFolder(from: string = __dirname): string | undefined {
  for (let folder = from, level = 0; level < 4; folder = path.dirname(folder), level++) {
    if (fs.existsSync(path.join(folder, 'package.json'))) return path.join(folder, '.cache', 'esmini', 'bin');
  }
  return undefined;
}

/**
 * Finds esmini: the configured path first (relative to `base`), then every folder of PATH, then `builtFolders`
 * (the esmini `npm start` built). A configured path that holds no esmini is reported rather than silently replaced.
 */
export function locateEsmini(
  configured: string | undefined,
  base: string = process.cwd(),
  searchPath: string | undefined = process.env.PATH,
  builtFolders: readonly string[] = [projectEsminiFolder()].filter((folder) => folder !== undefined),
): EsminiLocation {
  if (configured && configured.trim()) {
    const resolved = path.resolve(base, configured.trim());
    const program = programAt(resolved);
    if (program) return { found: true, program };
    return {
      found: false,
      message: `esmini is not at ${resolved} (setting modular2simple.esmini.path or --esmini). ${ESMINI_MISSING_HELP}`,
    };
  }
  for (const folder of [...(searchPath ?? '').split(path.delimiter), ...builtFolders]) {
    if (!folder) continue;
    for (const name of PROGRAM_NAMES) {
      const candidate = path.join(folder, name);
      if (isExecutableFile(candidate)) return { found: true, program: candidate };
    }
  }
  return { found: false, message: ESMINI_MISSING_HELP };
}
