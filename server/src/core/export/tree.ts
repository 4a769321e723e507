/**
 * A small mutable element tree for rewriting a scenario: the parser's tree keeps offsets and never changes,
 * an export moves, renames and drops elements. Each node remembers where it was written, for the loss report.
 */
import { coreMemo } from '../memos';
import { SourceRef } from '../sources';
import { LineIndex, Range } from '../text';
import { endTagStart, escapeAttributeValue, XmlAttribute, XmlDocument, XmlElement } from '../xml';

/** Where an element of the export was written in the sources (a catalog entry's file for an inlined entry). */
export interface Place {
  source: SourceRef;
  range: Range;
}

/**
 * An element of the tree. Its structure (name, children, parent) changes only through the functions of this
 * module, which keep each root's index of its nodes by name (`named`) up to date.
 */
export interface Node {
  readonly name: string;
  /** In the order written; a name at most once. */
  attributes: [string, string][];
  readonly children: readonly Node[];
  /** Character content of an element without children (a CustomCommandAction's command), decoded. */
  text?: string;
  parent: Node | undefined;
  place: Place | undefined;
}

/** The entry of an attribute; loops without callbacks, as these run for every node of an export, mostly before V8 optimizes them. */
function entryOf(node: Node, name: string): [string, string] | undefined {
  const attributes = node.attributes;
  for (let i = 0; i < attributes.length; i++) if (attributes[i][0] === name) return attributes[i];
  return undefined;
}

export function attr(node: Node, name: string): string | undefined {
  return entryOf(node, name)?.[1];
}

/** An attribute read as a number: `fallback` when it is absent or empty, NaN when it is no number. */
export function numberAttr(node: Node, name: string, fallback = 0): number {
  const value = attr(node, name);
  return value === undefined || value.trim() === '' ? fallback : Number(value);
}

/** A coordinate, angle or time as the export writes it: four decimals, without trailing zeros. */
export function fourDecimals(value: number): string {
  return String(Number(value.toFixed(4)));
}

export function setAttr(node: Node, name: string, value: string): void {
  const found = entryOf(node, name);
  if (found) found[1] = value;
  else node.attributes.push([name, value]);
}

export function removeAttr(node: Node, name: string): boolean {
  const attributes = node.attributes;
  for (let i = 0; i < attributes.length; i++) {
    if (attributes[i][0] !== name) continue;
    attributes.splice(i, 1);
    return true;
  }
  return false;
}

export function renameAttr(node: Node, from: string, to: string): void {
  const found = entryOf(node, from);
  if (found) found[0] = to;
}

export function child(node: Node, name: string): Node | undefined {
  const children = node.children;
  for (let i = 0; i < children.length; i++) if (children[i].name === name) return children[i];
  return undefined;
}

export function childrenNamed(node: Node, name: string): Node[] {
  const result: Node[] = [];
  for (const each of node.children) if (each.name === name) result.push(each);
  return result;
}

/**
 * Each root's nodes in document order and by name, made on the first question and then kept up to date by the
 * functions below as nodes are added, moved and removed (the rules ask for the nodes of a name dozens of times,
 * each between the previous rule's changes; making it again after each cost more than the export's mapping).
 */
interface NodeIndex {
  all: Node[];
  byName: Map<string, Node[]>;
  /** Nodes added or removed since the last question: past a share of the tree, making it again on the next question is cheaper. */
  edited: number;
}

const indexes = coreMemo<Node, NodeIndex>('exportNodeIndexes');

function rootOf(node: Node): Node {
  let top = node;
  while (top.parent) top = top.parent;
  return top;
}

/** The index of the tree `node` is in, if one was made and is still worth keeping up to date. */
function liveIndex(node: Node): NodeIndex | undefined {
  const root = rootOf(node);
  const index = indexes.get(root);
  if (index && index.edited > index.all.length / 2) {
    indexes.delete(root);
    return undefined;
  }
  return index;
}

/** A node becomes a child: an index of its own, made while it was a root, would not see later changes. */
function adopted(node: Node): void {
  indexes.delete(node);
}

function indexOf(root: Node): NodeIndex {
  let index = indexes.get(root);
  if (!index) {
    const all = walk(root);
    const byName = new Map<string, Node[]>();
    for (const each of all) {
      const same = byName.get(each.name);
      if (same) same.push(each);
      else byName.set(each.name, [each]);
    }
    index = { all, byName, edited: 0 };
    indexes.set(root, index);
  }
  index.edited = 0;
  return index;
}

/** Takes `node` and the nodes below it (still in the tree, a run of `all`) out of the index of their tree. */
function unindex(index: NodeIndex, root: Node, node: Node): void {
  const start = index.all.indexOf(node);
  if (start < 0) {
    indexes.delete(root);
    return;
  }
  const nodes = walk(node);
  index.all.splice(start, nodes.length);
  for (const each of nodes) {
    const same = index.byName.get(each.name) as Node[];
    same.splice(same.indexOf(each), 1);
  }
  index.edited += nodes.length;
}

/** The first node after `node` and the nodes below it in document order. */
function following(node: Node): Node | undefined {
  for (let at = node; at.parent; at = at.parent) {
    const siblings = at.parent.children;
    const position = siblings.indexOf(at);
    if (position + 1 < siblings.length) return siblings[position + 1];
  }
  return undefined;
}

