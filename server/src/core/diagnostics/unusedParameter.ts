import { defineDiagnostic, ProblemWording } from './definition';

export function unusedParameterWording(name: string): ProblemWording<'unused-parameter'> {
  return { severity: 'hint', code: 'unused-parameter', message: `parameter '${name}' is never used` };
}

/** A declared parameter nothing uses: shown faded. */
export const UNUSED_PARAMETER = defineDiagnostic({
  code: 'unused-parameter',
  rule: { description: 'A declared parameter is used.' },
  severity: 'hint',
  unnecessary: true,
});
