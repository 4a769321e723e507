import { Hover, MarkupKind } from 'vscode-languageserver/node';
import { attributesSetBy, describeGroup, overridablePlace, Place, resolvedTarget } from '../analysis';
import { FlatSource } from '../core/flatten';
import { displayRef, SourceRef } from '../core/sources';
import { OverridableAttribute } from '../core/keys';
import { ManeuverGroupInfo, ScenarioModel } from '../core/model';
import { syntacticTarget, Target, targetAt } from '../target';
import { code, escapeMarkdown } from '../markdown';
import { Workspace } from '../workspace';
import { schemaHoverAt } from './schemaHover';
import { assignmentHover } from './catalogs';
import { parameterHover } from './parameters';
import { distributionHover } from './distributions';

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

/** Hover for parameters and the modular extension, else what the OpenSCENARIO schema says of the element or attribute name. */
export async function hover(workspace: Workspace, ref: SourceRef, offset: number): Promise<Hover | null> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return null;
  const target = targetAt(source, offset);
  const distribution = await distributionHover(workspace, ref, offset);
  if (distribution) return distribution;
  return (
    (await modularHover(workspace, source, model, target, offset)) ??
    schemaHoverAt(model.document, workspace.settings.schemaVersion, target)
  );
}

/** Hover for parameters, keys (default, effective value and where each comes from) and references (what the group does). */
async function modularHover(
  workspace: Workspace,
  source: FlatSource,
  model: ScenarioModel,
  target: Target,
  offset: number,
): Promise<Hover | null> {
  const semantics = source.semantics;
  const assignment = semantics && target.kind === 'catalogReference' ? assignmentHover(workspace, semantics, target) : undefined;
  const semantic = assignment ?? (semantics ? await parameterHover(workspace, semantics, target) : undefined);
  if (semantic)
    return {
      contents: { kind: MarkupKind.Markdown, value: semantic.markdown },
      range: model.document.lines.range(semantic.start, semantic.end),
    };
  const syntactic = syntacticTarget(source, target, offset);
  if (syntactic.kind === 'nothing' || syntactic.kind === 'elementName') return null;
  const { attribute } = syntactic.hit;
  const range = model.document.lines.range(attribute.valueStart, attribute.valueEnd);
  const reply = (value: string): Hover => ({ contents: { kind: MarkupKind.Markdown, value }, range });

  switch (syntactic.kind) {
    case 'fileReference': {
      const link = syntactic.link;
      if (!link) return null;
      const resolved = resolvedTarget(link.resolution);
      if (!resolved || !link.source?.model) return reply(`${code(attribute.value)} does not resolve`);
      const groups = link.source.model.groups.map((group) => `- ${escapeMarkdown(group.name)}`);
      // The file name is what the attribute already shows: name only where it was found.
      return reply([`found at ${code(displayRef(resolved, workspace.folders[0]))}`, '', 'ManeuverGroups:', ...groups].join('\n'));
    }
    case 'groupReference': {
      const { link, group } = syntactic.linked ?? {};
      if (!link?.source || !group?.target) return null;
      return reply(
        groupSummary(
          `ManeuverGroup **${escapeMarkdown(group.target.name)}** of ${code(link.info.fileName)} (${group.overridable.length} overridable attributes)`,
          group.target,
        ),
      );
    }
    case 'key': {
      const linkedSource = syntactic.linked?.link.source;
      const group = syntactic.linked?.group;
      const match = syntactic.match;
      const plan = group?.plan;
      if (!group || !match || !linkedSource || !plan) return null;
      const key = code(attribute.value);
      if (match.targets.length === 0) return reply(`key ${key} overrides nothing in group ${code(group.info.name)}`);
      const sets = attributesSetBy(group, match);
      const lines = [
        sets.length > 0
          ? `key ${key} sets ${sets.length} attribute${sets.length === 1 ? '' : 's'}:`
          : `key ${key} sets nothing: a more specific key sets every attribute it matches`,
      ];
      if (sets.length > 0) lines.push('');
      for (const set of sets) {
        const declared = where(workspace, overridablePlace(linkedSource, set));
        lines.push(
          `- ${code(`${set.path.join('.')}.${set.attributeName}`)}: default ${defaultOf(set)} declared at ${declared}; takes effect: ${code(match.parameter.value)} (this key)`,
        );
      }
      const taken = match.targets.filter((candidate) => !sets.includes(candidate));
      if (taken.length > 0) lines.push('', `Matched, but set by a more specific key:`, '');
      for (const overridden of taken) {
        const applied = plan.applied.get(overridden);
        const by = applied
          ? `${code(applied.value)} from ${code(applied.key)} on line ${model.document.lines.positionAt(applied.element.start).line + 1}`
          : 'its default';
        lines.push(`- ${code(`${overridden.path.join('.')}.${overridden.attributeName}`)}: ${by}`);
      }
      return reply(lines.join('\n'));
    }
    case 'entityReference': {
      const entity = model.entities.find((candidate) => candidate.name === attribute.value);
      return reply(
        entity
          ? `entity ${code(entity.name)} (${entity.element.children[0]?.name ?? 'ScenarioObject'})`
          : `entity ${code(attribute.value)} is not declared in this file`,
      );
    }
    default:
      return null;
  }
}
