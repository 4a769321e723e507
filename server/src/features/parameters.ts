import { expressionMessage } from '../core/diagnostics/expressionWords';
import { CompletionItem, CompletionItemKind, LSPErrorCodes, ResponseError, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { composedValues } from '../core/flatten/carry';
import { FlatSource, LinkedGroupReference } from '../core/flatten';
import {
  Declaration,
  DocumentSemantics,
  formatValue,
  ParameterUse,
  parametersInScopeAt,
  Provenance,
  referencesOf,
  ValueResult,
} from '../core/semantics';
import { displayRef, refId, SourceRef } from '../core/sources';
import { SchemaIndex } from '../core/schema/index';
import { SimpleType } from '../core/schema/model';
import { attributeType, valueFits } from '../core/semantics/parameterValues';
import { typeByElementName } from '../core/schema/query';
import { elementAt, XmlAttribute, XmlDocument, XmlElement } from '../core/xml';
import { Place } from '../analysis';
import { ValueContext } from '../core/cursor';
import { dollarPrefix, Target } from '../target';
import { Workspace } from '../workspace';

/**
 * `$name` and `${...}` in the editor: definition, references, rename, completion after `$` and
 * hover, all read from the core's semantic model (core/semantics), never re-derived here.
 */

/** The semantics of the file as the workspace read it (unsaved text and packages included). */
export async function semanticsOf(
  workspace: Workspace,
  ref: SourceRef,
): Promise<{ source: FlatSource; semantics: DocumentSemantics } | undefined> {
  const source = await workspace.source(ref);
  return source.semantics ? { source, semantics: source.semantics } : undefined;
}

function lineOf(semantics: DocumentSemantics, offset: number): number {
  return semantics.model.document.lines.positionAt(offset).line + 1;
}

function declarationPlace(semantics: DocumentSemantics, declaration: Declaration): Place {
  const name = declaration.nameAttribute;
  const range = name
    ? semantics.model.document.lines.range(name.valueStart, name.valueEnd)
    : semantics.model.document.lines.range(declaration.element.start, declaration.element.nameEnd);
  return { ref: semantics.ref, range };
}

/** Where a `$name` (or parameterRef) is declared; empty when it is declared nowhere in scope. */
export function parameterDefinition(semantics: DocumentSemantics, use: ParameterUse): Place[] {
  return use.declaration ? [declarationPlace(semantics, use.declaration)] : [];
}

/** Every use of the declaration, optionally with the declaration. */
export function parameterReferences(semantics: DocumentSemantics, declaration: Declaration, includeDeclaration: boolean): Place[] {
  const lines = semantics.model.document.lines;
  const uses = referencesOf(semantics, declaration).map((use) => ({ ref: semantics.ref, range: lines.range(use.start, use.end) }));
  return includeDeclaration ? [declarationPlace(semantics, declaration), ...uses] : uses;
}

/** The name's own offsets (without the `$`) the target names, for prepareRename. */
export function parameterRenameRange(target: Target): { start: number; end: number; name: string } | undefined {
  const use = target.kind === 'parameter' || target.kind === 'expression' || target.kind === 'catalogReference' ? target.use : undefined;
  if (use) {
    if (!use.declaration) return undefined;
    const start = use.end - use.name.length;
    return { start, end: use.end, name: use.name };
  }
  const declaration = target.kind === 'declaration' ? target.declaration : undefined;
  const name = declaration?.nameAttribute;
  return declaration && name ? { start: name.valueStart, end: name.valueEnd, name: declaration.name } : undefined;
}

export const PARAMETER_NAME = /^[A-Za-z_][A-Za-z0-9_]*$/;

/**
 * Renames a parameter: its declaration and exactly its uses. A same-named
 * parameter of another scope is another Declaration of the model, so it is left alone.
 */
export function renameParameter(
  workspace: Workspace,
  semantics: DocumentSemantics,
  declaration: Declaration | undefined,
  newName: string,
): WorkspaceEdit | undefined {
  if (!declaration?.nameAttribute) return undefined;
  const name = newName.startsWith('$') ? newName.slice(1) : newName;
  if (!PARAMETER_NAME.test(name))
    throw new ResponseError(
      LSPErrorCodes.RequestFailed,
      `'${newName}' is not a parameter name (letters, digits and _, not starting with a digit)`,
    );
  if (semantics.ref.entries.length > 0 && !workspace.editablePackages) {
    throw new ResponseError(
      LSPErrorCodes.RequestFailed,
      'the parameter is inside a .mosc package, and this editor cannot write into packages',
    );
  }
  const lines = semantics.model.document.lines;
  const edits: TextEdit[] = [TextEdit.replace(lines.range(declaration.nameAttribute.valueStart, declaration.nameAttribute.valueEnd), name)];
  for (const use of referencesOf(semantics, declaration)) {
    // A use's offsets cover `$name`, or only the name for a parameterRef; the name is its tail either way.
    edits.push(TextEdit.replace(lines.range(use.end - use.name.length, use.end), name));
  }
  return { changes: { [workspace.uriOf(semantics.ref)]: edits } };
}

export function describeValue(result: ValueResult): string {
  return result.ok
    ? `${formatValue(result.value)} (${result.type})${differenceNote(result)}`
    : `cannot be evaluated: ${result.errors[0] ? expressionMessage(result.errors[0]) : 'unknown error'}`;
}

/** Where esmini computes another value than the standard: both, and esmini's rules that make the difference (SPEC 12). */
export function differenceNote(result: ValueResult): string {
  if (!result.ok || !result.differs) return '';
  const { standard, esmini, reasons } = result.differs;
  return `; by the standard ${standard}, by esmini ${esmini}${reasons.length ? ` (${reasons.join('; ')})` : ''}`;
}

/**
 * The schema type of the attribute a value is typed in (the tolerant parse's element at the tag, else the
 * first type with an element of that name); undefined with schema support off or an unknown attribute.
 */
export function attributeTypeAt(
  index: SchemaIndex | undefined,
  parsed: XmlDocument,
  context: ValueContext,
): { name: string; type: SimpleType } | undefined {
  if (!index) return undefined;
  const found = elementAt(parsed, context.tagStart);
  const placed =
    found && found.start === context.tagStart && found.name === context.element
      ? attributeType(index, found, context.attribute)
      : undefined;
  if (placed) return placed;
  const typeName = typeByElementName(index, context.element);
  const declaration = typeName ? index.attribute(typeName, context.attribute) : undefined;
  const type = declaration ? index.simpleType(declaration.type) : undefined;
  return declaration && type ? { name: declaration.type, type } : undefined;
}

/**
 * Completion after `$`: the parameters in scope at the cursor, innermost first, with value and type;
 * with the attribute's type known, those whose value fits it come first.
 */
export function parameterCompletion(
  document: TextDocument,
  semantics: DocumentSemantics,
  context: ValueContext,
  offset: number,
  attribute?: { name: string; type: SimpleType },
): CompletionItem[] {
  const typed = dollarPrefix(context) ?? '$';
  const start = offset - typed.length;
  const text = document.getText();
  let end = offset;
  while (end < context.valueEnd && /[A-Za-z0-9_]/.test(text[end])) end++;
  const range = { start: document.positionAt(start), end: document.positionAt(end) };
  return parametersInScopeAt(semantics, offset).map(({ declaration, value }, index) => ({
    label: `$${declaration.name}`,
    kind: CompletionItemKind.Variable,
    detail: `${declaration.writtenType ?? 'untyped'} = ${value.ok ? formatValue(value.value) : declaration.value}`,
    documentation: `declared in <${declaration.scope.element.name}> on line ${lineOf(semantics, declaration.element.start)}`,
    sortText: (attribute ? (value.ok && valueFits(value, attribute) ? '0' : '1') : '') + String(index).padStart(5, '0'),
    filterText: `$${declaration.name}`,
    textEdit: { range, newText: `$${declaration.name}` },
  }));
}

function scopeName(declaration: Declaration): string {
  const named = declaration.scope.element.attributes.find((attr) => attr.name === 'name')?.value;
  // A code span: markdown would otherwise read the tag as HTML.
  return `\`<${declaration.scope.element.name}${named ? ` ${named}` : ''}>\``;
}

function provenanceLine(semantics: DocumentSemantics, provenance: Provenance): string | undefined {
  switch (provenance.kind) {
    case 'declaration':
      return `declared in ${scopeName(provenance.declaration)} on line ${lineOf(semantics, provenance.declaration.element.start)}: \`${provenance.declaration.value}\``;
    case 'assignment':
      return `set by the catalog ParameterAssignment on line ${lineOf(semantics, provenance.assignment.element.start)}`;
    case 'override':
      return `overridden by the ParameterReference key \`${provenance.key}\``;
    case 'carried':
      return `carried from \`${provenance.from}\`, where \`${provenance.declaration.name}\` is declared \`${provenance.declaration.value}\``;
    default:
      return undefined;
  }
}

/** The source file (shown relative to the workspace) an imported group of `main` came from. */
function carriedFrom(workspace: Workspace, main: FlatSource, group: LinkedGroupReference): string | undefined {
  const source = main.links.find((link) => link.groups.includes(group))?.source;
  return source ? displayRef(source.ref, workspace.folders[0]) : undefined;
}

/** What each open main file importing this file makes of the attribute (a ParameterReference override or a carried declaration). */
async function composedLines(
  workspace: Workspace,
  semantics: DocumentSemantics,
  element: XmlElement,
  attr: XmlAttribute,
): Promise<string[]> {
  const lines: string[] = [];
  const id = refId(semantics.ref);
  for (const open of workspace.documents.values()) {
    if (refId(open.ref) === id) continue;
    const main = await workspace.source(open.ref);
    if (!main.links.some((link) => link.source && refId(link.source.ref) === id)) continue;
    for (const { group, result } of composedValues(main, element, attr.name, workspace.folders[0])) {
      const how =
        result.provenance.kind === 'override'
          ? `overridden by key \`${result.provenance.key}\``
          : result.provenance.kind === 'carried'
            ? `carried from \`${carriedFrom(workspace, main, group) ?? result.provenance.from}\``
            : result.provenance.kind === 'declaration'
              ? `the main file's declaration of \`${result.provenance.declaration.name}\``
              : 'as written';
      lines.push(
        `- in \`${displayRef(main.ref, workspace.folders[0])}\` (group ${group.info.name}): **${result.ok ? formatValue(result.value) : 'not evaluable'}**, ${how}`,
      );
    }
  }
  return lines;
}

/**
 * Hover on a `$name` or an attribute written `${...}`: type, value and where the value comes from
 * (the declarations of every parameter it reads).
 */
export async function parameterHover(
  workspace: Workspace,
  semantics: DocumentSemantics,
  target: Target,
): Promise<{ markdown: string; start: number; end: number } | undefined> {
  const hit = target.kind === 'nothing' || target.kind === 'elementName' ? undefined : target.hit;
  const found = hit?.inValue ? { element: hit.element, attribute: hit.attribute } : undefined;
  const use = target.kind === 'parameter' || target.kind === 'expression' || target.kind === 'catalogReference' ? target.use : undefined;
  const site = found ? semantics.model.siteOf.get(found.attribute) : undefined;
  if (found && site) {
    const { element, attribute: attr } = found;
    const result = semantics.evaluator.attributeValue(element, attr);
    const lines: string[] = [];
    const written = attr.value.trim();
    lines.push(
      site.form.kind === 'expression'
        ? `\`${written}\` = **${result.ok ? formatValue(result.value) : '?'}**${result.ok ? ` (${result.type})${differenceNote(result)}` : ''}`
        : `**${written}** = ${describeValue(result)}`,
    );
    if (!result.ok) for (const error of result.errors) lines.push(`- error: ${expressionMessage(error)}`);
    const provenance = provenanceLine(semantics, result.provenance);
    if (provenance) lines.push('', provenance);
    if (site.form.kind === 'expression') {
      const seen = new Set<Declaration>();
      const uses = semantics.model.uses.filter((candidate) => candidate.attribute === attr && candidate.element === element);
      if (uses.length > 0) lines.push('', 'parameters:');
      for (const candidate of uses) {
        if (!candidate.declaration) {
          lines.push(`- \`$${candidate.name}\`: not declared in this scope`);
          continue;
        }
        // The declaration the selected reading reads: with esmini, the last of two in one scope.
        const declaration = semantics.evaluator.declarationOf(site.scope, candidate.name, site.declaration) ?? candidate.declaration;
        if (seen.has(declaration)) continue;
        seen.add(declaration);
        const value = semantics.evaluator.declarationValue(declaration);
        lines.push(
          `- \`$${candidate.name}\` = ${describeValue(value)}, declared in ${scopeName(declaration)} on line ${lineOf(semantics, declaration.element.start)}`,
        );
      }
    }
    const composed = await composedLines(workspace, semantics, element, attr);
    if (composed.length > 0) lines.push('', 'in the files that import it:', ...composed);
    return { markdown: lines.join('\n'), start: attr.valueStart, end: attr.valueEnd };
  }
  if (use) {
    // A parameterRef names a parameter without using its value in an expression.
    if (!use.declaration) return { markdown: `parameter **${use.name}** is not declared in this scope`, start: use.start, end: use.end };
    const declaration = semantics.evaluator.declarationOf(semantics.model.scopeOf(use.element), use.name) ?? use.declaration;
    const value = semantics.evaluator.declarationValue(declaration);
    return {
      markdown: [`parameter **${use.name}** = ${describeValue(value)}`, '', provenanceLine(semantics, value.provenance) ?? ''].join('\n'),
      start: use.start,
      end: use.end,
    };
  }
  if (found) {
    // A literal of an imported group: shown only when a main file overrides it.
    const composed = await composedLines(workspace, semantics, found.element, found.attribute);
    if (composed.some((line) => line.includes('overridden by key'))) {
      return {
        markdown: [`**${found.attribute.value}** as written`, '', 'in the files that import it:', ...composed].join('\n'),
        start: found.attribute.valueStart,
        end: found.attribute.valueEnd,
      };
    }
  }
  const declaration = target.kind === 'declaration' ? target.declaration : undefined;
  if (declaration?.nameAttribute) {
    const value = semantics.evaluator.declarationValue(declaration);
    const count = referencesOf(semantics, declaration).length;
    return {
      markdown: `parameter **${declaration.name}** = ${describeValue(value)}, declared in ${scopeName(declaration)}; ${count} use${count === 1 ? '' : 's'}`,
      start: declaration.nameAttribute.valueStart,
      end: declaration.nameAttribute.valueEnd,
    };
  }
  return undefined;
}
