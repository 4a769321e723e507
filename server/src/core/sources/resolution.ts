import { pathsFor } from '../paths';
import { SourceRef } from './ref';

export type Resolution =
  | { kind: 'scenario'; ref: SourceRef; via: LookupPlace['via'] }
  | {
      kind: 'package';
      /** The `.mosc` file (or entry), or the folder standing for it. */
      packageRef: SourceRef;
      main: SourceRef;
      folder: boolean;
      via: LookupPlace['via'];
      /** Set when a `NAME.xosc` was found only as the package `NAME.mosc`. */
      fallbackFrom?: string;
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
  via: 'package' | 'folder' | 'scenarioPath' | 'parent';
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
