import { ElementParticle, Particle } from './model';
import { coreMemo } from '../memos';
import { ownString } from '../text';

interface Edge {
  particle: ElementParticle;
  to: number;
}

/** A set of automaton states, sorted, after following every empty transition. */
export type StateSet = readonly number[];

// State sets are interned per automaton, so one memo serves every automaton.
const transitions = coreMemo<StateSet, Map<string, { states: StateSet; particle: ElementParticle } | null>>('contentTransitions');

/**
 * A content model (sequence/choice with occurrences) as a nondeterministic automaton over child
 * element names. Built once per complex type; the schemas' models have at most a few dozen states.
 * `all` groups are not automata (any order): see AllModel.
 */
export class ContentAutomaton {
  private readonly empty: number[][] = [];
  private readonly edges: Edge[][] = [];
  private readonly closures = new Map<number, number[]>();
  private readonly interned = new Map<string, StateSet>();
  readonly start: StateSet;
  private readonly accept: number;

  constructor(particle: Particle | undefined) {
    const first = this.state();
    this.accept = particle ? this.build(particle, first) : first;
    this.start = this.intern(this.closure([first]));
  }

  private state(): number {
    this.empty.push([]);
    this.edges.push([]);
    return this.empty.length - 1;
  }

  /** Adds the particle from state `from`; returns the state after it. */
  private build(particle: Particle, from: number): number {
    const once = (start: number): number => {
      if (particle.kind === 'element') {
        const end = this.state();
        this.edges[start].push({ particle, to: end });
        return end;
      }
      if (particle.kind === 'choice') {
        const end = this.state();
        for (const item of particle.items) this.empty[this.build(item, start)].push(end);
        if (particle.items.length === 0) this.empty[start].push(end);
        return end;
      }
      // A sequence (and an `all` nested where XSD 1.0 does not allow one, read as a sequence).
      let current = start;
      for (const item of particle.items) current = this.build(item, current);
      return current;
    };
    let current = from;
    for (let i = 0; i < particle.min; i++) current = once(current);
    if (particle.max === -1) {
      const loopStart = this.state();
      this.empty[current].push(loopStart);
      const loopEnd = once(loopStart);
      this.empty[loopEnd].push(loopStart);
      const end = this.state();
      this.empty[loopStart].push(end);
      return end;
    }
    const end = this.state();
    for (let i = particle.min; i < particle.max; i++) {
      this.empty[current].push(end);
      current = once(current);
    }
    this.empty[current].push(end);
    return end;
  }

  private closure(states: Iterable<number>): number[] {
    const seen = new Set<number>();
    const stack = [...states];
    while (stack.length > 0) {
      const state = stack.pop() as number;
      if (seen.has(state)) continue;
      seen.add(state);
      for (const next of this.empty[state]) stack.push(next);
    }
    return [...seen].sort((a, b) => a - b);
  }

  private closureOf(state: number): number[] {
    let result = this.closures.get(state);
    if (!result) {
      result = this.closure([state]);
      this.closures.set(state, result);
    }
    return result;
  }

  /** One object per distinct state set, so that transitions can be remembered per set (a lazily built DFA). */
  private intern(states: number[]): StateSet {
    const key = states.join(',');
    let known = this.interned.get(key);
    if (!known) {
      known = states;
      this.interned.set(key, known);
    }
    return known;
  }

  /** The states after a child named `name`, or undefined when no path allows it here. */
  step(states: StateSet, name: string): { states: StateSet; particle: ElementParticle } | undefined {
    let table = transitions.get(states);
    if (!table) {
      table = new Map();
      transitions.set(states, table);
    }
    const remembered = table.get(name);
    if (remembered !== undefined) return remembered ?? undefined;
    const computed = this.computeStep(states, name);
    table.set(ownString(name), computed ?? null);
    return computed;
  }

  private computeStep(states: StateSet, name: string): { states: StateSet; particle: ElementParticle } | undefined {
    const next = new Set<number>();
    let particle: ElementParticle | undefined;
    for (const state of states) {
      for (const edge of this.edges[state]) {
        if (edge.particle.name !== name) continue;
        particle ??= edge.particle;
        for (const reached of this.closureOf(edge.to)) next.add(reached);
      }
    }
    return particle ? { states: this.intern([...next].sort((a, b) => a - b)), particle } : undefined;
  }

  accepts(states: StateSet): boolean {
    return states.includes(this.accept);
  }

  /** The element particles allowed next, each name once, in the content model's order. */
  allowed(states: StateSet): ElementParticle[] {
    const byName = new Map<string, ElementParticle>();
    for (const state of states)
      for (const edge of this.edges[state]) if (!byName.has(edge.particle.name)) byName.set(edge.particle.name, edge.particle);
    return [...byName.values()];
  }

  /**
   * The fewest elements to write from `states` until `goal` holds for a state: the required
   * elements that are missing (0-1 breadth-first search: empty transitions cost nothing).
   */
  shortestPath(states: StateSet, goal: (state: number) => boolean): ElementParticle[] | undefined {
    const distance = new Map<number, number>();
    const previous = new Map<number, { from: number; particle: ElementParticle | undefined }>();
    const queue: number[] = [];
    for (const state of states) {
      distance.set(state, 0);
      queue.push(state);
    }
    while (queue.length > 0) {
      // Picking the nearest each time keeps it exact; the automata are tiny.
      let best = 0;
      for (let i = 1; i < queue.length; i++) if ((distance.get(queue[i]) ?? 0) < (distance.get(queue[best]) ?? 0)) best = i;
      const state = queue.splice(best, 1)[0];
      const here = distance.get(state) ?? 0;
      if (goal(state)) {
        const path: ElementParticle[] = [];
        let current = state;
        for (let link = previous.get(current); link; link = previous.get(current)) {
          if (link.particle) path.unshift(link.particle);
          current = link.from;
        }
        return path;
      }
      const relax = (to: number, cost: number, particle: ElementParticle | undefined) => {
        const known = distance.get(to);
        if (known !== undefined && known <= here + cost) return;
        distance.set(to, here + cost);
        previous.set(to, { from: state, particle });
        queue.push(to);
      };
      for (const to of this.empty[state]) relax(to, 0, undefined);
      for (const edge of this.edges[state]) relax(edge.to, 1, edge.particle);
    }
    return undefined;
  }

  /** The required elements missing before the content is complete. */
  missingToEnd(states: StateSet): ElementParticle[] {
    return this.shortestPath(states, (state) => state === this.accept) ?? [];
  }

  /** The required elements missing before a child named `name` may stand here; undefined when none can make it fit. */
  missingBefore(states: StateSet, name: string): ElementParticle[] | undefined {
    return this.shortestPath(states, (state) => this.edges[state].some((edge) => edge.particle.name === name));
  }
}
