import { defineDiagnostic, ProblemWording } from './definition';

/** A chain of references (`chain`, as the report shows it) longer than the depth bound. */
export function tooDeepWording(maxDepth: number, chain: string): ProblemWording<'too-deep'> {
  return {
    severity: 'error',
    code: 'too-deep',
    message: `references nest deeper than ${maxDepth} files: ${chain}`,
    hint: 'flatten the inner packages first, or raise the bound with --max-depth',
  };
}

export const TOO_DEEP = defineDiagnostic({
  code: 'too-deep',
  rule: { description: 'A chain of references stays within the depth bound.' },
  severity: 'error',
});