/** Puts `node`, just placed in the tree, and the nodes below it into the index of their tree, in document order. */
function reindex(index: NodeIndex, root: Node, node: Node): void {
  const nodes = walk(node);
  const next = following(node);
  const at = next ? index.all.indexOf(next) : index.all.length;
  // A large subtree (spread as arguments below) is indexed by making the index again.
  if (at < 0 || nodes.length > index.all.length / 2) {
    indexes.delete(root);
    return;
  }
  index.all.splice(at, 0, ...nodes);
  // The nodes of one name in the new run go in together, after those of that name that come before the run.
  const byName = new Map<string, Node[]>();
  for (const each of nodes) {
    const same = byName.get(each.name);
    if (same) same.push(each);
    else byName.set(each.name, [each]);
  }
  for (const [name, added] of byName) {
    const same = index.byName.get(name);
    if (!same) {
      index.byName.set(name, added);
      continue;
    }
    let low = 0;
    let high = same.length;
    while (low < high) {
      const middle = (low + high) >> 1;
      if (index.all.indexOf(same[middle]) < at) low = middle + 1;
      else high = middle;
    }
    same.splice(low, 0, ...added);
  }
  index.edited += nodes.length;
}

/** Every node below `node` (itself included) in document order, walked. */
function walk(node: Node): Node[] {
  const result: Node[] = [];
  const stack = [node];
  while (stack.length > 0) {
    const next = stack.pop() as Node;
    result.push(next);
    for (let i = next.children.length - 1; i >= 0; i--) stack.push(next.children[i]);
  }
  return result;
}

/** Every node below `node` (itself included) in document order. */
export function allNodes(node: Node): Node[] {
  return node.parent ? walk(node) : indexOf(node).all.slice();
}

/** Every node below `node` (itself included) of that name, or of one of those names, in document order. */
export function named(node: Node, name: string | ReadonlySet<string>): Node[] {
  if (node.parent) {
    const all = walk(node);
    return typeof name === 'string' ? all.filter((each) => each.name === name) : all.filter((each) => name.has(each.name));
  }
  const index = indexOf(node);
  if (typeof name === 'string') return index.byName.get(name)?.slice() ?? [];
  return index.all.filter((each) => name.has(each.name));
}

/** A new node over `children` (a child still in a tree is moved out of it). */
export function makeNode(name: string, attributes: [string, string][] = [], children: Node[] = [], place?: Place): Node {
  const node: Node = { name, attributes, children, parent: undefined, place };
  for (const each of children) {
    removeNode(each);
    adopted(each);
    each.parent = node;
  }
  return node;
}

/**
 * A node that comes into a tree: a root (an index of its own would no longer see its changes); one still in a
 * tree stays in that tree's list of children too, as before, so neither tree's index can be kept.
 */
function entering(node: Node, index: NodeIndex | undefined, root: Node): NodeIndex | undefined {
  adopted(node);
  if (!node.parent) return index;
  indexes.delete(rootOf(node));
  indexes.delete(root);
  return undefined;
}

export function appendChild(parent: Node, node: Node, before?: Node): Node {
  const root = rootOf(parent);
  const index = entering(node, liveIndex(root), root);
  const children = parent.children as Node[];
  node.parent = parent;
  const position = before ? children.indexOf(before) : -1;
  if (position >= 0) children.splice(position, 0, node);
  else children.push(node);
  if (index) reindex(index, root, node);
  return node;
}

export function removeNode(node: Node): void {
  if (!node.parent) return;
  const root = rootOf(node);
  const index = liveIndex(root);
  if (index) unindex(index, root, node);
  const children = node.parent.children as Node[];
  const position = children.indexOf(node);
  if (position >= 0) children.splice(position, 1);
  node.parent = undefined;
}

/** Removes every child of `node`. */
export function removeChildren(node: Node): void {
  const root = rootOf(node);
  const index = liveIndex(root);
  const children = node.children as Node[];
  if (index) for (const each of children) unindex(index, root, each);
  for (const each of children.splice(0)) each.parent = undefined;
}

export function replaceNode(old: Node, replacement: Node): void {
  const parent = old.parent;
  if (!parent) return;
  const root = rootOf(parent);
  let index = liveIndex(root);
  if (index) unindex(index, root, old);
  index = entering(replacement, indexes.get(root), root);
  const children = parent.children as Node[];
  const position = children.indexOf(old);
  children[position] = replacement;
  replacement.parent = parent;
  old.parent = undefined;
  if (index) reindex(index, root, replacement);
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
    readonly name: string,
    public attributes: [string, string][],
    readonly children: Node[],
  ) {
    // Its children are made for it, so none has an index of its own.
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

/**
 * The tree as the parser's elements, for a check that reads a parsed document (the schema's) without writing
 * the tree out and reading it back. Offsets count the tags and attributes in document order, so findings sort
 * as they would in `serialize`'s text; there is no text, so an offset names no line. A node of `abridged`
 * (children all of one make) shows its first two children only.
 */
export function documentOf(root: Node, abridged?: ReadonlySet<Node>): { document: XmlDocument; nodeOf: Map<XmlElement, Node> } {
  const nodeOf = new Map<XmlElement, Node>();
  let offset = 0;
  const view = (node: Node, parent: XmlElement | undefined): XmlElement => {
    const start = offset++;
    const attributes: XmlAttribute[] = node.attributes.map(([name, value]) => {
      const nameStart = offset++;
      const valueStart = offset++;
      return { name, value, nameStart, nameEnd: nameStart, valueStart, valueEnd: valueStart, quote: '"' };
    });
    const element: XmlElement = {
      name: node.name,
      start,
      nameEnd: start,
      startTagEnd: offset++,
      end: 0,
      selfClosing: node.children.length === 0 && node.text === undefined,
      closed: true,
      attributes,
      children: [],
      parent,
    };
    nodeOf.set(element, node);
    const shown = abridged?.has(node) ? Math.min(2, node.children.length) : node.children.length;
    for (let i = 0; i < shown; i++) element.children.push(view(node.children[i], element));
    element.end = offset++;
    return element;
  };
  return { document: { text: '', root: view(root, undefined), problems: [], lines: new LineIndex('') }, nodeOf };
}
