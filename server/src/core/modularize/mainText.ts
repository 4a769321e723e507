import * as path from 'node:path';
import { applyEdits, TextEdit } from '../flatten/edits';
import { indentationAt } from '../text';
import { attributeValue, escapeAttributeValue } from '../xml';
import { Behaviour, ParsedInput, Use } from './types';

/** A `scenarioFileName` from the main's folder to the simple scenario, with `/` on every platform. */
function referenceName(main: string, file: string): string {
  return path.relative(path.dirname(main), file).split(path.sep).join('/');
}

/** The group that imports a behaviour in place of the group it was extracted from. */
export function referenceGroup(input: ParsedInput, behaviour: Behaviour, use: Use, indent: string, unit: string, eol: string): string {
  const group = use.occurrence.group;
  const actors = group.actor?.parent;
  const q = (value: string) => `"${escapeAttributeValue(value)}"`;
  const maximumExecutionCount = attributeValue(group.element, 'maximumExecutionCount');
  const lines = [
    `<ManeuverGroup${maximumExecutionCount === undefined ? '' : ` maximumExecutionCount=${q(maximumExecutionCount)}`} name=${q(use.outerName)}>`,
    `${unit}<Actors selectTriggeringEntities=${q((actors && attributeValue(actors, 'selectTriggeringEntities')) ?? 'false')}>`,
    `${unit}${unit}<EntityRef entityRef=${q(group.actor ? (attributeValue(group.actor, 'entityRef') ?? '') : '')}/>`,
    `${unit}</Actors>`,
    `${unit}<ScenarioReference scenarioFileName=${q(referenceName(input.output, behaviour.file))}>`,
  ];
  if (use.overrides.length === 0) lines.push(`${unit}${unit}<ManeuverGroupReference maneuverGroupName=${q(behaviour.groupName)}/>`);
  else {
    lines.push(`${unit}${unit}<ManeuverGroupReference maneuverGroupName=${q(behaviour.groupName)}>`);
    for (const override of use.overrides)
      lines.push(`${unit.repeat(3)}<ParameterReference key=${q(override.key)} value=${q(override.value)}/>`);
    lines.push(`${unit}${unit}</ManeuverGroupReference>`);
  }
  lines.push(`${unit}</ScenarioReference>`, '</ManeuverGroup>');
  return lines.map((line, index) => (index === 0 ? line : indent + line)).join(eol);
}

/**
 * The main of one input: its text as written, each extracted group replaced in place (at its
 * indentation) by a group that imports it, its file paths rebased onto the main's folder.
 */
export function mainText(input: ParsedInput, uses: { behaviour: Behaviour; use: Use }[]): string {
  const text = input.text;
  const eol = text.includes('\r\n') ? '\r\n' : '\n';
  const edits: TextEdit[] = uses.map(({ behaviour, use }) => {
    const element = use.occurrence.group.element;
    const indent = indentationAt(text, element.start);
    const firstChild = element.children[0];
    const childIndent = firstChild ? indentationAt(text, firstChild.start) : '';
    const unit = childIndent.startsWith(indent) && childIndent.length > indent.length ? childIndent.slice(indent.length) : '  ';
    return { start: element.start, end: element.end, text: referenceGroup(input, behaviour, use, indent, unit, eol) };
  });
  // The input's rebased paths, but for those inside the groups replaced (their simple scenarios rebase them).
  const outside = input.pathEdits.filter((edit) => !edits.some((group) => edit.start >= group.start && edit.end <= group.end));
  return applyEdits(text, [...edits, ...outside]);
}
