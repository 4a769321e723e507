/** Where an action of the scenario tree acts: its actors, and what the Init sets for an actor. */
import { ancestor, attr, child, childrenNamed, named, Node } from './tree';

/** The first value `read` finds in the actor's Init Privates (the Storyboard's Init: the only place the schema has one). */
export function fromInit(tree: Node, actor: string, read: (privateNode: Node) => number | undefined): number | undefined {
  const storyboard = child(tree, 'Storyboard');
  const init = storyboard ? child(storyboard, 'Init') : undefined;
  const privates = init ? named(init, 'Private').filter((privateNode) => attr(privateNode, 'entityRef') === actor) : [];
  for (const privateNode of privates) {
    const found = read(privateNode);
    if (found !== undefined) return found;
  }
  return undefined;
}

/** The actor's speed set in its Init (an absolute SpeedAction): the nominal speed of a time gap, and where a speed profile starts. */
export function startSpeedOf(tree: Node, actor: string): number | undefined {
  return fromInit(tree, actor, (privateNode) => {
    const target = named(privateNode, 'AbsoluteTargetSpeed')[0];
    return target ? Number(attr(target, 'value')) : undefined;
  });
}

/** The entities an action of a storyboard acts on: its ManeuverGroup's Actors, or the Private of an Init action. */
export function actorsOf(node: Node): string[] {
  const privateNode = ancestor(node, 'Private');
  if (privateNode) return [attr(privateNode, 'entityRef') ?? ''];
  const group = ancestor(node, 'ManeuverGroup');
  const actors = group ? child(group, 'Actors') : undefined;
  return actors ? childrenNamed(actors, 'EntityRef').map((each) => attr(each, 'entityRef') ?? '') : [];
}
