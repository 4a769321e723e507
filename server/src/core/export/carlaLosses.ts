/**
 * What an export does not keep as written, as the loss report lists it, and the one way a rule drops a part of a
 * storyboard that ScenarioRunner can do without.
 */
import { SourceRef } from '../sources';
import { Range } from '../text';
import { ancestor, attr, Node, removeNode } from './tree';

/** One thing of the input that the export does not keep as written. */
export interface CarlaLoss {
  /** dropped: not in the export; approximated: written otherwise, with a meaning close to the original; refused: nothing is written. */
  kind: 'dropped' | 'approximated' | 'refused';
  /** The file it was written in (as the user named it, or absolute) and its line, 1-based. */
  file: string;
  line: number;
  /** The element, or `Element/@attribute`. */
  element: string;
  /** What happens to it in the export. */
  what: string;
  /** What ScenarioRunner does instead (or would do with the original), with its source. */
  carla: string;
  source: SourceRef;
  range: Range;
}

export interface LossSink {
  dropped(node: Node, element: string, what: string, carla: string): void;
  approximated(node: Node, element: string, what: string, carla: string): void;
  refuse(node: Node, element: string, what: string, carla: string): void;
}

/** Drops the smallest unit of a storyboard holding `node` that ScenarioRunner can do without: its Condition, its Event's Action or its Init action. */
export function dropUnit(node: Node, context: { sink: LossSink }, element: string, carla: string): void {
  const unit =
    ancestorOrSelf(node, 'Condition') ??
    (ancestor(node, 'Event') ? ancestorOrSelf(node, 'Action') : undefined) ??
    (ancestor(node, 'Init') ? (ancestorOrSelf(node, 'PrivateAction') ?? ancestorOrSelf(node, 'GlobalAction')) : undefined);
  if (!unit) {
    context.sink.refuse(node, element, 'cannot be dropped without losing what holds it', carla);
    return;
  }
  const where = unit.name === 'Condition' ? 'condition' : ancestor(unit, 'Init') ? 'init action' : 'action';
  context.sink.dropped(node, element, `the ${where}${attr(unit, 'name') ? ` '${attr(unit, 'name')}'` : ''} is dropped`, carla);
  removeNode(unit);
}

export function ancestorOrSelf(node: Node, name: string): Node | undefined {
  return node.name === name ? node : ancestor(node, name);
}
