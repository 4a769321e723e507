import { strict as assert } from 'node:assert';
import {
  allNodes,
  appendChild,
  cloneNode,
  makeNode,
  named,
  Node,
  removeChildren,
  removeNode,
  replaceNode,
} from '../../server/src/core/export/tree';

/** The nodes of a tree in document order, walked here without the module's index. */
function walked(node: Node): Node[] {
  return [node, ...node.children.flatMap(walked)];
}

/** named() and allNodes() of the root agree with a walk of the tree as it is now, for every name in it. */
function assertIndexTrue(root: Node, names: readonly string[]): void {
  assert.deepEqual(allNodes(root), walked(root));
  for (const name of names)
    assert.deepEqual(
      named(root, name),
      walked(root).filter((each) => each.name === name),
      name,
    );
  const some = new Set(names.slice(0, 2));
  assert.deepEqual(
    named(root, some),
    walked(root).filter((each) => some.has(each.name)),
  );
}

const NAMES = ['A', 'B', 'C', 'D'];

/** A small tree: each level's children named in turn from NAMES. */
function tree(depth: number, width: number, salt = 0): Node {
  const children = depth === 0 ? [] : Array.from({ length: width }, (_, i) => tree(depth - 1, width, salt + i + 1));
  return makeNode(NAMES[salt % NAMES.length], [['at', String(salt)]], children);
}

// The export asks for the nodes of a name between its changes; the index it keeps must follow every change of structure.
describe('export tree: the index of nodes by name follows the changes', () => {
  it('after appends (at the end and before a sibling), removals, replacements and emptied parents', () => {
    const root = tree(3, 3);
    assertIndexTrue(root, NAMES);
    const inner = root.children[1];
    appendChild(inner, tree(1, 2, 7));
    assertIndexTrue(root, NAMES);
    appendChild(inner, makeNode('D'), inner.children[0]);
    assertIndexTrue(root, NAMES);
    appendChild(root.children[0].children[2], makeNode('A', [], [makeNode('B')]));
    assertIndexTrue(root, NAMES);
    removeNode(root.children[2].children[0]);
    assertIndexTrue(root, NAMES);
    replaceNode(root.children[0].children[1], tree(2, 2, 3));
    assertIndexTrue(root, NAMES);
    removeChildren(root.children[2]);
    assertIndexTrue(root, NAMES);
    appendChild(root, makeNode('C'));
    appendChild(root, makeNode('B'), root.children[0]);
    assertIndexTrue(root, NAMES);
  });

  it('after nodes move within the tree, into another tree, and out of a root that had an index of its own', () => {
    const root = tree(3, 2);
    const other = tree(2, 2, 2);
    assertIndexTrue(root, NAMES);
    assertIndexTrue(other, NAMES);
    // makeNode moves its children out of their tree.
    const wrapper = makeNode('D', [], [root.children[0].children[1], other.children[0]]);
    assertIndexTrue(root, NAMES);
    assertIndexTrue(other, NAMES);
    assertIndexTrue(wrapper, NAMES);
    // A root with an index becomes a child: the tree it joins sees it, and later changes below it.
    appendChild(root.children[1], wrapper);
    assertIndexTrue(root, NAMES);
    removeNode(wrapper.children[0]);
    assertIndexTrue(root, NAMES);
    const copy = cloneNode(root.children[1]);
    assertIndexTrue(copy, NAMES);
    replaceNode(root.children[0], copy);
    assertIndexTrue(root, NAMES);
  });

  it('after many changes between two questions, and a subtree larger than the rest', () => {
    const root = tree(2, 3);
    assertIndexTrue(root, NAMES);
    for (let i = 0; i < 40; i++)
      appendChild(root.children[i % 3], makeNode(NAMES[i % 4]), i % 2 ? root.children[i % 3].children[0] : undefined);
    assertIndexTrue(root, NAMES);
    appendChild(root.children[2], tree(4, 3, 1));
    assertIndexTrue(root, NAMES);
    for (const each of named(root, 'B')) removeNode(each);
    assertIndexTrue(root, NAMES);
  });
});
