import { Hover, MarkupKind } from 'vscode-languageserver/node';
import { attributesSetBy, describeGroup, groupLinkOf, keyMatchOf, linkOf, overridablePlace, Place, resolvedTarget } from '../analysis';
import { ancestor, attributeAt } from '../cursor';
import { displayRef, SourceRef } from '../core/sources';
import { OverridableAttribute } from '../core/keys';
import { ManeuverGroupInfo } from '../core/model';
import { code, escapeMarkdown } from '../markdown';
import { Workspace } from '../workspace';
import { schemaHover } from './schemaHover';
import { assignmentHover } from './catalogs';
import { parameterHover } from './parameters';

function where(workspace: Workspace, place: Place | undefined): string {
  if (!place) return 'an unknown place';
  return code(`${displayRef(place.ref, workspace.folders[0])}:${place.range.start.line + 1}`);
}

function defaultOf(target: OverridableAttribute): string {
  return target.defaultValue === undefined ? '(no default value)' : code(target.defaultValue);
}

function groupSummary(title: string, group: ManeuverGroupInfo): string {
  const lines = describeGroup(group);
  return [title, '', ...(lines.length ? lines : ['(no maneuvers)'])].join('\n');
}

/** Hover for the modular extension, else what the OpenSCENARIO schema says of the element or attribute name. */
export async function hover(workspace: Workspace, ref: SourceRef, offset: number): Promise<Hover | null> {
  return (await modularHover(workspace, ref, offset)) ?? schemaHover(workspace, ref, offset);
}

/** Hover for keys (default, effective value and where each comes from) and for references (what the group does). */
async function modularHover(workspace: Workspace, ref: SourceRef, offset: number): Promise<Hover | null> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return null;
  const semantic = source.semantics ? (assignmentHover(workspace, source.semantics, offset) ?? (await parameterHover(workspace, source.semantics, offset))) : undefined;
  if (semantic) return { contents: { kind: MarkupKind.Markdown, value: semantic.markdown }, range: model.document.lines.range(semantic.start, semantic.end) };
  const hit = attributeAt(model.document, offset);
  if (!hit) return null;
  const { element, attribute } = hit;
  const range = model.document.lines.range(attribute.valueStart, attribute.valueEnd);
  const reply = (value: string): Hover => ({ contents: { kind: MarkupKind.Markdown, value }, range });

  if (element.name === 'ScenarioReference' && attribute.name === 'scenarioFileName') {
    const link = linkOf(source, element);
    if (!link) return null;
    const target = resolvedTarget(link.resolution);
    if (!target || !link.source?.model) return reply(`${code(attribute.value)} does not resolve`);
    const groups = link.source.model.groups.map((group) => `- ${escapeMarkdown(group.name)}`);
    // The file name is what the attribute already shows: name only where it was found.
    return reply([`found at ${code(displayRef(target, workspace.folders[0]))}`, '', 'ManeuverGroups:', ...groups].join('\n'));
  }
  if (element.name === 'ManeuverGroupReference' && attribute.name === 'maneuverGroupName') {
    const reference = ancestor(element.parent, 'ScenarioReference');
    const link = reference ? linkOf(source, reference) : undefined;
    const group = link ? groupLinkOf(link, element) : undefined;
    if (!link?.source || !group?.target) return null;
    return reply(groupSummary(`ManeuverGroup **${escapeMarkdown(group.target.name)}** of ${code(link.info.fileName)} (${group.overridable.length} overridable attributes)`, group.target));
  }
  if (element.name === 'ParameterReference' && attribute.name === 'key') {
    const found = keyMatchOf(source, element);
    const linkedSource = found?.link.source;
    const plan = found?.group.plan;
    if (!found || !linkedSource || !plan) return null;
    const { group, match } = found;
    const key = code(attribute.value);
    if (match.targets.length === 0) return reply(`key ${key} overrides nothing in group ${code(group.info.name)}`);
    const sets = attributesSetBy(group, match);
    const lines = [sets.length > 0 ? `key ${key} sets ${sets.length} attribute${sets.length === 1 ? '' : 's'}:` : `key ${key} sets nothing: a more specific key sets every attribute it matches`];
    if (sets.length > 0) lines.push('');
    for (const target of sets) {
      const declared = where(workspace, overridablePlace(linkedSource, target));
      lines.push(`- ${code(`${target.path.join('.')}.${target.attributeName}`)}: default ${defaultOf(target)} declared at ${declared}; takes effect: ${code(match.parameter.value)} (this key)`);
    }
    const taken = match.targets.filter((target) => !sets.includes(target));
    if (taken.length > 0) lines.push('', `Matched, but set by a more specific key:`, '');
    for (const target of taken) {
      const applied = plan.applied.get(target);
      const by = applied ? `${code(applied.value)} from ${code(applied.key)} on line ${model.document.lines.positionAt(applied.element.start).line + 1}` : 'its default';
      lines.push(`- ${code(`${target.path.join('.')}.${target.attributeName}`)}: ${by}`);
    }
    return reply(lines.join('\n'));
  }
  if (attribute.name === 'entityRef') {
    const entity = model.entities.find((candidate) => candidate.name === attribute.value);
    return reply(entity ? `entity ${code(entity.name)} (${entity.element.children[0]?.name ?? 'ScenarioObject'})` : `entity ${code(attribute.value)} is not declared in this file`);
  }
  return null;
}
