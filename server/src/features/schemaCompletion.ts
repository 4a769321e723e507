import { CompletionItem, CompletionItemKind, CompletionItemTag, InsertTextFormat, MarkupKind } from 'vscode-languageserver/node';
import { SchemaIndex } from '../core/schema/index';
import { AttributeDeclaration, ElementParticle } from '../core/schema/model';
import { allowedChildren, indexFor, typeByElementName, typeOfElement } from '../core/schema/query';
import { elementSkeleton, placeholderValue, skeletonText, withOptionalChild } from '../core/schema/skeleton';
import { builtinOf, describeType, enumerationValues } from '../core/schema/values';
import { attribute, descendants, elementAt, XmlDocument, XmlElement } from '../core/xml';
import { ValueContext } from '../core/cursor';
import { CompletionTarget } from '../target';
import { Workspace } from '../workspace';

// Code actions read the current parse from here.
export { currentDocument } from '../target';

function escapeSnippet(value: string): string {
  return value.replace(/[$}\\|,]/g, (char) => `\\${char}`);
}

/** An attribute's value as a snippet: a choice of the enumeration's values, or a tab stop. */
function attributeValueSnippet(index: SchemaIndex, declaration: AttributeDeclaration, stop: number): string {
  const type = index.simpleType(declaration.type);
  const values = type ? enumerationValues(type) : [];
  const choices = values.length > 0 ? values : type && builtinOf(type) === 'boolean' ? ['true', 'false'] : [];
  return choices.length > 0 ? `\${${stop}|${choices.map(escapeSnippet).join(',')}|}` : `\${${stop}}`;
}

/** `name="…"` as a snippet. */
function attributeSnippet(index: SchemaIndex, declaration: AttributeDeclaration, stop: number): string {
  return `${declaration.name}="${attributeValueSnippet(index, declaration, stop)}"`;
}

/**
 * `<Name required="…">$0</Name>`, self-closing when the element holds nothing; with its required
 * children (recursively, the same skeleton as the quick fix inserts) when it has any, one tab stop per attribute.
 */
export function elementSnippet(index: SchemaIndex, particle: ElementParticle): string {
  const skeleton = elementSkeleton(index, particle);
  if (skeleton.children.length > 0) {
    let stop = 0;
    // The editor turns the snippet's tabs into the document's indentation and indents it where it is inserted.
    const text = skeletonText(skeleton, { indent: '', unit: '\t', eol: '\n' }, (declaration) =>
      attributeValueSnippet(index, declaration, ++stop),
    );
    const closing = `\n</${particle.name}>`;
    return `${text.slice(0, text.length - closing.length)}$0${closing}`;
  }
  const attributes = skeleton.attributes.map((declaration, position) => ` ${attributeSnippet(index, declaration, position + 1)}`);
  const type = index.complexType(particle.type);
  const empty = !type?.content && !type?.text;
  return empty ? `<${particle.name}${attributes.join('')}/>$0` : `<${particle.name}${attributes.join('')}>$0</${particle.name}>`;
}

function versionNote(since: string | undefined, deprecated: boolean, deprecatedSince: string | undefined): string {
  const parts: string[] = [];
  if (since) parts.push(`since OpenSCENARIO ${since}`);
  if (deprecated) parts.push(`deprecated${deprecatedSince ? ` since ${deprecatedSince}` : ''}`);
  return parts.join(', ');
}

