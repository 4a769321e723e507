/**
 * A small mutable element tree for rewriting a scenario: the parser's tree keeps offsets and never changes,
 * an export moves, renames and drops elements. Each node remembers where it was written, for the loss report.
 */
import { SourceRef } from '../sources';
import { Range } from '../text';
import { endTagStart, escapeAttributeValue, XmlDocument, XmlElement } from '../xml';

/** Where an element of the export was written in the sources (a catalog entry's file for an inlined entry). */
export interface Place {
  source: SourceRef;
  range: Range;
}

export interface Node {
  name: string;
  /** In the order written; a name at most once. */
  attributes: [string, string][];
  children: Node[];
  /** Character content of an element without children (a CustomCommandAction's command), decoded. */
  text?: string;
  parent: Node | undefined;
  place: Place | undefined;
}

export function attr(node: Node, name: string): string | undefined {
  return node.attributes.find(([key]) => key === name)?.[1];
}

export function setAttr(node: Node, name: string, value: string): void {
  const found = node.attributes.find(([key]) => key === name);
  if (found) found[1] = value;
  else node.attributes.push([name, value]);
}

export function removeAttr(node: Node, name: string): boolean {
  const index = node.attributes.findIndex(([key]) => key === name);
  if (index < 0) return false;
  node.attributes.splice(index, 1);
  return true;
}

export function renameAttr(node: Node, from: string, to: string): void {
  const found = node.attributes.find(([key]) => key === from);
  if (found) found[0] = to;
}

export function child(node: Node, name: string): Node | undefined {
  return node.children.find((candidate) => candidate.name === name);
}

export function childrenNamed(node: Node, name: string): Node[] {
  return node.children.filter((candidate) => candidate.name === name);
}

/** Every node below `node` (itself included) in document order. */
export function allNodes(node: Node): Node[] {
  const result: Node[] = [];
  const stack = [node];
  while (stack.length > 0) {
    const next = stack.pop() as Node;
    result.push(next);
    for (let i = next.children.length - 1; i >= 0; i--) stack.push(next.children[i]);
  }
  return result;
}

/** Every node below `node` (itself included) of that name, or of one of those names, in document order. */
export function named(node: Node, name: string | ReadonlySet<string>): Node[] {
  const result: Node[] = [];
  // The rules ask this of the whole tree dozens of times: one walk, no list of every node.
  const visit = typeof name === 'string' ? (each: Node) => each.name === name : (each: Node) => name.has(each.name);
  const walk = (at: Node): void => {
    if (visit(at)) result.push(at);
    for (const each of at.children) walk(each);
  };
  walk(node);
  return result;
}

export function makeNode(name: string, attributes: [string, string][] = [], children: Node[] = [], place?: Place): Node {
  const node: Node = { name, attributes, children, parent: undefined, place };
  for (const each of children) each.parent = node;
  return node;
}

export function appendChild(parent: Node, node: Node, before?: Node): Node {
  node.parent = parent;
  const index = before ? parent.children.indexOf(before) : -1;
  if (index >= 0) parent.children.splice(index, 0, node);
  else parent.children.push(node);
  return node;
}

export function removeNode(node: Node): void {
  if (!node.parent) return;
  const index = node.parent.children.indexOf(node);
  if (index >= 0) node.parent.children.splice(index, 1);
  node.parent = undefined;
}

export function replaceNode(old: Node, replacement: Node): void {
  const parent = old.parent;
  if (!parent) return;
  const index = parent.children.indexOf(old);
  parent.children[index] = replacement;
  replacement.parent = parent;
  old.parent = undefined;
}

export function ancestor(node: Node, name: string): Node | undefined {
  for (let at = node.parent; at; at = at.parent) if (at.name === name) return at;
  return undefined;
}

/** A deep copy (parents set), keeping each node's place. */
export function cloneNode(node: Node): Node {
  const copy = makeNode(
    node.name,
    node.attributes.map(([key, value]) => [key, value]),
    node.children.map(cloneNode),
    node.place,
  );
  if (node.text !== undefined) copy.text = node.text;
  return copy;
}

const ENTITY = /&(?:#x([0-9a-fA-F]+)|#(\d+)|(lt|gt|amp|quot|apos));/g;
const NAMED: Record<string, string> = { lt: '<', gt: '>', amp: '&', quot: '"', apos: "'" };

function decodeText(text: string): string {
  return text.replace(ENTITY, (_whole, hex: string | undefined, decimal: string | undefined, name: string | undefined) =>
    hex ? String.fromCodePoint(parseInt(hex, 16)) : decimal ? String.fromCodePoint(Number(decimal)) : NAMED[name as string],
  );
}

/** A node read from the parser's tree: where it was written is asked only for the few that a loss names, and computed then. */
class ParsedNode implements Node {
  parent: Node | undefined = undefined;
  text?: string;
  private known: Place | undefined | null = null;

  constructor(
    private readonly element: XmlElement,
    private readonly placeOf: (element: XmlElement) => Place | undefined,
    public name: string,
    public attributes: [string, string][],
    public children: Node[],
  ) {
    for (const each of children) each.parent = this;
  }

  get place(): Place | undefined {
    if (this.known === null) this.known = this.placeOf(this.element);
    return this.known;
  }

  set place(given: Place | undefined) {
    this.known = given;
  }
}

/**
 * The parser's element as a node tree; `placeOf` says where each element was written. `value` gives each
 * attribute's value as it is to be written (an export evaluates `$name` and `${...}` there).
 */
export function nodeFromXml(
  document: XmlDocument,
  element: XmlElement,
  placeOf: (element: XmlElement) => Place | undefined,
  value: (element: XmlElement, index: number) => string,
): Node {
  const node = new ParsedNode(
    element,
    placeOf,
    element.name,
    element.attributes.map((attribute, index) => [attribute.name, value(element, index)]),
    element.children.map((each) => nodeFromXml(document, each, placeOf, value)),
  );
  if (element.children.length === 0 && !element.selfClosing) {
    const closeTag = endTagStart(document.text, element);
    const raw = closeTag > element.startTagEnd ? document.text.slice(element.startTagEnd, closeTag) : '';
    const cdata = /^\s*<!\[CDATA\[([\s\S]*)\]\]>\s*$/.exec(raw);
    const text = cdata ? cdata[1] : decodeText(raw.replace(/<!--[\s\S]*?-->/g, ''));
    if (text.trim()) node.text = text;
  }
  return node;
}

function escapeText(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

/** The node as indented XML (two spaces a level), with the XML declaration. */
export function serialize(root: Node): string {
  const lines: string[] = ['<?xml version="1.0" encoding="UTF-8"?>'];
  const write = (node: Node, depth: number): void => {
    const indent = '  '.repeat(depth);
    const attributes = node.attributes.map(([key, value]) => ` ${key}="${escapeAttributeValue(value)}"`).join('');
    if (node.children.length === 0 && node.text === undefined) {
      lines.push(`${indent}<${node.name}${attributes}/>`);
      return;
    }
    if (node.children.length === 0) {
      lines.push(`${indent}<${node.name}${attributes}>${escapeText(node.text as string)}</${node.name}>`);
      return;
    }
    lines.push(`${indent}<${node.name}${attributes}>`);
    for (const each of node.children) write(each, depth + 1);
    lines.push(`${indent}</${node.name}>`);
  };
  write(root, 0);
  return lines.join('\n') + '\n';
}
