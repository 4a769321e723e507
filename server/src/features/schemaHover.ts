import { Hover, MarkupKind } from 'vscode-languageserver/node';
import { SchemaIndex } from '../core/schema/index';
import { AttributeDeclaration, ElementParticle } from '../core/schema/model';
import { indexFor, particleOfElement, typeOfElement } from '../core/schema/query';
import { describeType } from '../core/schema/values';
import { XmlDocument } from '../core/xml';
import { Target } from '../target';

/** The particle's occurrence in the schema's own terms: within a choice "required" would mislead. */
function occurrence(particle: ElementParticle): string {
  return `minOccurs ${particle.min}, maxOccurs ${particle.max === -1 ? 'unbounded' : particle.max}`;
}

function history(version: string, since: string | undefined, deprecated: boolean, deprecatedSince: string | undefined): string {
  const parts = [since ? `introduced in OpenSCENARIO ${since}` : 'in OpenSCENARIO since 1.0'];
  if (deprecated) parts.push(`**deprecated**${deprecatedSince ? ` since ${deprecatedSince}` : ''}`);
  return `${parts.join('; ')} (this file: ${version})`;
}

function elementHover(index: SchemaIndex, particle: ElementParticle, parentName: string | undefined): string {
  const type = index.complexType(particle.type);
  const required = (type?.attributes ?? []).filter((declaration) => declaration.required).map((declaration) => `\`${declaration.name}\``);
  const children = index.childParticles(particle.type).map((child) => child.name);
  const lines = [
    // Tag names as code: Markdown would read <Name> as HTML and drop it.
    `**\`<${particle.name}>\`** — type \`${particle.type.replace(/^#/, '')}\`${parentName ? `, ${occurrence(particle)} in \`<${parentName}>\`` : ''}`,
    '',
    history(index.version, particle.since, index.isDeprecated(particle), particle.deprecatedSince),
  ];
  if (required.length > 0) lines.push('', `Required attributes: ${required.join(', ')}`);
  if (children.length > 0) lines.push('', `Children (${type?.content?.kind ?? 'sequence'}): ${[...new Set(children)].join(', ')}`);
  return lines.join('\n');
}

function attributeHover(index: SchemaIndex, elementName: string, declaration: AttributeDeclaration): string {
  const simple = index.simpleType(declaration.type);
  return [
    `**${elementName}.${declaration.name}** — \`${declaration.type.replace(/^#/, '')}\`, ${declaration.required ? 'required' : 'optional'}`,
    '',
    `Allowed: ${simple ? describeType(simple).replace(/\$/g, '\\$') : 'any text'}`,
    '',
    history(index.version, declaration.since, index.isAttributeDeprecated(declaration), declaration.deprecatedSince),
  ].join('\n');
}

/** Hover on an element's tag name or an attribute's name: what the schema of the file's version says. */
export function schemaHoverAt(document: XmlDocument, setting: Parameters<typeof indexFor>[1], target: Target): Hover | null {
  const index = indexFor(document, setting);
  if (!index) return null;
  const reply = (value: string, start: number, end: number): Hover => ({
    contents: { kind: MarkupKind.Markdown, value },
    range: document.lines.range(start, end),
  });
  if (target.kind === 'elementName') {
    const { element } = target;
    const particle = particleOfElement(index, element);
    return particle ? reply(elementHover(index, particle, element.parent?.name), element.start + 1, element.nameEnd) : null;
  }
  const hit = target.kind === 'nothing' || target.hit === undefined || target.hit.inValue ? undefined : target.hit;
  const typeName = hit ? typeOfElement(index, hit.element) : undefined;
  const declaration = hit && typeName ? index.attribute(typeName, hit.attribute.name) : undefined;
  return hit && declaration
    ? reply(attributeHover(index, hit.element.name, declaration), hit.attribute.nameStart, hit.attribute.nameEnd)
    : null;
}
