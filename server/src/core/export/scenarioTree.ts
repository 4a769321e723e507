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

/** What can change an actor's speed once the story runs: longitudinal actions, trajectories with timing, synchronization and controllers. */
const SPEED_CHANGING: ReadonlySet<string> = new Set([
  'SpeedAction',
  'SpeedProfileAction',
  'LongitudinalDistanceAction',
  'SynchronizeAction',
  'FollowTrajectoryAction',
  'ControllerAction',
  'ActivateControllerAction',
  'AssignControllerAction',
  'OverrideControllerValueAction',
]);

/**
 * The speed the actor keeps for the whole run, when that is certain: its Init sets it at once (a step) and nothing
 * else can change it (no controller of its own, no other speed-changing action on it but `except`), else undefined.
 */
export function constantSpeedOf(tree: Node, actor: string, except?: Node): number | undefined {
  const storyboard = child(tree, 'Storyboard');
  const init = storyboard ? child(storyboard, 'Init') : undefined;
  if (!storyboard || !init) return undefined;
  const object = named(tree, 'ScenarioObject').find((each) => attr(each, 'name') === actor);
  if (!object || child(object, 'ObjectController')) return undefined;
  let speed: number | undefined;
  for (const privateNode of named(init, 'Private').filter((each) => attr(each, 'entityRef') === actor))
    for (const action of named(privateNode, SPEED_CHANGING)) {
      const target = action.name === 'SpeedAction' ? named(action, 'AbsoluteTargetSpeed')[0] : undefined;
      const dynamics = action.name === 'SpeedAction' ? named(action, 'SpeedActionDynamics')[0] : undefined;
      if (!target || speed !== undefined || (dynamics && attr(dynamics, 'dynamicsShape') !== 'step')) return undefined;
      speed = Number(attr(target, 'value'));
    }
  if (speed === undefined || !Number.isFinite(speed)) return undefined;
  for (const story of childrenNamed(storyboard, 'Story'))
    for (const action of named(story, SPEED_CHANGING)) {
      if (action === except) continue;
      const group = ancestor(action, 'ManeuverGroup');
      const actors = group ? child(group, 'Actors') : undefined;
      // Triggering entities are known only when the run decides them: any of them may be this actor.
      if (!actors || attr(actors, 'selectTriggeringEntities') === 'true' || actorsOf(action).includes(actor)) return undefined;
    }
  return speed;
}
