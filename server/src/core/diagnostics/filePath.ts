import { defineDiagnostic, ProblemWording } from './definition';

/** What pack found about a path of a packed file that reaches outside the package. */
export interface OutsidePackageFacts {
  kind: 'file' | 'directory';
  /** The path on disk it reaches. */
  disk: string;
  /** The path as written in the package, relative to the package's folder, where pack rewrote it. */
  rewritten?: string;
  /** The path as written in the file. */
  written: string;
  /** Whether it names a parameter, so it is left as written (SPEC 11.6). */
  viaParameter: boolean;
}

/** A path the package does not carry: pack warns, and the client offers to pack again storing it inside. */
export function reachesOutsidePackageWording({
  kind,
  disk,
  rewritten,
  written,
  viaParameter,
}: OutsidePackageFacts): ProblemWording<'file-path'> {
  return {
    severity: 'warning',
    code: 'file-path',
    message: `the package reaches ${kind === 'directory' ? 'the folder' : 'the file'} ${disk} outside itself${rewritten !== undefined ? ` (written '${rewritten}', relative to the package's folder)` : ''}; the package does not run without it`,
    // A path naming a parameter is never rewritten (SPEC 11.6), so not carried either.
    hint: viaParameter
      ? `'${written}' names a parameter, so it is left as written: --self-contained stores the file only where the parameter's value names it inside the package (no '..', not absolute); otherwise write the path itself`
      : 'pack with --self-contained to store it inside the package',
  };
}

/** A path of a flattened package naming `entry` inside it, which standard output cannot carry. */
export function packagedPathOnStandardOutputWording(written: string, entry: string): ProblemWording<'file-path'> {
  return {
    severity: 'warning',
    code: 'file-path',
    message: `'${written}' names ${entry} inside the package, which standard output cannot carry; it is left as written`,
    hint: "flatten to a file: the package's files are then written beside it",
  };
}

/** A `$parameter` path (`written`) naming a package file whose copy beside the output would replace another file (`taken`), which the output then reaches. */
export function packagedPathTakenMessage(written: string, taken: string): string {
  return (
    `'${written}' names a file of the package, whose copy would go to ${taken}, which holds another file: it is not replaced, so ` +
    'the output reaches that file instead (write the output to another folder, or move that file away and write it again)'
  );
}

/**
 * A catalog folder (`written`) that does not resolve from `from` and was found in `folders` through the scenario path: it is
 * written as it stands (SPEC 11.6), and esmini looks a catalog up as NAME.xosc in each `--path` folder (CommonMini.cpp LocateFile).
 */
export function catalogFoundThroughSearchPathMessage(written: string, from: string, folders: readonly string[]): string {
  return (
    `catalog folder '${written}' does not resolve from ${from}; it was found only through the scenario path (${folders.join(', ')}). ` +
    'A path found through a search path is written as it stands (SPEC 11.6), so esmini loads its catalogs only when run with ' +
    `${folders.map((folder) => `--path ${folder}`).join(' ')} (or write the path so that it resolves from the scenario's own folder)`
  );
}

/** A path the output cannot name from where it is written: `message` is the rebasing's finding. */
export function unrebasedPathWording(message: string): ProblemWording<'file-path'> {
  return {
    severity: 'warning',
    code: 'file-path',
    message,
    hint: 'declare the parameter with an absolute path, or write the output beside this file',
  };
}

/** Where esmini looks a catalog entry's controller File up (ScenarioReader.cpp parseOSCObjectController): how both wordings start. */
function controllerFileLookup(entry: string, written: string): string {
  return `catalog entry '${entry}' names its controller File ${written}, which esmini looks up from the working folder, then from the folder of the scenario that uses the entry`;
}

/**
 * A catalog controller entry's File written as a relative path (`written`, quoted, with the value a parameter gives it), which esmini looks up from the folder of the
 * scenario that uses the entry, where it names `disk`: the catalog is not part of the output, so nothing rebases it. `main`: the
 * main file that scenario is flattened from, when the reference lies in a group it imports from another file.
 */
export function catalogControllerFileWording(
  entry: string,
  written: string,
  disk: string,
  output: string | undefined,
  main?: string,
): ProblemWording<'file-path'> {
  return {
    severity: 'warning',
    code: 'file-path',
    message:
      `${controllerFileLookup(entry, written)} (not the catalog's): from ${main === undefined ? 'here' : `the folder of ${main}, which imports this group,`} it names ${disk}; ` +
      `${output === undefined ? 'the output on standard output' : `the output in ${output}`} may reach another file or none`,
    hint: `write the File's path absolute in the catalog entry, or name it through a parameter this reference assigns, or write the output beside ${main ?? 'this file'}`,
  };
}

/**
 * A catalog controller entry's relative File (`written`, quoted, with the value a parameter gives it) used from a group that
 * `main` imports from a file in another folder or package: esmini reads it from the main's folder, where it names no file
 * (`missing`), while the file lies beside the imported file (`beside`), so the flattened scenario runs without it.
 */
export function importedControllerFileWording(
  entry: string,
  written: string,
  main: string,
  missing: string,
  beside: string,
): ProblemWording<'file-path'> {
  return {
    severity: 'warning',
    code: 'file-path',
    message:
      `${controllerFileLookup(entry, written)}: from the folder of ${main}, which imports this group, it names ${missing}, ` +
      `which does not exist; the file lies beside this file (${beside}), so the flattened scenario runs without the controller's File`,
    hint: `copy ${beside} to ${missing}, or write the File's path absolute in the catalog entry`,
  };
}

export const FILE_PATH = defineDiagnostic({
  code: 'file-path',
  rule: { description: 'A file path of a written scenario names, from where it is written, the file its source named (SPEC 11.6).' },
  severity: 'warning',
});
