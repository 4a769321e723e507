import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import { parseXml, reparseValueEdit, reparseXml, valueEditOf, XmlDocument, XmlElement } from '../../server/src/core/xml';
import { repoRoot } from '../support/paths';

/** Everything a consumer reads from a parse, as plain data. */
function shape(document: XmlDocument): unknown {
  const element = (node: XmlElement): unknown => [
    node.name,
    node.start,
    node.nameEnd,
    node.startTagEnd,
    node.end,
    node.selfClosing,
    node.closed,
    node.parent?.start ?? -1,
    node.attributes.map((a) => [a.name, a.value, a.nameStart, a.nameEnd, a.valueStart, a.valueEnd, a.quote]),
    node.children.map(element),
  ];
  return { root: document.root ? element(document.root) : null, problems: document.problems.length, text: document.text };
}

const original = fs.readFileSync(path.join(repoRoot, 'examples', 'main.xosc'), 'utf8');
const parsed = parseXml(original);
const values: { start: number; end: number }[] = [];
(function collect(node: XmlElement) {
  for (const a of node.attributes) values.push({ start: a.valueStart, end: a.valueEnd });
  node.children.forEach(collect);
})(parsed.root!);

describe('core: re-parsing after an edit', () => {
  it('gives the same tree as a full parse for edits inside one attribute value', () => {
    fc.assert(
      fc.property(
        fc.nat(values.length - 1),
        fc.nat(),
        fc.nat(),
        fc.string({ unit: fc.constantFrom('1', '2', '.', '-', 'a', 'Z', ' ', 'é', '中'), maxLength: 4 }),
        (which, from, length, inserted) => {
          const value = values[which];
          const start = value.start + (from % (value.end - value.start + 1));
          const end = Math.min(value.end, start + (length % 3));
          const edited = original.slice(0, start) + inserted + original.slice(end);
          const fast = reparseValueEdit(parsed, edited);
          assert.ok(fast, 'an edit inside a value takes the fast path');
          assert.deepEqual(shape(fast), shape(parseXml(edited)));
        },
      ),
      { numRuns: 300 },
    );
  });

  it('shares the subtrees before the edit, and every parent is the element holding it, edit after edit', () => {
    const valuesOf = (document: XmlDocument) => {
      const found: { start: number; end: number }[] = [];
      (function collect(node: XmlElement) {
        for (const a of node.attributes) found.push({ start: a.valueStart, end: a.valueEnd });
        node.children.forEach(collect);
      })(document.root!);
      return found;
    };
    const parentsHold = (node: XmlElement): boolean => node.children.every((child) => child.parent === node && parentsHold(child));
    fc.assert(
      fc.property(
        fc.array(
          fc.record({ which: fc.nat(), from: fc.nat(), inserted: fc.string({ unit: fc.constantFrom('1', '.', 'a'), maxLength: 3 }) }),
          {
            minLength: 1,
            maxLength: 5,
          },
        ),
        (edits) => {
          let document = parseXml(original);
          for (const { which, from, inserted } of edits) {
            const candidates = valuesOf(document);
            const value = candidates[which % candidates.length];
            const start = value.start + (from % (value.end - value.start + 1));
            const edited = document.text.slice(0, start) + inserted + document.text.slice(start);
            const next = reparseValueEdit(document, edited);
            assert.ok(next, 'an edit inside a value takes the fast path');
            assert.deepEqual(shape(next), shape(parseXml(edited)));
            assert.ok(parentsHold(next.root!), 'each child names its parent in the new tree');
            const before = document.root!.children.filter((child) => child.end <= start);
            for (const child of before) assert.ok(next.root!.children.includes(child), 'a subtree before the edit is shared');
            document = next;
          }
        },
      ),
      { numRuns: 200 },
    );
  });

  it('maps every element of the previous tree to its counterpart: itself when it does not hold the edit and its offsets stay, else its copy', () => {
    const elementsOf = (document: XmlDocument) => {
      const found: XmlElement[] = [];
      (function collect(node: XmlElement) {
        found.push(node);
        node.children.forEach(collect);
      })(document.root!);
      return found;
    };
    const before = elementsOf(parsed);
    const edits = [values[0], values[Math.floor(values.length / 2)], values[values.length - 1]].flatMap((value) => [
      { value, typed: value.end - value.start === 1 ? '78' : '7' },
      // Typing over characters keeps the text's length: nothing after the edit moves.
      ...(value.end > value.start ? [{ value, typed: '7'.repeat(value.end - value.start) }] : []),
    ]);
    for (const { value, typed } of edits) {
      const edited = original.slice(0, value.start) + typed + original.slice(value.end);
      const kept = typed.length === value.end - value.start;
      const document = reparseValueEdit(parsed, edited);
      assert.ok(document);
      const edit = valueEditOf(document);
      assert.ok(edit, 'the re-parse keeps how it was made');
      const after = elementsOf(document);
      assert.equal(after.length, before.length);
      // In document order, the counterpart of the n-th element is the n-th element of the new tree.
      before.forEach((element, index) => {
        const counterpart = edit.elementOf(element);
        assert.equal(counterpart, after[index], `element ${index} (<${element.name}> at ${element.start})`);
        assert.equal(
          counterpart === element,
          element.end <= value.start || (kept && element.start >= value.end),
          `shared exactly when wholly before the edit, or after it with the length kept: ${index}`,
        );
      });
      // An index in document order (all elements, those of one name, the few before the edit) maps as elementOf does, kept as it is when every one is shared.
      const byName = new Map<string, XmlElement[]>();
      for (const element of before) byName.set(element.name, [...(byName.get(element.name) ?? []), element]);
      for (const list of [before, ...byName.values(), before.filter((element) => element.end <= value.start)]) {
        const counterparts = edit.counterparts(list);
        assert.deepEqual(
          counterparts.map((element) => after.indexOf(element)),
          list.map((element) => after.indexOf(edit.elementOf(element))),
        );
        assert.equal(
          counterparts === list,
          list.every((element) => edit.elementOf(element) === element),
        );
      }
    }
  });

  it('falls back to a full parse for any other edit, markup included', () => {
    fc.assert(
      fc.property(
        fc.nat(original.length),
        fc.nat(6),
        fc.string({ unit: fc.constantFrom('<', '>', '"', "'", '&', '\n', 'x', ' ', '/', '='), maxLength: 4 }),
        (start, length, inserted) => {
          const edited = original.slice(0, start) + inserted + original.slice(Math.min(original.length, start + length));
          assert.deepEqual(shape(reparseXml(parsed, edited)), shape(parseXml(edited)));
        },
      ),
      { numRuns: 300 },
    );
  });

  it('copies the tree rather than scanning it again when a value changes', () => {
    const at = original.indexOf('value="27.5"') + 'value="'.length;
    const edited = original.slice(0, at) + '3' + original.slice(at + 2);
    assert.equal(
      reparseValueEdit(parsed, edited.replace('<Entities>', '<Entities >')),
      undefined,
      'a second edit, in markup, is not taken',
    );
    assert.equal(
      reparseValueEdit(parsed, original.slice(0, at) + '"' + original.slice(at)),
      undefined,
      'a quote typed into a value is not taken',
    );
    const document = reparseXml(parsed, edited);
    assert.notEqual(document.root, parsed.root, 'a new tree, so caches keyed by the old one never apply to it');
    assert.equal(parsed.root!.children.length, document.root!.children.length);
    assert.equal(reparseXml(parsed, original), parsed, 'unchanged text gives the same document');
  });
});
