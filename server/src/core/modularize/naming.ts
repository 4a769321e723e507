import { XmlElement } from '../xml';

/** `LaneChangeAction` -> `lane_change`, `SimulationTimeCondition` -> `simulation_time`. */
function snake(name: string, suffix: string): string {
  const stem = name.endsWith(suffix) && name.length > suffix.length ? name.slice(0, -suffix.length) : name;
  return stem
    .replace(/([a-z0-9])([A-Z])/g, '$1_$2')
    .replace(/([A-Z])([A-Z][a-z])/g, '$1_$2')
    .toLowerCase();
}

/** The innermost elements named `*Suffix` (an action inside no other action of its kind below it), in document order, each kind once. */
function innermost(elements: XmlElement[], suffix: string): string[] {
  const names: string[] = [];
  for (const element of elements) {
    if (!element.name.endsWith(suffix) || element.name === suffix) continue;
    if (element.children.some((child) => child.name.endsWith(suffix))) continue;
    const name = snake(element.name, suffix);
    if (!names.includes(name)) names.push(name);
  }
  return names;
}

/**
 * A file stem that says what a group does: its actions in order (`speed_lane_change`), and what
 * starts it (`speed_after_simulation_time`); `no_action` for a group without actions.
 */
export function behaviourName(elements: XmlElement[]): string {
  const actions = innermost(elements, 'Action').filter((name) => name !== 'private' && name !== 'global' && name !== 'user_defined');
  const conditions = innermost(elements, 'Condition');
  const parts = actions.slice(0, 3);
  if (parts.length === 0) parts.push('no_action');
  if (conditions.length > 0) parts.push('after', conditions[0]);
  return parts.join('_').replace(/[^a-z0-9_]/g, '_');
}

/** `stem`, or `stem_2`, `stem_3`, ... : the first not yet in `taken` (compared without case, for case-insensitive file systems). */
export function uniqueName(stem: string, taken: Set<string>): string {
  let name = stem;
  for (let n = 2; taken.has(name.toLowerCase()); n++) name = `${stem}_${n}`;
  taken.add(name.toLowerCase());
  return name;
}