/** Child elements allowed at the cursor, in content-model order with the required ones first. */
function elementItems(index: SchemaIndex, document: XmlDocument, start: number, offset: number): CompletionItem[] {
  let parent = elementAt(document, offset);
  // A half-typed `<Nam` parses as an element of its own: its parent is where the child goes.
  while (parent && parent.start >= start && parent.parent) parent = parent.parent;
  if (!parent || offset < parent.startTagEnd) return [];
  const typeName = typeOfElement(index, parent) ?? typeByElementName(index, parent.name);
  if (!typeName) return [];
  const preceding = parent.children.filter((child) => child.end <= start).map((child) => child.name);
  const following = parent.children.find((child) => child.start >= offset)?.name;
  const range = { start: positionOf(document, start), end: positionOf(document, offset) };
  const typedOpen = document.text[start] === '<';
  // The modular extension's elements come as whole-reference snippets from the completion of references.
  const allowed = allowedChildren(index, typeName, preceding, following).filter(({ particle }) => !particle.type.startsWith('#'));
  return allowed.map(({ particle, required }, position) => {
    const deprecated = index.isDeprecated(particle);
    const note = versionNote(particle.since, deprecated, particle.deprecatedSince);
    const item: CompletionItem = {
      label: particle.name,
      kind: CompletionItemKind.Property,
      detail: `${required ? 'required' : 'optional'}${particle.max === -1 ? ', any number' : ''} in <${parent.name}> (OpenSCENARIO ${index.version})${note ? `; ${note}` : ''}`,
      sortText: `${required ? 0 : deprecated ? 2 : 1}_${String(position).padStart(3, '0')}`,
      filterText: typedOpen ? `<${particle.name}` : particle.name,
      insertTextFormat: InsertTextFormat.Snippet,
      textEdit: { range, newText: elementSnippet(index, particle) },
    };
    if (deprecated) item.tags = [CompletionItemTag.Deprecated];
    return item;
  });
}

function positionOf(document: XmlDocument, offset: number) {
  return document.lines.positionAt(offset);
}

/** The element whose start tag begins at `tagStart`, when the parse has one there. */
function elementStartingAt(document: XmlDocument, tagStart: number): XmlElement | undefined {
  const found = elementAt(document, tagStart);
  return found && found.start === tagStart ? found : undefined;
}

function typeAtTag(index: SchemaIndex, document: XmlDocument, tagStart: number, elementName: string): string | undefined {
  const element = elementStartingAt(document, tagStart);
  return (element && element.name === elementName ? typeOfElement(index, element) : undefined) ?? typeByElementName(index, elementName);
}

/** Attribute names not yet written, required first. */
function attributeItems(
  index: SchemaIndex,
  document: XmlDocument,
  context: { tagStart: number; element: string; written: string[]; start: number },
  offset: number,
): CompletionItem[] {
  const typeName = typeAtTag(index, document, context.tagStart, context.element);
  const type = typeName ? index.complexType(typeName) : undefined;
  if (!type) return [];
  const range = { start: positionOf(document, context.start), end: positionOf(document, offset) };
  return type.attributes
    .filter((declaration) => !context.written.includes(declaration.name))
    .map((declaration, position) => {
      const simple = index.simpleType(declaration.type);
      const deprecated = index.isAttributeDeprecated(declaration);
      const note = versionNote(declaration.since, deprecated, declaration.deprecatedSince);
      const item: CompletionItem = {
        label: declaration.name,
        kind: CompletionItemKind.Field,
        detail: `${declaration.required ? 'required' : 'optional'} ${declaration.type}${note ? `; ${note}` : ''}`,
        documentation: simple ? { kind: MarkupKind.Markdown, value: `Allowed: ${describeType(simple)}` } : undefined,
        sortText: `${declaration.required ? 0 : deprecated ? 2 : 1}_${String(position).padStart(3, '0')}`,
        insertTextFormat: InsertTextFormat.Snippet,
        textEdit: { range, newText: attributeSnippet(index, declaration, 1) },
      };
      if (deprecated) item.tags = [CompletionItemTag.Deprecated];
      return item;
    });
}

/** The parameters declared in the document, for a value that may be `$name`. */
function declaredParameters(document: XmlDocument): { name: string; value: string; type: string }[] {
  if (!document.root) return [];
  const seen = new Set<string>();
  const result: { name: string; value: string; type: string }[] = [];
  for (const element of descendants(document.root)) {
    if (element.name !== 'ParameterDeclaration') continue;
    const name = attribute(element, 'name')?.value;
    if (!name || seen.has(name)) continue;
    seen.add(name);
    result.push({ name, value: attribute(element, 'value')?.value ?? '', type: attribute(element, 'parameterType')?.value ?? '' });
  }
  return result;
}

