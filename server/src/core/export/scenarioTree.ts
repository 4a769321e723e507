/** Where an action of the scenario tree acts: its actors, and what the Init sets for an actor. */
import { ancestor, attr, child, childrenNamed, named, Node } from './tree';

/** The first value `read` finds in the actor's Init Privates (the Storyboard's Init: the only place the schema has one). */
export function fromInit<T>(tree: Node, actor: string, read: (privateNode: Node) => T | undefined): T | undefined {
  const storyboard = child(tree, 'Storyboard');
  const init = storyboard ? child(storyboard, 'Init') : undefined;
  const privates = init ? named(init, 'Private').filter((privateNode) => attr(privateNode, 'entityRef') === actor) : [];
  for (const privateNode of privates) {
    const found = read(privateNode);
    if (found !== undefined) return found;
  }
  return undefined;
}

/** The entity of that name (a ScenarioObject of the Entities), if the scenario has one. */
export function scenarioObjectOf(tree: Node, name: string): Node | undefined {
  const entities = child(tree, 'Entities');
  return entities ? childrenNamed(entities, 'ScenarioObject').find((each) => attr(each, 'name') === name) : undefined;
}

/** The actor's speed set in its Init (an absolute SpeedAction): the nominal speed of a time gap, and where a speed profile starts. */
export function startSpeedOf(tree: Node, actor: string, through: ReadonlySet<string> = new Set()): number | undefined {
  return fromInit(tree, actor, (privateNode) => {
    const absolute = named(privateNode, 'AbsoluteTargetSpeed')[0];
    if (absolute) return Number(attr(absolute, 'value'));
    // esmini starts a speed relative to another entity from that entity's Init speed (ALKS's targets: the ego's less a delta).
    const relative = named(privateNode, 'RelativeTargetSpeed')[0];
    const reference = relative ? (attr(relative, 'entityRef') ?? '') : '';
    const from = relative && !through.has(reference) ? startSpeedOf(tree, reference, new Set([...through, actor])) : undefined;
    return relative && from !== undefined ? relativeSpeed(relative, from) : undefined;
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

/**
 * Whether a story action may act on `actor`: its ManeuverGroup names it, or names no actors, or takes them from the
 * triggering entities, which are known only when the run decides them (any of them may be this actor).
 */
export function mayActOn(action: Node, actor: string): boolean {
  const group = ancestor(action, 'ManeuverGroup');
  const actors = group ? child(group, 'Actors') : undefined;
  return !actors || attr(actors, 'selectTriggeringEntities') === 'true' || actorsOf(action).includes(actor);
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

/** Actions a speed question leaves out: one (the action asking), or several (also those known to start only after it). */
export type Excepted = Node | ReadonlySet<Node>;

function isExcepted(action: Node, except: Excepted | undefined): boolean {
  return except instanceof Set ? except.has(action) : action === except;
}

/**
 * The speed the actor keeps for the whole run, when that is certain: its Init sets it at once (a step) and nothing
 * else can change it (no controller of its own, no other speed-changing action on it but `except`), else undefined.
 */
export function constantSpeedOf(
  tree: Node,
  actor: string,
  except?: Excepted,
  through: ReadonlySet<string> = new Set(),
): number | undefined {
  const storyboard = child(tree, 'Storyboard');
  const init = storyboard ? child(storyboard, 'Init') : undefined;
  if (!storyboard || !init) return undefined;
  const object = scenarioObjectOf(tree, actor);
  if (!object || child(object, 'ObjectController')) return undefined;
  let speed: number | undefined;
  for (const privateNode of named(init, 'Private').filter((each) => attr(each, 'entityRef') === actor))
    for (const action of named(privateNode, SPEED_CHANGING)) {
      if (!changesSpeed(action)) continue;
      const dynamics = action.name === 'SpeedAction' ? named(action, 'SpeedActionDynamics')[0] : undefined;
      if (action.name !== 'SpeedAction' || speed !== undefined || (dynamics && attr(dynamics, 'dynamicsShape') !== 'step'))
        return undefined;
      speed = initTargetSpeed(tree, action, actor, through);
    }
  if (speed === undefined || !Number.isFinite(speed)) return undefined;
  return storySpeedChangesOf(tree, actor, except).length === 0 ? speed : undefined;
}

/** The story's actions that may change the actor's speed once the story runs, but `except`, in document order. */
export function storySpeedChangesOf(tree: Node, actor: string, except?: Excepted): Node[] {
  const storyboard = child(tree, 'Storyboard');
  const found: Node[] = [];
  for (const story of storyboard ? childrenNamed(storyboard, 'Story') : [])
    for (const action of named(story, SPEED_CHANGING))
      if (!isExcepted(action, except) && changesSpeed(action) && mayActOn(action, actor)) found.push(action);
  return found;
}

/**
 * The one speed the story gives an actor that stands until then: no speed-changing action in its Init, no controller of its
 * own, and of its story's speed-changing actions (but `except`) only one, a step SpeedAction to an absolute speed; else undefined.
 */
export function storySpeedOf(tree: Node, actor: string, except?: Excepted): { speed: number; action: Node } | undefined {
  const storyboard = child(tree, 'Storyboard');
  const init = storyboard ? child(storyboard, 'Init') : undefined;
  const object = scenarioObjectOf(tree, actor);
  if (!storyboard || !object || child(object, 'ObjectController')) return undefined;
  const inInit = init ? named(init, 'Private').filter((each) => attr(each, 'entityRef') === actor) : [];
  if (inInit.some((privateNode) => named(privateNode, SPEED_CHANGING).some(changesSpeed))) return undefined;
  const found = storySpeedChangesOf(tree, actor, except);
  const [action] = found;
  if (found.length !== 1 || action.name !== 'SpeedAction' || actorsOf(action).length !== 1) return undefined;
  const dynamics = named(action, 'SpeedActionDynamics')[0];
  const absolute = named(action, 'AbsoluteTargetSpeed')[0];
  const speed = Number(absolute ? attr(absolute, 'value') : NaN);
  if (!dynamics || attr(dynamics, 'dynamicsShape') !== 'step' || !Number.isFinite(speed)) return undefined;
  return { speed, action };
}

/** A trajectory without timing is followed at the speed the actor has (the standard ignores its vertex times): it changes no speed. */
function changesSpeed(action: Node): boolean {
  return action.name !== 'FollowTrajectoryAction' || child(child(action, 'TimeReference') ?? action, 'Timing') !== undefined;
}

/** An Init SpeedAction's target: absolute, or relative to an entity whose own speed is constant (esmini sets it once at the start). */
function initTargetSpeed(tree: Node, action: Node, actor: string, through: ReadonlySet<string>): number | undefined {
  const absolute = named(action, 'AbsoluteTargetSpeed')[0];
  if (absolute) return Number(attr(absolute, 'value'));
  const relative = named(action, 'RelativeTargetSpeed')[0];
  const reference = relative ? (attr(relative, 'entityRef') ?? '') : '';
  if (!relative || through.has(reference) || reference === actor) return undefined;
  const from = constantSpeedOf(tree, reference, undefined, new Set([...through, actor]));
  return from === undefined ? undefined : relativeSpeed(relative, from);
}

/** A RelativeTargetSpeed's speed from its entity's: a delta added or a factor applied. */
function relativeSpeed(relative: Node, from: number): number | undefined {
  const value = Number(attr(relative, 'value'));
  if (!Number.isFinite(value)) return undefined;
  return attr(relative, 'speedTargetValueType') === 'factor' ? from * value : from + value;
}
