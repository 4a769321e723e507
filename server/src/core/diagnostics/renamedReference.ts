import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isSuggestion, ProblemWording } from './definition';

/** A reference to `written`, which flattening renamed to each of `renamed`. */
export function renamedReferenceWording(written: string, renamed: readonly string[]): ProblemWording<'renamed-reference'> {
  return {
    severity: 'error',
    code: 'renamed-reference',
    message: `flattening renamed '${written}' to ${renamed.map((name) => `'${name}'`).join(', ')}, so this reference names nothing in the flattened scenario`,
    hint: `refer to the imported group by its flattened name${renamed.length === 1 ? ` '${renamed[0]}'` : ''}`,
  };
}

/** A reference to a group that flattening renames: the new name. */
export const RENAMED_REFERENCE = defineDiagnostic({
  code: 'renamed-reference',
  rule: { description: 'A reference to a group that flattening renames is updated.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['renamed-reference'] => isSuggestion(value),
});
