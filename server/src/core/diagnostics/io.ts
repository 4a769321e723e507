import { defineDiagnostic, ProblemWording } from './definition';

/** A file that cannot be read: `message` says which and why (the file system's error, or the reader's). */
export function ioWording(message: string, hint?: string): ProblemWording<'io'> {
  return { severity: 'error', code: 'io', message, hint };
}

/** A folder given where pack takes a file. */
export function packFolderWording(input: string): ProblemWording<'io'> {
  return ioWording(`${input} is a folder; pack a folder with 'modular2simple pack FOLDER -o OUT.mosc'`);
}

/** A folder to pack that holds no main.xosc (`folder` as messages show it). */
export function notUnpackedPackageWording(folder: string): ProblemWording<'io'> {
  return ioWording(`${folder} holds no main.xosc, so it is not an unpacked package`, 'a package folder must hold main.xosc');
}

export const IO = defineDiagnostic({
  code: 'io',
  rule: { description: 'The file can be read.' },
  severity: 'error',
});
