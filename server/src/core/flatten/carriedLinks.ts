import { planOverrides } from '../keys';
import { coreMemo } from '../memos';
import { ScenarioReferenceInfo } from '../model';
import { Problem } from '../problems';
import { refId, ScenarioStore, SourceRef } from '../sources';
import { Position, Range } from '../text';
import { ValueEdit, XmlDocument } from '../xml';
import { LinkContext } from './link';
import { LinkedGroupReference, LinkedReference } from './types';

/** What linking a parse's references made, for the next parse after an edit inside one value (`linksOfParse` of core/memos.ts). */
export interface ParseLinks {
  store: ScenarioStore;
  /** The ids of the files being read when the links were made: the reading file last. */
  stack: string[];
  links: LinkedReference[];
  /** For each link, the problems linking it reported in the reading file (in the order reported). */
  problems: readonly Problem[][];
  /** The analysis's checks of each reference (`referenceChecks`), carried with the links; undefined where not made or not carried. */
  checks?: ParseChecks;
}

/** The problems the analysis found for one reference, apart from linking it. */
export interface ReferenceCheckResults {
  /** Entities its imported groups name that the main file does not declare. */
  entity: readonly Problem[];
  /** Its override values that do not fit the attributes they set. */
  override: readonly Problem[];
}

/** The analysis's checks of a parse's references, made with what it read of the rest of the file (`context`). */
export interface ParseChecks {
  /** What the checks read outside the references: the entities declared, the schema version; another context checks all again. */
  context: string;
  results: (ReferenceCheckResults | undefined)[];
}

const linksOfParses = coreMemo<XmlDocument, ParseLinks>('linksOfParse');

const NO_PROBLEMS: Problem[] = [];

/** Remembers what linking the references of `document` made. */
export function rememberLinks(document: XmlDocument, links: ParseLinks): void {
  linksOfParses.set(document, links);
}

/** What linking the references of `document` last made, while `links` are still those links (a later linking of the same parse replaces them). */
export function linksOfParse(document: XmlDocument, links: readonly LinkedReference[]): ParseLinks | undefined {
  const known = linksOfParses.get(document);
  return known?.links === links ? known : undefined;
}

/** What the references of a file re-parsed after `edit` (or read again from the same parse: no edit) can take from the previous parse's links. */
export class LinkCarry {
  /** Where the edit ends in the previous text, once a problem is moved (the previous parse's lines are not indexed otherwise). */
  private editEnd: Position | undefined;
  private readonly fromId: string;

  private constructor(
    private readonly previous: ParseLinks,
    private readonly edit: ValueEdit | undefined,
    private readonly context: LinkContext,
    private readonly from: SourceRef,
    private readonly stack: SourceRef[],
  ) {
    this.fromId = refId(from);
  }

  /**
   * The carry from the previous parse's links, when `document` came from it by a value edit (or is that parse, read
   * again: a generation that changed another file, or a change leaving the text as it was) and they were made with
   * the same store and stack.
   */
  static of(
    document: XmlDocument,
    edit: ValueEdit | undefined,
    referenceCount: number,
    context: LinkContext,
    from: SourceRef,
    stack: SourceRef[],
  ): LinkCarry | undefined {
    const previous = linksOfParses.get(edit ? edit.previous : document);
    if (!previous || previous.store !== context.store || previous.links.length !== referenceCount) return undefined;
    if (previous.stack.length !== stack.length || previous.stack.some((id, index) => id !== refId(stack[index]))) return undefined;
    return new LinkCarry(previous, edit, context, from, stack);
  }