/** Enumeration values, true/false, and `$parameters` where the attribute's type admits one. */
function valueItems(index: SchemaIndex, document: XmlDocument, context: ValueContext): CompletionItem[] {
  const typeName = typeAtTag(index, document, context.tagStart, context.element);
  const declaration = typeName ? index.attribute(typeName, context.attribute) : undefined;
  const simple = declaration ? index.simpleType(declaration.type) : undefined;
  if (!declaration || !simple) return [];
  const range = { start: positionOf(document, context.valueStart), end: positionOf(document, context.valueEnd) };
  const items: CompletionItem[] = [];
  for (const alternative of simple.alternatives) {
    for (const value of alternative.enumeration ?? []) {
      const deprecated = alternative.deprecatedValues?.includes(value) ?? false;
      const since = alternative.valuesSince?.[value];
      const item: CompletionItem = {
        label: value,
        kind: CompletionItemKind.EnumMember,
        detail: `${declaration.type}${since ? `, since OpenSCENARIO ${since}` : ''}${deprecated ? ', deprecated' : ''}`,
        sortText: `${deprecated ? 1 : 0}_${value}`,
        textEdit: { range, newText: value },
      };
      if (deprecated) item.tags = [CompletionItemTag.Deprecated];
      items.push(item);
    }
    if (alternative.builtin === 'boolean')
      for (const value of ['true', 'false'])
        items.push({
          label: value,
          kind: CompletionItemKind.Value,
          detail: declaration.type,
          sortText: `0_${value}`,
          textEdit: { range, newText: value },
        });
  }
  if (simple.parameter) {
    for (const parameter of declaredParameters(document)) {
      items.push({
        label: `$${parameter.name}`,
        kind: CompletionItemKind.Variable,
        detail: `parameter${parameter.type ? ` (${parameter.type})` : ''} = ${parameter.value}`,
        sortText: `5_${parameter.name}`,
        textEdit: { range, newText: `$${parameter.name}` },
      });
    }
  }
  return items;
}

/** A tab stop holding a value the type accepts (so that the skeleton validates as inserted), or a choice of the allowed values. */
function placeholderSnippet(index: SchemaIndex, declaration: AttributeDeclaration, stop: number): string {
  const snippet = attributeValueSnippet(index, declaration, stop);
  const placeholder = placeholderValue(index, declaration.type);
  return snippet === `\${${stop}}` && placeholder ? `\${${stop}:${escapeSnippet(placeholder)}}` : snippet;
}

/** `1.3` → revMajor 1, revMinor 3. */
function versionParts(version: string): { revMajor: string; revMinor: string } {
  const [revMajor, revMinor] = version.split('.');
  return { revMajor, revMinor };
}

/**
 * A whole scenario of the schema's version as a snippet: the XML declaration (unless written), the root
 * with its required content plus ParameterDeclarations and the Storyboard's StopTrigger, the FileHeader's
 * version and today's date filled in, a tab stop for each other required attribute.
 */
export function scenarioSkeletonSnippet(index: SchemaIndex, withDeclaration: boolean, now = new Date()): string {
  const root: ElementParticle = { kind: 'element', name: index.schema.rootElement, type: index.schema.rootType, min: 1, max: 1 };
  const filled: Record<string, string> = { ...versionParts(index.version), date: now.toISOString().replace(/\.\d{3}Z$/, '') };
  let stop = 0;
  // What the schema leaves optional but a new scenario wants: its parameters and an end.
  const scenario = withOptionalChild(index, elementSkeleton(index, root), 'ParameterDeclarations');
  const complete = {
    ...scenario,
    children: scenario.children.map((child) => (child.name === 'Storyboard' ? withOptionalChild(index, child, 'StopTrigger') : child)),
  };
  const text = skeletonText(complete, { indent: '', unit: '\t', eol: '\n' }, (declaration) =>
    declaration.name in filled
      ? escapeSnippet(filled[declaration.name])
      : // A ManeuverGroup that runs once, not never (0 is the type's placeholder).
        declaration.name === 'maximumExecutionCount'
        ? `\${${++stop}:1}`
        : placeholderSnippet(index, declaration, ++stop),
  );
  return `${withDeclaration ? '<?xml version="1.0" encoding="UTF-8"?>\n' : ''}${text}\n$0`;
}

/** Schema completion at the cursor; empty when schema support is off or nothing in the schema applies. */
export function schemaCompletion(workspace: Workspace, parsed: XmlDocument, target: CompletionTarget, offset: number): CompletionItem[] {
  const index = indexFor(parsed, workspace.settings.schemaVersion);
  if (!index) return [];
  switch (target.kind) {
    case 'nothing':
      return [];
    case 'attributeName':
      return attributeItems(index, parsed, target, offset);
    case 'elementName':
      return elementItems(index, parsed, target.start, offset);
    default:
      return valueItems(index, parsed, target.context);
  }
}
