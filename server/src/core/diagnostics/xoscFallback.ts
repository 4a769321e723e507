import { ProblemDataByCode } from '../problems';
import { changeTo, defineDiagnostic, isRecordOf, isString, ProblemWording } from './definition';

/** The package read for a `NAME.xosc` that does not exist: `NAME.mosc`. */
export function fallbackPackageName(xoscName: string): string {
  return `${xoscName.slice(0, -'.xosc'.length)}.mosc`;
}

/**
 * A `.xosc` that does not exist, read from the flattened package of its name: `used` when flattening,
 * `stored` when packing.
 */
export function xoscFallbackWording(xoscName: string, packageName: string, how: 'used' | 'stored'): ProblemWording<'xosc-fallback'> {
  return {
    severity: 'warning',
    code: 'xosc-fallback',
    message:
      how === 'used'
        ? `'${xoscName}' does not exist; the flattened package '${packageName}' is used in its place`
        : `'${xoscName}' does not exist; the package '${packageName}' is stored for it`,
    hint: `write scenarioFileName="${packageName}"`,
  };
}

/** A `.xosc` that does not exist, read from the flattened package of its name: name the package. */
export const XOSC_FALLBACK = defineDiagnostic({
  code: 'xosc-fallback',
  rule: { description: 'A NAME.xosc reference resolved only through the NAME.mosc fallback.' },
  severity: 'warning',
  deprecated: true,
  isData: (value): value is ProblemDataByCode['xosc-fallback'] =>
    isRecordOf<ProblemDataByCode['xosc-fallback']>(value, { replacement: isString }),
  fixes: ({ data, range }) => (data?.replacement ? [changeTo(range, data.replacement)] : []),
});
