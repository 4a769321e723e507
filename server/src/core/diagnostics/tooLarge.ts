import { defineDiagnostic, ProblemWording } from './definition';

/**
 * The flattened `file` (as messages show it) would pass the bound of `limit` characters, `projected` counted so far,
 * the groups imported through `chain` multiplying at each level.
 */
export function tooLargeWording(file: string, limit: number, projected: number, chain: string): ProblemWording<'too-large'> {
  return {
    severity: 'error',
    code: 'too-large',
    message: `the flattened ${file} would exceed ${limit.toLocaleString('en-US')} characters (${projected.toLocaleString('en-US')} so far): groups imported through ${chain} multiply at each level`,
    hint: 'import fewer copies, or raise the bound with --max-output-size',
  };
}

export const TOO_LARGE = defineDiagnostic({
  code: 'too-large',
  rule: { description: 'A file or a flattened result stays within the size bounds.' },
  severity: 'error',
});
