import { ZERO_RANGE } from '../problems';
import { Range } from '../text';
import { displayRef, SourceRef } from '../sources';
import { attribute, selfAndDescendants, XmlElement } from '../xml';
import { copiedFrom, originOf } from './origin';
import { FlatSource } from './types';

/** The storyboard elements esmini reports transitions of, and the condition it reports firing. */
export type StoryboardKind = 'Story' | 'Act' | 'ManeuverGroup' | 'Maneuver' | 'Event' | 'Action' | 'Condition';

const NESTED_KINDS: Record<string, readonly StoryboardKind[]> = {
  Storyboard: ['Story'],
  Story: ['Act'],
  Act: ['ManeuverGroup'],
  ManeuverGroup: ['Maneuver'],
  Maneuver: ['Event'],
  Event: ['Action'],
};

const STORYBOARD_KINDS: ReadonlySet<string> = new Set<StoryboardKind>([
  'Story',
  'Act',
  'ManeuverGroup',
  'Maneuver',
  'Event',
  'Action',
  'Condition',
]);

/** esmini's element type numbers (StoryboardElement.hpp, ElementType; the esminiLib.hpp callback passes them). */
export const ESMINI_ELEMENT_TYPES: Record<number, StoryboardKind | 'Storyboard'> = {
  1: 'Storyboard',
  2: 'Story',
  3: 'Act',
  4: 'ManeuverGroup',
  5: 'Maneuver',
  6: 'Event',
  7: 'Action',
};

/** What a condition compares, as the flattened scenario writes it (values may still be `$name`s). */
export interface ConditionSpec {
  /** The condition element's name: `TimeHeadwayCondition`, `SimulationTimeCondition`, ... */
  type: string;
  rule: string | undefined;
  /** The threshold as written. */
  value: string | undefined;
  /** The entity compared against, for the relative conditions. */
  entityRef: string | undefined;
  /** The triggering entities of a ByEntityCondition. */
  triggeringEntities: string[];
  edge: string | undefined;
  delay: string | undefined;
}

/** Where a ManeuverGroup holding a ScenarioReference is written: its start tag's lines. */
export interface ImportPlace {
  /** The importing group's name as written there. */
  name: string;
  /** What its reference imports: `CutIn from lane_change.xosc`. */
  imports: string;
  source: SourceRef;
  range: Range;
  lastTagLine: number;
}

/** One storyboard element of the flattened scenario with the place in the modular sources it was written. */
export interface MappedElement {
  kind: StoryboardKind;
  /** As esmini names it: the name evaluated when it holds an expression it could evaluate, else as written. */
  name: string;
  /** esmini's full path (`Story::Act::ManeuverGroup::Maneuver::Event::Action`); for a condition, its owner's path then its name. */
  path: string;
  element: XmlElement;
  parent: MappedElement | undefined;
  /** Where the element was written: the simple scenario for a copy of an imported group. */
  source: SourceRef;
  /** 0-based lines of its start tag in that file. */
  range: Range;
  /** The start tag's last line (a tag may spread its attributes over several). */
  lastTagLine: number;
  /**
   * For a copy of an imported group: each ManeuverGroup whose ScenarioReference imports it, the nearest first (an
   * intermediate main's, ...) and the scenario debugged's last.
   */
  importedAt?: ImportPlace[];
  condition?: ConditionSpec;
  /** For a condition: the trigger it is part of (a StartTrigger starts its owner, a StopTrigger ends it). */
  trigger?: 'start' | 'stop';
}

function conditionSpec(condition: XmlElement): ConditionSpec {
  const byEntity = condition.children.find((child) => child.name === 'ByEntityCondition');
  const byValue = condition.children.find((child) => child.name === 'ByValueCondition');
  const inner = byEntity ? byEntity.children.find((child) => child.name === 'EntityCondition')?.children[0] : byValue?.children[0];
  const triggering = byEntity?.children.find((child) => child.name === 'TriggeringEntities');
  return {
    type: inner?.name ?? 'Condition',
    rule: inner ? attribute(inner, 'rule')?.value : undefined,
    value: inner ? (attribute(inner, 'value') ?? attribute(inner, 'duration') ?? attribute(inner, 'tolerance'))?.value : undefined,
    entityRef: inner ? attribute(inner, 'entityRef')?.value : undefined,
    triggeringEntities: (triggering?.children ?? [])
      .filter((child) => child.name === 'EntityRef')
      .map((child) => attribute(child, 'entityRef')?.value ?? ''),
    edge: attribute(condition, 'conditionEdge')?.value,
    delay: attribute(condition, 'delay')?.value,
  };
}

