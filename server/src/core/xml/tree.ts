import { XmlAttribute, XmlDocument, XmlElement } from './types';

export function attribute(element: XmlElement, name: string): XmlAttribute | undefined {
  // An index loop: for...of makes an iterator per call, and this is called for nearly every element read.
  const attributes = element.attributes;
  for (let i = 0; i < attributes.length; i++) if (attributes[i].name === name) return attributes[i];
  return undefined;
}

export function attributeValue(element: XmlElement, name: string): string | undefined {
  return attribute(element, name)?.value;
}

/** Calls `visit` on `element` and every element below it, in document order, without an array of them all. */
export function forEachElement(element: XmlElement, visit: (element: XmlElement) => void): void {
  const stack: XmlElement[] = [element];
  while (stack.length > 0) {
    const next = stack.pop() as XmlElement;
    visit(next);
    for (let i = next.children.length - 1; i >= 0; i--) stack.push(next.children[i]);
  }
}

/** Every element below `element`, in document order (an array: generators are slow on hot paths). */
export function descendants(element: XmlElement): XmlElement[] {
  const result: XmlElement[] = [];
  forEachElement(element, (next) => {
    if (next !== element) result.push(next);
  });
  return result;
}

/** The first element below `element` of a name, in document order (the walk stops there). */
export function firstDescendant(element: XmlElement, name: string): XmlElement | undefined {
  const stack: XmlElement[] = [];
  for (let i = element.children.length - 1; i >= 0; i--) stack.push(element.children[i]);
  while (stack.length > 0) {
    const next = stack.pop() as XmlElement;
    if (next.name === name) return next;
    for (let i = next.children.length - 1; i >= 0; i--) stack.push(next.children[i]);
  }
  return undefined;
}

/** The innermost element whose tag range contains the offset. */
export function elementAt(document: XmlDocument, offset: number): XmlElement | undefined {
  let current = document.root;
  if (!current || offset < current.start || offset > current.end) return undefined;
  for (;;) {
    const child: XmlElement | undefined = current.children.find((c) => offset >= c.start && offset <= c.end);
    if (!child) return current;
    current = child;
  }
}

/** What escapeAttributeValue changes: most values have none of it, and are returned as they are without seven passes. */
const ATTRIBUTE_SPECIALS = /[&<>"'\t\n\r]/;

/** Escapes text for use inside an attribute value delimited by `quote`. */
export function escapeAttributeValue(value: string, quote: '"' | "'" = '"'): string {
  if (!ATTRIBUTE_SPECIALS.test(value)) return value;
  let escaped = value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
  escaped = quote === '"' ? escaped.replace(/"/g, '&quot;') : escaped.replace(/'/g, '&apos;');
  return escaped.replace(/\t/g, '&#9;').replace(/\n/g, '&#10;').replace(/\r/g, '&#13;');
}

export function isWellFormed(document: XmlDocument): boolean {
  return !document.problems.some((problem) => problem.severity === 'error');
}

/** The element and every element below it, in document order. */
export function selfAndDescendants(element: XmlElement): XmlElement[] {
  const result = descendants(element);
  result.unshift(element);
  return result;
}

/** The element of the tree that starts exactly at an offset. */
export function elementStartingAt(root: XmlElement | undefined, offset: number): XmlElement | undefined {
  let current = root;
  while (current) {
    if (current.start === offset) return current;
    current = current.children.find((child) => offset >= child.start && offset < child.end);
  }
  return undefined;
}

/** Offset of the `</` of a closed element that is not self-closing (its end tag may hold whitespace: `</Act >`). */
export function endTagStart(text: string, element: XmlElement): number {
  return text.lastIndexOf('</', element.end - 1);
}

/** Whether `element` is `ancestor` or lies below it. */
export function isWithin(element: XmlElement, ancestor: XmlElement): boolean {
  for (let current: XmlElement | undefined = element; current; current = current.parent) if (current === ancestor) return true;
  return false;
}
