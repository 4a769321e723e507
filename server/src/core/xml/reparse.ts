import { LineIndex } from '../text';
import { PLAIN_VALUE } from './characters';
import { parseXml } from './scanner';
import { XmlAttribute, XmlDocument, XmlElement } from './types';

/**
 * Parses `text` knowing `previous`, the same document before one edit. When the edit lies inside a
 * single attribute value and changes no markup, the tree is copied with shifted offsets instead of
 * scanning the text again (typing a value in a large file); otherwise this is `parseXml(text)`.
 */
export function reparseXml(previous: XmlDocument, text: string): XmlDocument {
  return reparseValueEdit(previous, text) ?? parseXml(text);
}

const MARKUP = /["'<>&\r\n]/;
const COMPARED_CHUNK = 1024;

/** The one region in which two texts differ (`[prefix, removedEnd)` of the old, `[prefix, insertedEnd)` of the new), when it holds no markup. */
export function markupFreeEdit(old: string, text: string): { prefix: number; removedEnd: number; insertedEnd: number } | undefined {
  const shorter = Math.min(old.length, text.length);
  // Equal chunks are skipped by the engine's string comparison, far faster than a loop over characters.
  let prefix = 0;
  while (prefix + COMPARED_CHUNK <= shorter && old.slice(prefix, prefix + COMPARED_CHUNK) === text.slice(prefix, prefix + COMPARED_CHUNK)) prefix += COMPARED_CHUNK;
  while (prefix < shorter && old.charCodeAt(prefix) === text.charCodeAt(prefix)) prefix++;
  let suffix = 0;
  const sameChunkBefore = (end: number) => old.slice(old.length - end - COMPARED_CHUNK, old.length - end) === text.slice(text.length - end - COMPARED_CHUNK, text.length - end);
  while (suffix + COMPARED_CHUNK <= shorter - prefix && sameChunkBefore(suffix)) suffix += COMPARED_CHUNK;
  while (suffix < shorter - prefix && old.charCodeAt(old.length - 1 - suffix) === text.charCodeAt(text.length - 1 - suffix)) suffix++;
  const removedEnd = old.length - suffix;
  const insertedEnd = text.length - suffix;
  if (MARKUP.test(old.slice(prefix, removedEnd)) || MARKUP.test(text.slice(prefix, insertedEnd))) return undefined;
  return { prefix, removedEnd, insertedEnd };
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
  while (element && !edited) {
    edited = element.attributes.find((candidate) => candidate.valueStart <= prefix && removedEnd <= candidate.valueEnd);
    if (edited) break;
    if (prefix < element.startTagEnd) return undefined;
    element = element.children.find((child) => child.start <= prefix && removedEnd <= child.end);
  }
  if (!edited) return undefined;
  const delta = insertedEnd - removedEnd;
  const raw = text.slice(edited.valueStart, edited.valueEnd + delta);
  if (!PLAIN_VALUE.test(raw)) return undefined;
  const shift = (offset: number) => (offset >= removedEnd && offset > prefix ? offset + delta : offset);
  const target = edited;
  const copy = (source: XmlElement, parent: XmlElement | undefined): XmlElement => {
    const result: XmlElement = {
      name: source.name,
      start: shift(source.start),
      nameEnd: shift(source.nameEnd),
      startTagEnd: shift(source.startTagEnd),
      end: shift(source.end),
      selfClosing: source.selfClosing,
      closed: source.closed,
      attributes: source.attributes.map((attribute) =>
        attribute === target
          ? { ...attribute, value: raw, valueEnd: attribute.valueEnd + delta }
          : {
              name: attribute.name,
              value: attribute.value,
              nameStart: shift(attribute.nameStart),
              nameEnd: shift(attribute.nameEnd),
              valueStart: shift(attribute.valueStart),
              valueEnd: shift(attribute.valueEnd),
              quote: attribute.quote,
            },
      ),
      children: [],
      parent,
    };
    for (const child of source.children) result.children.push(copy(child, result));
    return result;
  };
  const root = copy(previous.root, undefined);
  let lines: LineIndex | undefined;
  return {
    text,
    root,
    problems: [],
    entities: previous.entities,
    get lines() {
      lines ??= new LineIndex(text);
      return lines;
    },
  };
}