  /**
   * The link of the `index`th reference and the problems it reports, taken from the previous parse's: when the
   * edit lies outside the reference and its outer group (all linking reads of the reading file), its file
   * resolves as it did and the file read is the same source. Undefined when it must be linked again.
   */
  carry(index: number, reference: ScenarioReferenceInfo): { link: LinkedReference; problems: Problem[] } | undefined {
    const before = this.previous.links[index];
    const info = before.info;
    const region = info.outerGroup?.element ?? info.element;
    const edit = this.edit;
    if (edit && region.start <= edit.prefix && edit.removedEnd <= region.end) return undefined;
    if (reference.fileName !== info.fileName || reference.element.start !== (edit ? edit.shift(info.element.start) : info.element.start))
      return undefined;
    if (!before.source || before.cycle || reference.groupReferences.length !== info.groupReferences.length) return undefined;
    if (this.context.store.knownResolution(reference.fileName, this.from) !== before.resolution) return undefined;
    const target =
      before.resolution.kind === 'package'
        ? before.resolution.main
        : before.resolution.kind === 'scenario'
          ? before.resolution.ref
          : undefined;
    if (!target || this.context.knownSource?.(target, this.stack) !== before.source) return undefined;
    const problems = this.problemsOf(index);
    if (!problems) return undefined;
    this.context.rendered(before.source);
    if (reference === info) return { link: before, problems };
    const groups = reference.groupReferences.map((groupReference, groupIndex): LinkedGroupReference => {
      const linked = before.groups[groupIndex];
      if (groupReference === linked.info) return linked;
      // The same keys and the same group's attributes plan the same overrides, of this parse's parameters.
      const plan =
        linked.plan &&
        planOverrides(
          linked.overridable,
          groupReference.parameters.filter((parameter) => parameter.keyAttribute),
        );
      return { info: groupReference, target: linked.target, overridable: linked.overridable, plan };
    });
    return { link: { info: reference, resolution: before.resolution, source: before.source, groups, cycle: undefined }, problems };
  }

  /** The context the previous parse's reference checks were made in; undefined when there are none to carry. */
  get checksContext(): string | undefined {
    return this.previous.checks?.context;
  }

  /** The checks of the `index`th reference, carried with its link (`carry` gave one), placed in the edited text. */
  checksOf(index: number): ReferenceCheckResults | undefined {
    const before = this.previous.checks?.results[index];
    if (!before) return undefined;
    // Nothing to move (most references): the same results, not a new object per reference and edit.
    if (before.entity.length === 0 && before.override.length === 0) return before;
    return { entity: this.movedProblems(before.entity), override: this.movedProblems(before.override) };
  }

  private movedProblems(problems: readonly Problem[]): Problem[] {
    return problems.length === 0 ? NO_PROBLEMS : problems.map((problem) => ({ ...problem, range: this.moved(problem.range) }));
  }

  /** The problems the previous link reported, placed in the edited text; undefined when one points into the reading file elsewhere (linked again). */
  private problemsOf(index: number): Problem[] | undefined {
    const previous = this.previous.problems[index];
    if (previous.length === 0) return NO_PROBLEMS;
    const moved: Problem[] = [];
    for (const problem of previous) {
      if (problem.related?.some((related) => refId(related.source) === this.fromId)) return undefined;
      moved.push(refId(problem.source) === this.fromId ? { ...problem, range: this.moved(problem.range) } : { ...problem });
    }
    return moved;
  }

  /** A range of the previous text, wholly before or wholly after the edit, in the edited text (the edit changes no line). */
  private moved(range: Range): Range {
    return { start: this.movedPosition(range.start), end: this.movedPosition(range.end) };
  }

  private movedPosition(position: Position): Position {
    const edit = this.edit;
    if (!edit) return { line: position.line, character: position.character };
    this.editEnd ??= edit.previous.lines.positionAt(edit.removedEnd);
    return position.line === this.editEnd.line && position.character >= this.editEnd.character
      ? { line: position.line, character: position.character + edit.delta }
      : { line: position.line, character: position.character };
  }
}

/** The problems each link reported, as linkAll records them. */
export function linkProblems(problems: Problem[], from: number, to: number): Problem[] {
  return from === to ? NO_PROBLEMS : problems.slice(from, to);
}