/** The Conditions of a trigger element (StartTrigger, StopTrigger). */
function triggerConditions(trigger: XmlElement | undefined): XmlElement[] {
  if (!trigger) return [];
  return trigger.children
    .filter((group) => group.name === 'ConditionGroup')
    .flatMap((group) => group.children.filter((child) => child.name === 'Condition'));
}

/**
 * Every storyboard element of a flattened scenario (Story to Action, and every Condition of their triggers and of
 * the Storyboard's StopTrigger), each with esmini's path and where it was written in the modular sources, so that a
 * transition esmini reports finds its source line and a breakpoint on a source line finds every flattened copy.
 * `evaluateName` gives esmini's name for a name holding `$` or `${...}` (undefined when it cannot).
 */
export class StoryboardMap {
  readonly elements: MappedElement[] = [];
  private readonly byPath = new Map<string, MappedElement>();
  private readonly conditionsByName = new Map<string, MappedElement[]>();
  /** The text of each file an element or an importing group was written in, by its display key. */
  private readonly texts = new Map<string, string>();

  constructor(
    readonly flat: FlatSource,
    evaluateName: (element: XmlElement, written: string) => string | undefined = () => undefined,
  ) {
    const root = flat.model?.document.root;
    const storyboard = root?.children.find((child) => child.name === 'Storyboard');
    if (!storyboard) return;
    const visit = (element: XmlElement, parent: MappedElement | undefined) => {
      const kinds = NESTED_KINDS[element.name] ?? [];
      // Actions live under Event directly; the others under their parent, ManeuverGroup's Maneuvers too.
      for (const child of element.children) {
        if (!kinds.includes(child.name as StoryboardKind)) continue;
        const mapped = this.add(child, child.name as StoryboardKind, parent, evaluateName);
        visit(child, mapped);
        const trigger = child.children.find((candidate) => candidate.name === 'StartTrigger');
        const stop = child.children.find((candidate) => candidate.name === 'StopTrigger');
        for (const condition of triggerConditions(trigger)) this.add(condition, 'Condition', mapped, evaluateName).trigger = 'start';
        for (const condition of triggerConditions(stop)) this.add(condition, 'Condition', mapped, evaluateName).trigger = 'stop';
      }
    };
    visit(storyboard, undefined);
    for (const condition of triggerConditions(storyboard.children.find((child) => child.name === 'StopTrigger')))
      this.add(condition, 'Condition', undefined, evaluateName).trigger = 'stop';
  }

  private add(
    element: XmlElement,
    kind: StoryboardKind,
    parent: MappedElement | undefined,
    evaluateName: (element: XmlElement, written: string) => string | undefined,
  ): MappedElement {
    const written = attribute(element, 'name')?.value ?? '';
    const name = written.includes('$') ? (evaluateName(element, written) ?? written) : written;
    const path = parent ? `${parent.path}::${name}` : name;
    const origin = originOf(this.flat, element);
    const document = (origin.source.original ?? origin.source.model)?.document;
    if (document) this.texts.set(refKey(origin.source.ref), document.text);
    const range = document ? document.lines.range(origin.element.start, origin.element.nameEnd) : ZERO_RANGE;
    const lastTagLine = document ? document.lines.range(origin.element.startTagEnd - 1, origin.element.startTagEnd - 1).start.line : 0;
    const mapped: MappedElement = { kind, name, path, element, parent, source: origin.source.ref, range, lastTagLine };
    if (kind === 'ManeuverGroup') mapped.importedAt = this.outerGroupsOf(element);
    if (kind === 'Condition') {
      mapped.condition = conditionSpec(element);
      const sameName = this.conditionsByName.get(name);
      if (sameName) sameName.push(mapped);
      else this.conditionsByName.set(name, [mapped]);
    } else if (!this.byPath.has(path)) {
      this.byPath.set(path, mapped);
    }
    this.elements.push(mapped);
    return mapped;
  }

