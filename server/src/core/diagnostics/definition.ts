import { Problem, ProblemCode, ProblemCodeWithData, ProblemDataByCode, Severity } from '../problems';
import { Position, Range } from '../text';
import { PARAMETER_ATTRIBUTES } from '../model';
import { attribute, elementAt, XmlDocument, XmlElement } from '../xml';
import type { SchemaVersionSetting } from '../schema/version';
import { Rule } from './qcRules';

/** The data a problem of code `C` carries: the shape `ProblemDataByCode` names, none for a code without data. */
export type DataOf<C extends ProblemCode> = C extends ProblemCodeWithData ? ProblemDataByCode[C] : never;

/** What a problem says, apart from where: the part a diagnostic's module builds. */
export type ProblemWording<C extends ProblemCode = ProblemCode> = Pick<Problem, 'severity' | 'message' | 'hint'> & { code: C };

/** A problem's words alone, where its producer gives the code and severity with the facts (the schema check). */
export type Words = Pick<Problem, 'message' | 'hint'>;

/** A message about a value an override set, naming the ParameterReference that set it. */
export function setByWords(message: string, key: string): string {
  return `${message} (set by ParameterReference '${key}')`;
}

/** `did you mean 'x'?`, where there is a closest name. */
export function didYouMean(suggestion: string | undefined): string | undefined {
  return suggestion ? `did you mean '${suggestion}'?` : undefined;
}

/** A text with its line index, as a fix reads and places it (an LSP `TextDocument` is one). */
export interface TextLines {
  getText(): string;
  positionAt(offset: number): Position;
  offsetAt(position: Position): number;
}

/** The problem's first related location, as a fix of the problem may read and edit it. */
export interface RelatedPlace {
  range: Range;
  /** Whether it lies in the document of the problem. */
  sameDocument: boolean;
  /** The name of its file, as the last segment of its address. */
  fileName: string;
  /** Whether a fix may edit its file (not inside a package the workspace does not edit, nor a file it cannot name). */
  editable(): Promise<boolean>;
  /** Its file's text, where a fix may edit it. */
  text(): Promise<TextLines | undefined>;
}

/** What a fix of one problem is given: the problem's data, document and range, and its first related place. */
export interface FixContext<D> {
  data: D | undefined;
  document: TextLines;
  range: Range;
  /** The document's parse tree (parsed at most once per request). */
  parsed(): Promise<XmlDocument>;
  related: RelatedPlace | undefined;
  /** The schema version the workspace checks against (its `schemaVersion` setting), for fixes that insert what the schema requires. */
  schemaVersion: SchemaVersionSetting | 'off';
  /** What the file's analysis knows of parameters around the problem, for a fix that declares one; undefined where the file has no analysis. */
  parameters(): Promise<ParameterScopes | undefined>;
}

/** A parameter's declaration elsewhere, which a new declaration of its name may copy: its type, value and where it stands. */
export interface ParameterTemplate {
  type: string;
  value: string;
  /** Where it is declared, as a fix's title names it (a file, or `line 12`). */
  from: string;
}

/** The parameter scopes around a problem, from the analysis of its file (the editor's adapter reads them). */
export interface ParameterScopes {
  /** The elements of the scopes that enclose the problem, innermost first (their parse is the document's text). */
  scopes: readonly XmlElement[];
  /** The document's root element. */
  root: XmlElement | undefined;
  /** The declaration of `name` in a simple scenario the file imports, else in another scope of the file. */
  declarationOf(name: string): ParameterTemplate | undefined;
}

/** One replacement of a fix: in the problem's document, or in the file of its first related place. */
export interface FixEdit {
  place: 'document' | 'related';
  range: Range;
  newText: string;
}

/** A replacement of the problem's document from offset `start` to `end`. */
export function documentEdit(document: Pick<TextLines, 'positionAt'>, start: number, end: number, newText: string): FixEdit {
  return { place: 'document', range: { start: document.positionAt(start), end: document.positionAt(end) }, newText };
}

/** A quick fix of a problem, as text edits: the editor's adapter (server/src/features/fixes/) makes it a code action. */
export interface CoreFix {
  title: string;
  edits: FixEdit[];
  preferred?: boolean;
  /** A file to rename (absolute paths), where renaming is the fix (a catalog file ScenarioRunner reads only by name). */
  rename?: { from: string; to: string };
  /** An editor command that does what no edit can, given the problem's document: exporting it for a simulator. */
  command?: EditorCommand;
}

/** The commands a core fix may offer, by what they do (the editor's adapter names its own command for each). */
export type EditorCommand = 'export-for-carla';

/** One diagnostic: its code, its rule, its usual severity, the data its problems carry and their quick fixes. */
export interface DiagnosticBase<C extends ProblemCode> {
  readonly code: C;
  readonly rule: Rule;
  /** The severity its producers give it (where they choose per problem, the usual one). */
  readonly severity: Severity;
  /** A problem the original tool ignored silently: what `flatten --force` skips. */
  readonly skippedByForce?: true;
  /** Shown struck through in the editor: what the problem names is kept only for compatibility. */
  readonly deprecated?: true;
  /** Shown faded in the editor: what the problem names is not needed. */
  readonly unnecessary?: true;
  readonly fixes?: (context: FixContext<DataOf<C>>) => CoreFix[] | Promise<CoreFix[]>;
}

/** A code whose problems carry data checks it (a client sends a diagnostic's data back as it likes). */
export type DiagnosticDefinition<C extends ProblemCode> = DiagnosticBase<C> &
  (C extends ProblemCodeWithData ? { readonly isData: (value: unknown) => value is DataOf<C> } : { readonly isData?: undefined });

