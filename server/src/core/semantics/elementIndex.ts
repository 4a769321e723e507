import { attribute, forEachElement, ValueEdit, XmlElement } from '../xml';
import { SemanticModel } from './types';
import { coreMemo } from '../memos';

/** The document's elements by name, gathered once per model (the network checks each ask for a few names). */
const elementIndex = coreMemo<SemanticModel, Map<string, XmlElement[]>>('elementIndex');

export function elementsNamed(model: SemanticModel, name: string): XmlElement[] {
  let index = elementIndex.get(model);
  if (!index) {
    const byName = new Map<string, XmlElement[]>();
    if (model.document.root)
      forEachElement(model.document.root, (element) => {
        const list = byName.get(element.name);
        if (list) list.push(element);
        else byName.set(element.name, [element]);
      });
    index = byName;
    elementIndex.set(model, index);
  }
  return index.get(name) ?? [];
}

/** The children with a `name` attribute of one element that has two or more of them. */
export interface NamedSiblings {
  parent: XmlElement;
  children: XmlElement[];
}

const namedSiblingIndex = coreMemo<SemanticModel, NamedSiblings[]>('namedSiblings');

/**
 * Every element's children that have a `name` attribute, where two or more do, parents in document
 * order (the check of names unique on each level reads these, not every element of the tree).
 */
export function namedSiblings(model: SemanticModel): readonly NamedSiblings[] {
  let index = namedSiblingIndex.get(model);
  if (!index) {
    const found: NamedSiblings[] = [];
    if (model.document.root)
      forEachElement(model.document.root, (parent) => {
        if (parent.children.length < 2) return;
        const children = parent.children.filter((child) => attribute(child, 'name') !== undefined);
        if (children.length >= 2) found.push({ parent, children });
      });
    index = found;
    namedSiblingIndex.set(model, index);
  }
  return index;
}

/**
 * The index of a model carried over an in-value edit, from the previous model's: the same elements by
 * name in the same order, each its counterpart (most are shared with the previous tree), instead of a
 * walk of the whole tree on each keystroke.
 */
export function carryElementIndex(previous: SemanticModel, model: SemanticModel, edit: ValueEdit): void {
  carryNamedSiblings(previous, model, edit);
  const known = elementIndex.get(previous);
  if (!known) return;
  const index = new Map<string, XmlElement[]>();
  for (const [name, elements] of known) index.set(name, edit.counterparts(elements));
  elementIndex.set(model, index);
}

/** The same for `namedSiblings`: an in-value edit changes no element's name, children or attribute names. */
function carryNamedSiblings(previous: SemanticModel, model: SemanticModel, edit: ValueEdit): void {
  const known = namedSiblingIndex.get(previous);
  if (!known) return;
  namedSiblingIndex.set(
    model,
    known.map(({ parent, children }) => ({
      parent: edit.elementOf(parent),
      children: edit.counterparts(children),
    })),
  );
}
