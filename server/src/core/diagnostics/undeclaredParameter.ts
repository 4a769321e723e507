import { ProblemDataByCode } from '../problems';
import { indentationAt, Range } from '../text';
import { endTagStart, escapeAttributeValue, XmlElement } from '../xml';
import { ExpressionFact, UnknownParameterFact } from './expressionFacts';
import { CoreFix, defineDiagnostic, FixContext, isRecord, isString, ParameterScopes, ProblemWording, TextLines } from './definition';

/** The message of a `$name` in an expression that no declaration resolves, or whose declaration has no valid value (`words`: its cause's message). */
export function unknownParameterMessage(fact: UnknownParameterFact, words: (cause: ExpressionFact) => string): string {
  if (fact.fact === 'undeclared') return undeclaredMessage(fact.name);
  return `'${fact.name}' has no valid value (${fact.cause ? words(fact.cause) : 'see its declaration'})`;
}

function undeclaredMessage(name: string): string {
  return `parameter '${name}' is not declared in this scope`;
}

/** The hint of an undeclared parameter: a declaration to write, and where. */
export function declareParameterHint(name: string, where: string): string {
  return `declare <ParameterDeclaration name="${name}" parameterType="..." value="..."/> in the ParameterDeclarations of ${where}`;
}

/**
 * A `$name` no declaration in scope resolves; or (`entry`) a parameter the catalog entry a CatalogReference
 * names uses, which neither the entry nor the referencing file declares.
 */
export function undeclaredParameterWording(name: string, entry?: string): ProblemWording<'undeclared-parameter'> {
  return entry === undefined
    ? {
        severity: 'error',
        code: 'undeclared-parameter',
        message: undeclaredMessage(name),
        hint: declareParameterHint(name, 'the file or of an enclosing element'),
      }
    : {
        severity: 'error',
        code: 'undeclared-parameter',
        message: `catalog entry '${entry}' uses parameter '${name}', which neither the entry nor this file declares`,
        hint: `declare '${name}' in this file, or in the entry's ParameterDeclarations`,
      };
}

function declarationsChild(element: XmlElement): XmlElement | undefined {
  return element.children.find((child) => child.name === 'ParameterDeclarations');
}

function unitOf(text: string): string {
  return /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ';
}

/**
 * Declare parameter `name` in the nearest enclosing ParameterDeclarations (one is created at the root, after
 * the FileHeader, when no enclosing scope has any), with the type and value of its declaration elsewhere
 * where there is one.
 */
function declareParameter(document: TextLines, { scopes, root, declarationOf }: ParameterScopes, name: string): CoreFix | undefined {
  const text = document.getText();
  const template = declarationOf(name);
  const line = `<ParameterDeclaration name="${name}" parameterType="${escapeAttributeValue(template?.type ?? 'string')}" value="${escapeAttributeValue(template?.value ?? '')}"/>`;
  const eol = text.includes('\r\n') ? '\r\n' : '\n';
  const unit = unitOf(text);
  const scope = scopes.find((element) => declarationsChild(element));
  const holder = scope ? declarationsChild(scope) : undefined;
  const insert = (offset: number, newText: string): { range: Range; newText: string } => {
    const at = document.positionAt(offset);
    return { range: { start: at, end: at }, newText };
  };
  let edit: { range: Range; newText: string };
  if (holder && !holder.selfClosing && holder.closed) {
    const close = endTagStart(text, holder);
    const closeLineStart = text.lastIndexOf('\n', close - 1) + 1;
    const outer = indentationAt(text, holder.start);
    const onOwnLine = /^[ \t]*$/.test(text.slice(closeLineStart, close));
    edit = onOwnLine ? insert(closeLineStart, `${outer}${unit}${line}${eol}`) : insert(close, `${eol}${outer}${unit}${line}${eol}${outer}`);
  } else if (holder) {
    const outer = indentationAt(text, holder.start);
    edit = {
      range: { start: document.positionAt(holder.start), end: document.positionAt(holder.end) },
      newText: `<ParameterDeclarations>${eol}${outer}${unit}${line}${eol}${outer}</ParameterDeclarations>`,
    };
  } else {
    if (!root) return undefined;
    // The standard's order puts ParameterDeclarations right after the FileHeader.
    const header = root.children.find((child) => child.name === 'FileHeader');
    const anchor = header ? header.end : root.startTagEnd;
    const outer = header ? indentationAt(text, header.start) : indentationAt(text, root.start) + unit;
    edit = insert(anchor, `${eol}${outer}<ParameterDeclarations>${eol}${outer}${unit}${line}${eol}${outer}</ParameterDeclarations>`);
  }
  const title = template?.from
    ? `Declare parameter '${name}' (value ${template.value} from ${template.from})`
    : `Declare parameter '${name}'`;
  return { title, edits: [{ place: 'document', ...edit }], preferred: true };
}

/** The quick fix of an undeclared parameter (of this code and of undeclared-catalog-parameter): declare it, from the file's analysis. */
export async function declareParameterFixes({ data, document, parameters }: FixContext<{ parameter: string }>): Promise<CoreFix[]> {
  const scopes = data?.parameter ? await parameters() : undefined;
  const fix = scopes && data ? declareParameter(document, scopes, data.parameter) : undefined;
  return fix ? [fix] : [];
}

/** A `$name` naming no declared parameter: its fix declares it, with the value of a source's declaration where one has it. */
export const UNDECLARED_PARAMETER = defineDiagnostic({
  code: 'undeclared-parameter',
  rule: { description: 'A $name names a declared parameter.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-parameter'] => isRecord(value) && isString(value.parameter),
  fixes: declareParameterFixes,
});
