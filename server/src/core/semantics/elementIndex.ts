import { forEachElement, ValueEdit, XmlElement } from '../xml';
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

/**
 * The index of a model carried over an in-value edit, from the previous model's: the same elements by
 * name in the same order, each its counterpart (most are shared with the previous tree), instead of a
 * walk of the whole tree on each keystroke.
 */
export function carryElementIndex(previous: SemanticModel, model: SemanticModel, edit: ValueEdit): void {
  const known = elementIndex.get(previous);
  if (!known) return;
  const index = new Map<string, XmlElement[]>();
  // In document order: when the last is shared, so is every one, and the list is the previous one.
  for (const [name, elements] of known)
    index.set(name, edit.shared(elements[elements.length - 1]) ? elements : elements.map(edit.elementOf));
  elementIndex.set(model, index);
}