/** A definition in the registry, whatever its code: its fixes take the data `isData` accepted. */
export interface RegisteredDiagnostic<C extends ProblemCode = ProblemCode> extends Omit<DiagnosticBase<C>, 'fixes'> {
  readonly isData?: (value: unknown) => boolean;
  readonly fixes?: (context: FixContext<unknown>) => Promise<CoreFix[]>;
}

/** A diagnostic's definition as the registry lists it. */
export function defineDiagnostic<C extends ProblemCode>(definition: DiagnosticDefinition<C>): RegisteredDiagnostic<C> {
  const { fixes } = definition;
  return {
    ...definition,
    // The adapter passes only data that `isData` accepted, so the data has the code's shape.
    fixes: fixes && (async (context) => fixes(context as FixContext<DataOf<C>>)),
  };
}

export function isRecord(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

export function isString(value: unknown): value is string {
  return typeof value === 'string';
}

export function isOptionalString(value: unknown): value is string | undefined {
  return value === undefined || isString(value);
}

export function isStringList(value: unknown): value is string[] {
  return Array.isArray(value) && value.every(isString);
}

/** A record whose fields each pass their check. */
export function isRecordOf<T>(value: unknown, fields: { [K in keyof T]-?: (field: unknown) => boolean }): value is T {
  if (!isRecord(value)) return false;
  return Object.entries<(field: unknown) => boolean>(fields).every(([name, check]) => check(value[name]));
}

export const isSuggestion = (value: unknown): value is ProblemDataByCode['schema-value'] =>
  isRecordOf<ProblemDataByCode['schema-value']>(value, { suggestion: isString });

/** A replacement in the file of a problem's first related location. */
export const isRelatedReplacement = (value: unknown): value is { relatedReplacement: string } =>
  isRecordOf<{ relatedReplacement: string }>(value, { relatedReplacement: isString });

/** The indentation of the line that holds `offset`. */
export function indentOfLine(text: string, offset: number): string {
  const lineStart = text.lastIndexOf('\n', offset - 1) + 1;
  return /^[ \t]*/.exec(text.slice(lineStart))?.[0] ?? '';
}

/** A text's line break and indentation unit, as an inserted block copies them. */
export function layoutOf(text: string): { eol: string; unit: string } {
  return { eol: text.includes('\r\n') ? '\r\n' : '\n', unit: /^( +|\t)/m.exec(text.slice(0, 4000))?.[1] ?? '  ' };
}

/** The edit (text offsets) that puts `block` before `element`: on a line of its own at the element's indentation where the element starts its line, else right before it. */
export function insertionBefore(text: string, element: XmlElement, block: string): { start: number; end: number; newText: string } {
  const lineStart = text.lastIndexOf('\n', element.start - 1) + 1;
  const indent = text.slice(lineStart, element.start);
  return /^[ \t]*$/.test(indent)
    ? { start: lineStart, end: lineStart, newText: `${indent}${block}${layoutOf(text).eol}` }
    : { start: element.start, end: element.start, newText: block };
}

/**
 * The edit (text offsets) that inserts children at the end of `parent`, each block `blocksAt` writes at an
 * indentation and line break: `<Parent/>` becomes `<Parent>…</Parent>`; a closing tag on its own line gets
 * the blocks on lines of their own above it, else they go right before it. Undefined when the closing tag is not found.
 */
export function childrenInsertion(
  text: string,
  parent: XmlElement,
  blocksAt: (indent: string, lineBreak: string) => string[],
): { start: number; end: number; newText: string } | undefined {
  const { eol, unit } = layoutOf(text);
  const childIndent = indentOfLine(text, parent.start) + unit;
  if (parent.selfClosing) {
    const slash = text.lastIndexOf('/', parent.end - 1);
    return {
      start: slash,
      end: parent.end,
      newText: `>${blocksAt(childIndent, eol)
        .map((block) => `${eol}${childIndent}${block}`)
        .join('')}${eol}${indentOfLine(text, parent.start)}</${parent.name}>`,
    };
  }
  const closing = text.lastIndexOf(`</${parent.name}`, parent.end);
  if (closing < 0) return undefined;
  const lineStart = text.lastIndexOf('\n', closing - 1) + 1;
  if (/^[ \t]*$/.test(text.slice(lineStart, closing)))
    return {
      start: lineStart,
      end: lineStart,
      newText: blocksAt(childIndent, eol)
        .map((block) => `${childIndent}${block}${eol}`)
        .join(''),
    };
  return { start: closing, end: closing, newText: blocksAt('', '').join('') };
}

/** The text offset where a new attribute goes: right after parameterAttributes, else after the element name. */
export function attributeInsertOffset(element: XmlElement): number {
  const declaration = attribute(element, PARAMETER_ATTRIBUTES);
  return declaration ? declaration.valueEnd + 1 : element.nameEnd;
}

/** `Change to '<text>'`: `text` written where the problem is. */
export function changeTo(range: Range, text: string, preferred = true): CoreFix {
  return { title: `Change to '${text}'`, edits: [{ place: 'document', range, newText: text }], preferred };
}

/** The fix of a code whose data names the closest valid text: change to it. */
export function changeToSuggestion({ data, range }: FixContext<{ suggestion: string }>): CoreFix[] {
  return data?.suggestion ? [changeTo(range, data.suggestion)] : [];
}

/** The element whose start tag's name holds `offset` (where the schema places its findings about an element). */
export function elementAtRange(document: XmlDocument, offset: number): XmlElement | undefined {
  const found = elementAt(document, offset);
  return found && found.start + 1 <= offset && offset <= found.nameEnd ? found : undefined;
}
