import { SemanticTokens, SemanticTokensBuilder, SemanticTokensLegend } from 'vscode-languageserver/node';
import { DocumentSemantics, ExpressionNode } from '../core/semantics';
import { serverMemo } from '../database';

/** Semantic highlighting of `$name` and `${...}`: parameters, operators, numbers and functions, apart from literal values. */

const TOKEN_TYPES = ['parameter', 'operator', 'number', 'function', 'keyword', 'variable'] as const;
const TOKEN_MODIFIERS = ['declaration', 'readonly'] as const;
type TokenType = (typeof TOKEN_TYPES)[number];

export const SEMANTIC_TOKENS_LEGEND: SemanticTokensLegend = { tokenTypes: [...TOKEN_TYPES], tokenModifiers: [...TOKEN_MODIFIERS] };

const DECLARATION = 1 << TOKEN_MODIFIERS.indexOf('declaration');
const READONLY = 1 << TOKEN_MODIFIERS.indexOf('readonly');

interface Token {
  start: number;
  end: number;
  type: TokenType;
  modifiers: number;
}

function treeTokens(text: string, node: ExpressionNode, out: Token[]): void {
  switch (node.kind) {
    case 'number':
      out.push({ start: node.start, end: node.end, type: 'number', modifiers: 0 });
      return;
    case 'boolean':
      out.push({ start: node.start, end: node.end, type: 'keyword', modifiers: 0 });
      return;
    case 'constant':
      out.push({ start: node.start, end: node.end, type: 'variable', modifiers: READONLY });
      return;
    case 'parameter':
      out.push({ start: node.start, end: node.end, type: 'parameter', modifiers: 0 });
      return;
    case 'unary':
      out.push({ start: node.start, end: node.start + node.operator.length, type: 'operator', modifiers: 0 });
      treeTokens(text, node.operand, out);
      return;
    case 'binary': {
      treeTokens(text, node.left, out);
      // The tree keeps no operator offset: it is the operator's text between the operands.
      const at = text.indexOf(node.operator, node.left.end);
      if (at >= 0 && at < node.right.start) out.push({ start: at, end: at + node.operator.length, type: 'operator', modifiers: 0 });
      treeTokens(text, node.right, out);
      return;
    }
    case 'call':
      out.push({ start: node.start, end: node.start + node.name.length, type: 'function', modifiers: 0 });
      for (const arg of node.args) treeTokens(text, arg, out);
      return;
  }
}

// A model never changes once built: its tokens are listed once per analysis.
const tokensOf = serverMemo<DocumentSemantics, Token[]>('semanticTokens');

/** The tokens between two offsets, sorted and without overlaps. */
export function semanticTokenList(semantics: DocumentSemantics, start = 0, end = Number.MAX_SAFE_INTEGER): Token[] {
  let all = tokensOf.get(semantics);
  if (!all) {
    all = listTokens(semantics);
    tokensOf.set(semantics, all);
  }
  return start === 0 && end === Number.MAX_SAFE_INTEGER ? all : all.filter((token) => token.end >= start && token.start <= end);
}

function listTokens(semantics: DocumentSemantics): Token[] {
  const model = semantics.model;
  const text = model.document.text;
  const tokens: Token[] = [];
  for (const declaration of model.declarations) {
    const name = declaration.nameAttribute;
    if (name && name.valueEnd > name.valueStart)
      tokens.push({ start: name.valueStart, end: name.valueEnd, type: 'parameter', modifiers: DECLARATION });
  }
  for (const site of model.sites) {
    if (site.form.kind === 'parameter') {
      tokens.push({ start: site.form.start, end: site.form.end, type: 'parameter', modifiers: 0 });
      continue;
    }
    const expression = site.form.expression;
    tokens.push({ start: expression.start, end: expression.bodyStart, type: 'operator', modifiers: 0 });
    if (expression.tree) treeTokens(text, expression.tree, tokens);
    else
      for (const parameter of expression.parameters)
        tokens.push({ start: parameter.start, end: parameter.end, type: 'parameter', modifiers: 0 });
    if (expression.bodyEnd < expression.end)
      tokens.push({ start: expression.bodyEnd, end: expression.end, type: 'operator', modifiers: 0 });
  }
  for (const use of model.uses)
    if (use.via === 'parameterRef') tokens.push({ start: use.start, end: use.end, type: 'parameter', modifiers: 0 });
  tokens.sort((a, b) => a.start - b.start);
  const result: Token[] = [];
  let last = -1;
  for (const token of tokens) {
    if (token.start < last || token.end <= token.start) continue;
    result.push(token);
    last = token.end;
  }
  return result;
}

const encodedOf = serverMemo<DocumentSemantics, SemanticTokens>('encodedSemanticTokens');

export function semanticTokens(semantics: DocumentSemantics, start?: number, end?: number): SemanticTokens {
  if (start === undefined && end === undefined) {
    const known = encodedOf.get(semantics);
    if (known) return known;
    const encoded = encode(semantics);
    encodedOf.set(semantics, encoded);
    return encoded;
  }
  return encode(semantics, start, end);
}

function encode(semantics: DocumentSemantics, start?: number, end?: number): SemanticTokens {
  const lines = semantics.model.document.lines;
  const builder = new SemanticTokensBuilder();
  for (const token of semanticTokenList(semantics, start, end)) {
    const from = lines.positionAt(token.start);
    const to = lines.positionAt(token.end);
    // Tokens span one line (clients need not support multiline tokens); a wrapped one is left out.
    if (from.line !== to.line) continue;
    builder.push(from.line, from.character, to.character - from.character, TOKEN_TYPES.indexOf(token.type), token.modifiers);
  }
  return builder.build();
}
