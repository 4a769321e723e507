import { ProblemSubject } from '../problems';
import { SizedCache } from '../sources';
import { schemaIndex } from './index';
import { typeOfElement } from './query';
import { ChosenVersion } from './version';
import { markupFreeEdit, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { checkAttribute, checkSchema, findingOffsets, SchemaCheckOptions, SchemaFinding, subjectOf } from './validate';
import { CORE_MEMOS } from '../memos';

/** A finding by offsets only, so that a remembered check holds no parse tree. */
export interface PlacedFinding {
  start: number;
  end: number;
  /** The name of the finding's attribute, to find it again in a later parse. */
  attributeName?: string;
  finding: FindingWords;
}

/** `Omit` of each member of a union (a finding of each code keeps its own facts). */
type OmitEach<T, K extends PropertyKey> = T extends unknown ? Omit<T, K> : never;

/** A finding without its parse tree: the element and attribute only by name. */
export type FindingWords = OmitEach<SchemaFinding, 'element' | 'attribute'> & { subject?: ProblemSubject };

interface RememberedCheck {
  text: string;
  setting: string;
  chosen: ChosenVersion;
  placed: PlacedFinding[];
}

const REMEMBERED_FILES: number = CORE_MEMOS.lastSchemaChecks.bound.entries;

/** Characters of remembered text (and about 100 bytes a finding) kept in all: the text of a file no longer open is its own copy. */
export const REMEMBERED_CHECK_BYTES: number = CORE_MEMOS.lastSchemaChecks.bound.bytes;

const BYTES_PER_FINDING = 100;

function rememberedSize(check: RememberedCheck): number {
  return check.text.length + BYTES_PER_FINDING * check.placed.length;
}

function placed(finding: SchemaFinding): PlacedFinding {
  const [start, end] = findingOffsets(finding);
  // The tree is dropped: only offsets and words are kept.
  const { element: _element, attribute: _attribute, ...words } = finding;
  return { start, end, attributeName: finding.attribute?.name, finding: { ...words, subject: subjectOf(finding) } };
}

/**
 * The check of `document` from the remembered check of its previous text, when one edit inside one
 * attribute value separates them: the other findings only move, and that attribute is checked again.
 */
function recheckValueEdit(previous: RememberedCheck, document: XmlDocument): PlacedFinding[] | undefined {
  if (!document.root) return undefined;
  const edit = markupFreeEdit(previous.text, document.text);
  if (!edit) return undefined;
  const delta = edit.insertedEnd - edit.removedEnd;
  let element: XmlElement | undefined = document.root;
  let edited: XmlAttribute | undefined;
  while (element && !edited) {
    edited = element.attributes.find((candidate) => candidate.valueStart <= edit.prefix && edit.insertedEnd <= candidate.valueEnd);
    if (edited || edit.prefix < element.startTagEnd) break;
    element = element.children.find((child) => child.start <= edit.prefix && edit.insertedEnd <= child.end);
  }
  // The FileHeader's revMajor/revMinor choose the schema: an edit there checks everything again.
  if (!element || !edited || element.name === 'FileHeader') return undefined;
  const index = schemaIndex(previous.chosen.version);
  const typeName = typeOfElement(index, element);
  const oldValueEnd = edited.valueEnd - delta;
  const kept = previous.placed
    .filter((entry) => entry.start < edited.nameStart || entry.start > oldValueEnd)
    .map((entry) => (entry.start >= edit.removedEnd ? { ...entry, start: entry.start + delta, end: entry.end + delta } : entry));
  const fresh: PlacedFinding[] = [];
  if (typeName) checkAttribute(index, previous.chosen, element, typeName, edited, (finding) => fresh.push(placed(finding)));
  for (const entry of kept) {
    const insertAt = entry.finding.data?.insertAt;
    if (insertAt !== undefined && Number(insertAt) >= edit.removedEnd)
      entry.finding = { ...entry.finding, data: { ...entry.finding.data, insertAt: String(Number(insertAt) + delta) } };
  }
  return [...kept, ...fresh].sort((a, b) => a.start - b.start);
}

/**
 * The last schema check of each file (at most 64, and at most about 32 MiB of text and findings, the
 * least recently checked file going first), for edits inside one attribute value (typing a value in a
 * large file). One is owned by whoever checks a stream of edits: a language server's workspace, a CLI run.
 * A file no longer remembered is simply checked in full again.
 */
export class SchemaCheckMemory {
  private readonly checks: SizedCache<RememberedCheck>;

  constructor(maxFiles = REMEMBERED_FILES, maxBytes = REMEMBERED_CHECK_BYTES) {
    this.checks = new SizedCache(maxBytes, maxFiles);
  }

  /** Approximate bytes remembered. */
  get size(): number {
    return this.checks.size;
  }

  /** The files remembered, the least recently checked first. */
  keys(): string[] {
    return this.checks.keys();
  }

  /** The schema check of a document, from the remembered check of its previous text where one value edit separates them. */
  check(key: string, document: XmlDocument, options: SchemaCheckOptions): PlacedFinding[] {
    const setting = `${options.version ?? 'auto'} ${options.modular ? 'modular' : 'strict'}`;
    const previous = this.checks.get(key);
    let check: RememberedCheck | undefined;
    // The same text checks the same (a file read again by a new generation's flattener).
    const same = previous && previous.setting === setting && previous.text === document.text;
    const moved = same ? previous.placed : previous && previous.setting === setting ? recheckValueEdit(previous, document) : undefined;
    if (previous && moved) check = { ...previous, text: document.text, placed: moved };
    else {
      const full = checkSchema(document, options);
      // The FileHeader element would keep the whole parse tree; a re-check needs only the version.
      check = { text: document.text, setting, chosen: { ...full.chosen, header: undefined }, placed: full.findings.map(placed) };
    }
    this.checks.set(key, check, rememberedSize(check));
    return check.placed;
  }
}
