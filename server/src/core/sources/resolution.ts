import { pathsFor } from '../paths';
import { SourceRef } from './ref';

export type Resolution =
  | { kind: 'scenario'; ref: SourceRef; via: LookupPlace['via']; shadowed?: string[] }
  | {
      kind: 'package';
      /** The `.mosc` file (or entry), or the folder standing for it. */
      packageRef: SourceRef;
      main: SourceRef;
      folder: boolean;
      via: LookupPlace['via'];
      /** Set when a `NAME.xosc` was found only as the package `NAME.mosc`. */
      fallbackFrom?: string;
      /** For `library:NAME`: the modules of that name in later libraries, which this one hides. */
      shadowed?: string[];
    }
  /** `searched`: the places looked in, absolute and in order; `suggestion`: the closest name that exists there. */
  | { kind: 'missing'; searched: string[]; hint?: string; suggestion?: string }
  | { kind: 'invalid'; message: string }
  /** The package that should hold the name cannot be read (a broken archive, a bound exceeded). */
  | { kind: 'unreadable'; message: string; hint?: string };

/** One place searched for a referenced name (SPEC 3). */
export interface LookupPlace {
  /** A folder on disk, or a folder inside a package. */
  packageRef: SourceRef | undefined;
  directory: string;
  via: 'package' | 'folder' | 'scenarioPath' | 'parent' | 'library';
}

/** The prefix of a `scenarioFileName` that names a module of the scenario libraries (`library:cut-in`). */
export const LIBRARY_PREFIX = 'library:';

/** A scenario library: a folder whose `.xosc` files are modules, searched for `library:NAME` names. */
export interface LibraryFolder {
  folder: string;
  /** How messages name it: `built-in`, or `user` for a folder of the user's setting or SCENARIO_LIBRARY_PATH. */
  label: string;
}

/** The file name a `library:NAME` stands for (`NAME.xosc`, or NAME as written when it ends in .xosc or .mosc). */
export function libraryFileName(moduleName: string): string {
  return /\.(xosc|mosc)$/i.test(moduleName) ? moduleName : `${moduleName}.xosc`;
}

export interface FolderOptions {
  folder: string;
  scenarioPath: string[];
}

/** Whether `directory` is `folder` or lies below it. */
export function isWithinFolder(directory: string, folder: string): boolean {
  const separator = pathsFor(folder).sep;
  return directory === folder || directory.startsWith(folder.endsWith(separator) ? folder : folder + separator);
}
