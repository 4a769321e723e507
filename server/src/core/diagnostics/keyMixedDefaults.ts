import { defineDiagnostic, ProblemWording } from './definition';

/** A key that sets `count` attributes whose defaults differ (`defaults`: each default and how many have it) to `value`. */
export function keyMixedDefaultsWording(
  key: string,
  count: number,
  defaults: ReadonlyMap<string, number>,
  value: string,
): ProblemWording<'key-mixed-defaults'> {
  const listed = [...defaults].map(([each, times]) => `'${each}' (${times}×)`);
  return {
    severity: 'warning',
    code: 'key-mixed-defaults',
    message: `key '${key}' sets ${count} attributes whose defaults differ: ${listed.join(', ')}; all of them get '${value}'`,
    hint: 'write a longer key that reaches only the attributes you mean, or list the attribute in parameterAttributes only where it should be overridden',
  };
}

/** The related location's note: one of the attributes the key sets. */
export function keyMixedDefaultsNote(attributeName: string, defaultValue: string | undefined): string {
  return `'${attributeName}' with default '${defaultValue}'`;
}

export const KEY_MIXED_DEFAULTS = defineDiagnostic({
  code: 'key-mixed-defaults',
  rule: { description: 'The attributes one key sets share one default.' },
  severity: 'warning',
});
