import { sameValue } from '../flatten/carry';
import { parseScenario } from '../model';
import { Declaration, semanticModelOf } from '../semantics';
import { isWithin, XmlDocument, XmlElement } from '../xml';
import { ParsedInput, PooledGroup } from './types';

/** The declaration each parameter used inside `group` resolves to, where that lies outside it (what flattening carries, SPEC 11). */
function declarationsReadBy(document: XmlDocument, group: XmlElement): Map<string, Declaration> {
  const found = new Map<string, Declaration>();
  for (const use of semanticModelOf(document).uses) {
    if (!use.declaration || !isWithin(use.element, group) || isWithin(use.declaration.element, group)) continue;
    if (!found.has(use.name)) found.set(use.name, use.declaration);
  }
  return found;
}

/**
 * For each group of a simple scenario (by its index in `groups`), the parameters it reads whose declaration
 * there differs from the one some use's own scenario gives: flattening that use's main would keep the main's
 * and warn (parameter-conflict), so the group must read a copy of its own, which each use overrides.
 */
export function parameterConflicts(text: string, groups: readonly PooledGroup[], inputs: readonly ParsedInput[]): Map<number, Set<string>> {
  const model = parseScenario(text);
  const conflicts = new Map<number, Set<string>>();
  groups.forEach((group, index) => {
    const written = model.groups.find((candidate) => candidate.name === group.groupName);
    if (!written) return;
    const inFile = declarationsReadBy(model.document, written.element);
    for (const occurrence of group.occurrences) {
      for (const [name, declaration] of declarationsReadBy(inputs[occurrence.input].document, occurrence.group.element)) {
        const shared = inFile.get(name);
        if (shared && !sameValue(shared, declaration)) conflicts.set(index, new Set([...(conflicts.get(index) ?? []), name]));
      }
    }
  });
  return conflicts;
}

/** `$name` (alone or inside a `${...}` expression), not the start of a longer name. */
function usePattern(name: string): RegExp {
  return new RegExp(`\\$${name.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}(?!\\w)`, 'g');
}

/**
 * `value` reading `copy` wherever it reads `$name`. A `parameterRef` is left alone (a ParameterAssignment's names the
 * catalog entry's parameter): a group naming the parameter so keeps sharing no file, as the flatten-back check finds.
 */
export function readingCopy(value: string, name: string, copy: string): string {
  return value.replace(usePattern(name), () => `$${copy}`);
}

/** The name of a group's own copy of `name` in a simple scenario: none of `taken` (case-insensitive). */
export function copyName(name: string, groupName: string, taken: ReadonlySet<string>): string {
  const stem = `${name}_${groupName.replace(/\W+/g, '_')}`;
  let candidate = stem;
  for (let n = 2; taken.has(candidate.toLowerCase()); n++) candidate = `${stem}_${n}`;
  return candidate;
}