  /**
   * The ManeuverGroups whose ScenarioReferences made this copy: the scenario debugged's outer group and, while the group
   * it imports is itself a copy in an intermediate main, that main's, and so on; listed the nearest to the copy first.
   */
  private outerGroupsOf(copy: XmlElement): ImportPlace[] | undefined {
    const places: ImportPlace[] = [];
    let source: FlatSource | undefined = this.flat;
    let element: XmlElement | undefined = copy;
    while (source && element) {
      const at: XmlElement = element;
      const insertion = source.insertions.find((candidate) => candidate.start === at.start);
      const document = source.original?.document;
      if (!insertion || !document) break;
      const outer = insertion.outerGroup.element;
      // An importing group's file may write no element of its own that survives flattening (a main inside a package).
      this.texts.set(refKey(source.ref), document.text);
      places.unshift({
        name: attribute(outer, 'name')?.value ?? '',
        imports: `${insertion.reference.name} from ${insertion.link.info.fileName}`,
        source: source.ref,
        range: document.lines.range(outer.start, outer.nameEnd),
        lastTagLine: document.lines.range(outer.startTagEnd - 1, outer.startTagEnd - 1).start.line,
      });
      const copied = copiedFrom(source, insertion, element);
      source = copied?.source;
      element = copied?.element;
    }
    return places.length > 0 ? places : undefined;
  }

  /** The conditions of the element's StartTrigger (what it waits for in standby). */
  startConditions(owner: MappedElement): MappedElement[] {
    return this.elements.filter((element) => element.kind === 'Condition' && element.parent === owner && element.trigger === 'start');
  }

  /** The element esmini names by this full path (`A::B::C`). */
  atPath(path: string): MappedElement | undefined {
    return this.byPath.get(path);
  }

  /** The conditions of that name (esmini's condition callback gives only the name: copies of a group share it). */
  conditionsNamed(name: string): MappedElement[] {
    return this.conditionsByName.get(name) ?? [];
  }

  /** The text of a file an element was written in (the files inside a package have no path to open). */
  textOf(ref: SourceRef): string | undefined {
    return this.texts.get(refKey(ref));
  }

  /**
   * Every flattened element whose start tag, in the file `isFile` accepts, covers the 0-based line; a ManeuverGroup
   * holding a ScenarioReference stands for the copies it imports.
   */
  atLine(isFile: (ref: SourceRef) => boolean, line: number): MappedElement[] {
    return this.elements.filter((element) => this.placeAtLine(element, isFile, line) !== undefined);
  }

  /**
   * Where the element covers the 0-based line in the file `isFile` accepts: the element as written, or, for a copy of
   * an imported group, the importing group that writes its ScenarioReference there.
   */
  placeAtLine(element: MappedElement, isFile: (ref: SourceRef) => boolean, line: number): MappedElement | ImportPlace | undefined {
    const covers = (place: { source: SourceRef; range: Range; lastTagLine: number }) =>
      line >= place.range.start.line && line <= place.lastTagLine && isFile(place.source);
    return covers(element) ? element : element.importedAt?.find(covers);
  }

  /**
   * The storyboard element a source of the scenario, in the file `isFile` accepts, starts on the 0-based line, whether
   * or not a copy of it runs (a group no reference of the scenario imports has none): says why a breakpoint there stops nowhere.
   */
  writtenAt(isFile: (ref: SourceRef) => boolean, line: number): { kind: StoryboardKind; name: string } | undefined {
    const seen = new Set<FlatSource>();
    const visit = (source: FlatSource | undefined): { kind: StoryboardKind; name: string } | undefined => {
      if (!source || seen.has(source)) return undefined;
      seen.add(source);
      const document = source.original?.document;
      if (document?.root && isFile(source.ref)) {
        const written = selfAndDescendants(document.root).find(
          (element) =>
            STORYBOARD_KINDS.has(element.name) &&
            document.lines.positionAt(element.start).line <= line &&
            line <= document.lines.positionAt(element.startTagEnd - 1).line,
        );
        if (written) return { kind: written.name as StoryboardKind, name: attribute(written, 'name')?.value ?? '' };
      }
      for (const link of source.links) {
        const found = visit(link.source);
        if (found) return found;
      }
      return undefined;
    };
    return visit(this.flat);
  }

  /** Whether an element is written in, or a ManeuverGroup there imports one into the scenario from, the file `isFile` accepts. */
  writesIn(isFile: (ref: SourceRef) => boolean): boolean {
    return this.elements.some((element) => isFile(element.source) || (element.importedAt ?? []).some((place) => isFile(place.source)));
  }
}

function refKey(ref: SourceRef): string {
  return displayRef(ref, undefined);
}
