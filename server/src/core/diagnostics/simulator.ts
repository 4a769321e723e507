import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isOptionalString, isRecord, isString } from './definition';

function isSimulatorData(value: unknown): value is ProblemDataByCode['simulator'] {
  if (!isRecord(value) || !isOptionalString(value.suggestion)) return false;
  if (value.exportMaps !== undefined && typeof value.exportMaps !== 'boolean') return false;
  return value.rename === undefined || (isRecord(value.rename) && isString(value.rename.from) && isString(value.rename.to));
}

function baseName(file: string): string {
  return file.slice(Math.max(file.lastIndexOf('/'), file.lastIndexOf('\\')) + 1);
}

/**
 * What the selected simulator does not run as written (core/profiles/, core/semantics/checks/carla.ts): an
 * error where it refuses the scenario, a warning where it runs it otherwise. Its fixes: the one edit that
 * answers it where there is one (the value of a `${...}`, revMinor="0"), the catalog file's rename, and
 * the export for CARLA where the export maps it.
 */
export const SIMULATOR = defineDiagnostic({
  code: 'simulator',
  rule: { description: 'The selected simulator runs what the file uses.' },
  severity: 'warning',
  isData: isSimulatorData,
  fixes: ({ data, range }) => [
    ...(data?.suggestion !== undefined
      ? [{ title: `Write '${data.suggestion}'`, edits: [{ place: 'document' as const, range, newText: data.suggestion }], preferred: true }]
      : []),
    ...(data?.rename
      ? [{ title: `Rename ${baseName(data.rename.from)} to ${baseName(data.rename.to)}`, edits: [], rename: data.rename, preferred: true }]
      : []),
    ...(data?.exportMaps ? [{ title: 'Export for CARLA…', edits: [], command: 'export-for-carla' as const }] : []),
  ],
});
