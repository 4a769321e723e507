import { LineIndex, partitionPoint } from '../text';
import { PLAIN_VALUE } from './characters';
import { parseXml } from './scanner';
import { XmlAttribute, XmlDocument, XmlElement } from './types';
import { coreMemo } from '../memos';
import { carryTextSearches } from './textSearch';

/**
 * Parses `text` knowing `previous`, the same document before one edit. When the edit lies inside a
 * single attribute value and changes no markup, the tree is copied with shifted offsets instead of
 * scanning the text again (typing a value in a large file); otherwise this is `parseXml(text)`.
 * Subtrees wholly before the edit are not copied: the new tree shares them (their roots' `parent`
 * then names the new tree's element, so the previous tree is only read through `valueEditOf`); so are
 * those wholly after it when the edit keeps the text's length (typing over characters moves no offset).
 */
export function reparseXml(previous: XmlDocument, text: string): XmlDocument {
  return reparseValueEdit(previous, text) ?? parseXml(text);
}

const MARKUP = /["'<>&\r\n]/;
const COMPARED_CHUNK = 1024;

/**
 * How far from 0 the spans `same(from, size)` compares stay equal, up to `limit`: at most COMPARED_CHUNK short of
 * the first difference. Spans double while equal and halve after a difference, so a keystroke in a large text
 * compares a few dozen spans, not one per KiB (each span compared is two slices allocated).
 */
function equalRun(limit: number, same: (from: number, size: number) => boolean): number {
  let done = 0;
  let size = COMPARED_CHUNK;
  while (done + size <= limit && same(done, size)) {
    done += size;
    size *= 2;
  }
  // The difference (or the limit) lies in [done, done + size): halves of it that are equal are passed.
  while (size > COMPARED_CHUNK) {
    size /= 2;
    if (done + size <= limit && same(done, size)) done += size;
  }
  return done;
}

/** The one region in which two texts differ (`[prefix, removedEnd)` of the old, `[prefix, insertedEnd)` of the new), when it holds no markup. */
export function markupFreeEdit(old: string, text: string): { prefix: number; removedEnd: number; insertedEnd: number } | undefined {
  const shorter = Math.min(old.length, text.length);
  // Equal spans are skipped by the engine's string comparison, far faster than a loop over characters.
  let prefix = equalRun(shorter, (from, size) => old.slice(from, from + size) === text.slice(from, from + size));
  while (prefix < shorter && old.charCodeAt(prefix) === text.charCodeAt(prefix)) prefix++;
  let suffix = equalRun(
    shorter - prefix,
    (from, size) => old.slice(old.length - from - size, old.length - from) === text.slice(text.length - from - size, text.length - from),
  );
  while (suffix < shorter - prefix && old.charCodeAt(old.length - 1 - suffix) === text.charCodeAt(text.length - 1 - suffix)) suffix++;
  const removedEnd = old.length - suffix;
  const insertedEnd = text.length - suffix;
  if (MARKUP.test(old.slice(prefix, removedEnd)) || MARKUP.test(text.slice(prefix, insertedEnd))) return undefined;
  return { prefix, removedEnd, insertedEnd };
}

/**
 * How a parse came from the previous one by an edit inside one attribute value: the same elements and
 * attributes in the same places, offsets from `removedEnd` on moved by `delta`, one value changed.
 * Models of the previous parse can be carried over instead of being built again (`valueEditOf`).
 */
export interface ValueEdit {
  previous: XmlDocument;
  /** Offsets in the previous text: the edit replaced `[prefix, removedEnd)`. */
  prefix: number;
  removedEnd: number;
  /** How far offsets at or after `removedEnd` moved. */
  delta: number;
  /** The element holding the edited attribute, in the previous tree and in the new one. */
  previousElement: XmlElement;
  element: XmlElement;
  previousAttribute: XmlAttribute;
  attribute: XmlAttribute;
  /** The new tree's counterpart of an element of the previous tree. */
  elementOf(previous: XmlElement): XmlElement;
  /** Whether an element of the previous tree is in the new one too (not holding the edit, and before it unless nothing moved): what refers only to it carries over as it is. */
  shared(previous: XmlElement): boolean;
  /**
   * The counterparts of elements of the previous tree listed in document order (an index of the tree):
   * the list itself when the new tree shares every one. Only the elements holding the edit, and those
   * after it when it moved them, are looked at: a keystroke does not walk every element of a large index.
   */
  counterparts(elements: XmlElement[]): XmlElement[];
  /**
   * The same for an index whose entries name an element each, in document order of their elements (several
   * entries may name one): each entry naming an element not shared replaced by `carry(entry)`, the list itself when none is.
   */
  carriedEntries<T>(entries: T[], elementOfEntry: (entry: T) => XmlElement, carry: (entry: T) => T): T[];
  /** The new tree's counterpart of an attribute of an element of the previous tree. */
  attributeOf(previousElement: XmlElement, previous: XmlAttribute): XmlAttribute;
  /** An offset of the previous text in the new text. */
  shift(offset: number): number;
}

// Only the latest parse of a chain keeps its edit (and so the previous tree): older ones are forgotten.
const valueEdits = coreMemo<XmlDocument, ValueEdit>('previousParseOfValueEdit');

/** The value edit that made `document` from its previous parse, until `forgetValueEdit`. */
export function valueEditOf(document: XmlDocument): ValueEdit | undefined {
  return valueEdits.get(document);
}

/** Lets the previous parse go once the models that could reuse it are built. */
export function forgetValueEdit(document: XmlDocument): void {
  valueEdits.delete(document);
}

/** The child whose range holds `offset`, by its index (children are ordered by offset and do not overlap). */
function childIndexAt(element: XmlElement, offset: number): number {
  const children = element.children;
  let low = 0;
  let high = children.length - 1;
  while (low <= high) {
    const middle = (low + high) >> 1;
    const child = children[middle];
    if (offset < child.start) high = middle - 1;
    else if (offset >= child.end) low = middle + 1;
    else return middle;
  }
  return -1;
}

/** The fast path of reparseXml: undefined unless the edit lies inside one attribute value. */
export function reparseValueEdit(previous: XmlDocument, text: string): XmlDocument | undefined {
  const old = previous.text;
  if (!previous.root || previous.problems.length > 0) return undefined;
  if (old === text) return previous;
  const edit = markupFreeEdit(old, text);
  if (!edit) return undefined;
  const { prefix, removedEnd, insertedEnd } = edit;
  // The attribute whose value holds the whole edit (its ends may touch the quotes, not cross them).
  let element: XmlElement | undefined = previous.root;
  let edited: XmlAttribute | undefined;
  // The elements holding the edit, outermost first: the only ones copied when nothing moves.
  const holding: XmlElement[] = [];
  while (element && !edited) {
    holding.push(element);
    edited = element.attributes.find((candidate) => candidate.valueStart <= prefix && removedEnd <= candidate.valueEnd);
    if (edited) break;
    if (prefix < element.startTagEnd) return undefined;
    // By halves: an element may have thousands of children (the Init actions of a large file).
    const index = childIndexAt(element, prefix);
    const child: XmlElement | undefined = index < 0 ? undefined : element.children[index];
    element = child && removedEnd <= child.end ? child : undefined;
  }
  if (!edited || !element) return undefined;
  const delta = insertedEnd - removedEnd;
  const raw = text.slice(edited.valueStart, edited.valueEnd + delta);
  if (!PLAIN_VALUE.test(raw)) return undefined;
  const shift = (offset: number) => (offset >= removedEnd && offset > prefix ? offset + delta : offset);
  // Offsets after the edit move unless its length is kept (typing over characters): then only the elements holding it are copied.
  const shared = (source: XmlElement) => source.end <= prefix || (delta === 0 && source.start >= removedEnd);
  const target = edited;
  const editedElement = element;
  let editedCopy: XmlAttribute | undefined;
  // Attributes hold no parent, so those the edit does not move are shared with the previous tree.
  const copyAttributes = (attributes: XmlAttribute[]): XmlAttribute[] => {
    let moved = false;
    for (const attribute of attributes) if (attribute === target || attribute.nameStart >= removedEnd) moved = true;
    if (!moved) return attributes;
    return attributes.map((attribute) => {
      if (attribute === target) return (editedCopy = { ...attribute, value: raw, valueEnd: attribute.valueEnd + delta });
      if (attribute.nameStart < removedEnd || delta === 0) return attribute;
      return {
        name: attribute.name,
        value: attribute.value,
        nameStart: attribute.nameStart + delta,
        nameEnd: attribute.nameEnd + delta,
        valueStart: attribute.valueStart + delta,
        valueEnd: attribute.valueEnd + delta,
        quote: attribute.quote,
      };
    });
  };
  // Each copied element's copy, for the models carried over: one lookup each (walking both trees by child index cost more, above all before V8 compiled it).
  const copies = new Map<XmlElement, XmlElement>();
  const copy = (source: XmlElement, parent: XmlElement | undefined): XmlElement => {
    // A subtree not holding the edit, whose offsets do not move, keeps its values: shared, only its root taking the new parent.
    if (parent && shared(source)) {
      source.parent = parent;
      return source;
    }
    const result: XmlElement = {
      name: source.name,
      start: shift(source.start),
      nameEnd: shift(source.nameEnd),
      startTagEnd: shift(source.startTagEnd),
      end: shift(source.end),
      selfClosing: source.selfClosing,
      closed: source.closed,
      attributes: copyAttributes(source.attributes),
      children: [],
      parent,
    };
    copies.set(source, result);
    for (const child of source.children) result.children.push(copy(child, result));
    return result;
  };
  const root = copy(previous.root, undefined);
  const movedFrom = delta === 0 ? undefined : removedEnd;
  const document = documentOf(text, root, previous.entities);
  const elementOf = counterpartsIn(copies, shared);
  const newElement = elementOf(editedElement);
  valueEdits.delete(previous);
  valueEdits.set(document, {
    previous,
    prefix,
    removedEnd,
    delta,
    previousElement: editedElement,
    element: newElement,
    previousAttribute: target,
    attribute: editedCopy as XmlAttribute,
    elementOf,
    shared,
    counterparts: (elements) => carriedInOrder(elements, (element) => element, elementOf, holding, movedFrom),
    carriedEntries: (entries, elementOfEntry, carry) => carriedInOrder(entries, elementOfEntry, carry, holding, movedFrom),
    attributeOf: (sourceElement, source) =>
      (source.nameStart < removedEnd || delta === 0) && source !== target
        ? source
        : elementOf(sourceElement).attributes[sourceElement.attributes.indexOf(source)],
    shift,
  });
  carryTextSearches(previous, document, prefix, removedEnd, insertedEnd);
  return document;
}

// Built outside reparseValueEdit: a closure there would keep the previous tree alive through the new document.
function documentOf(text: string, root: XmlElement, entities: ReadonlyMap<string, string> | undefined): XmlDocument {
  let lines: LineIndex | undefined;
  return {
    text,
    root,
    problems: [],
    entities,
    get lines() {
      lines ??= new LineIndex(text);
      return lines;
    },
  };
}

/**
 * `entries` (naming elements of the previous tree, in document order) with each one naming an element not
 * shared replaced by `carry(entry)`: an element of `holding` (those holding the edit), or one starting at or
 * after `movedFrom` when the edit moved them. Found by halves, as an element's start is unique and grows in document order.
 */
function carriedInOrder<T>(
  entries: T[],
  elementOfEntry: (entry: T) => XmlElement,
  carry: (entry: T) => T,
  holding: readonly XmlElement[],
  movedFrom: number | undefined,
): T[] {
  let result: T[] | undefined;
  const firstStartingAt = (offset: number) => partitionPoint(entries.length, (index) => elementOfEntry(entries[index]).start < offset);
  for (const element of holding)
    for (let index = firstStartingAt(element.start); index < entries.length && elementOfEntry(entries[index]) === element; index++)
      (result ??= entries.slice())[index] = carry(entries[index]);
  if (movedFrom !== undefined)
    for (let index = firstStartingAt(movedFrom); index < entries.length; index++)
      (result ??= entries.slice())[index] = carry(entries[index]);
  return result ?? entries;
}

/** The counterpart of an element of the previous tree: itself when shared (not holding the edit, its offsets kept), else its copy. */
function counterpartsIn(
  copies: ReadonlyMap<XmlElement, XmlElement>,
  shared: (source: XmlElement) => boolean,
): (source: XmlElement) => XmlElement {
  return (source) => {
    if (shared(source)) return source;
    const counterpart = copies.get(source);
    if (!counterpart) throw new Error(`no element at ${source.start} in the previous parse`);
    return counterpart;
  };
}
