import { defineDiagnostic, ProblemWording } from './definition';

/** A package that cannot be read: `message` is the package reader's. */
export function badPackageWording(message: string, hint?: string): ProblemWording<'bad-package'> {
  return { severity: 'error', code: 'bad-package', message, hint };
}

/** A reference to `fileName` whose package cannot be read: `reason` is the package reader's message. */
export function unreadablePackageWording(fileName: string, reason: string, hint: string | undefined): ProblemWording<'bad-package'> {
  return badPackageWording(`cannot look up '${fileName}': ${reason}`, hint);
}

export const BAD_PACKAGE = defineDiagnostic({
  code: 'bad-package',
  rule: { description: 'A .mosc package is a readable ZIP archive holding main.xosc.' },
  severity: 'error',
});
