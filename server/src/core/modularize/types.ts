import { TextEdit } from '../flatten/edits';
import { XmlDocument } from '../xml';
import { GroupOccurrence, Slot } from './shape';

/** One scenario to modularize: where it is, where its main goes, its text. */
export interface ModularizeInput {
  /** Absolute path of the input. */
  path: string;
  /** Absolute path of its main in the output folder. */
  output: string;
  text: string;
  /** The text's parse, when the caller has it already. */
  document?: XmlDocument;
  /**
   * By a CatalogReference's start offset: the parameters its catalog entry uses without declaring them (esmini takes
   * them from the scenario), which a simple scenario holding it must declare. Known to a caller that resolved the catalogs.
   */
  catalogParameters?: ReadonlyMap<number, readonly string[]>;
}

/** The edits that make the file paths of a scenario written in `fromDirectory` reach the same files from `toDirectory`. */
export type RebasePaths = (document: XmlDocument, fromDirectory: string, toDirectory: string) => Promise<TextEdit[]>;

export interface ModularizeOptions {
  /** The folder the simple scenarios are written to (absolute). */
  simpleFolder: string;
  /** How file paths are rebased onto the outputs' folders: flatten's rebasing unless a test gives another. */
  rebase?: RebasePaths;
}

/** One override a main sets on an imported group. */
export interface Override {
  key: string;
  value: string;
}

/** How one occurrence of a behaviour is imported. */
export interface Use {
  occurrence: GroupOccurrence;
  outerName: string;
  overrides: Override[];
}

/** A recurring group, extracted into a simple scenario of its own. */
export interface Behaviour {
  shapeKey: string;
  /** The simple scenario's absolute path. */
  file: string;
  /** The group's name in the simple scenario (what `maneuverGroupName` names). */
  groupName: string;
  slots: Slot[];
  defaults: string[];
  /** Attributes listed in `parameterAttributes`, as `Element.attr` keys in document order. */
  parameters: string[];
  uses: Use[];
  /** The simple scenario's text (shared by the behaviours pooled into one file). */
  text: string;
  /** The group as its simple scenario holds it, for pooling it with others into one file. */
  part: PooledGroup;
}

/** What modularize made of one input. */
export interface MainResult {
  input: string;
  output: string;
  text: string;
  linesBefore: number;
  linesAfter: number;
  /** Behaviours this main imports (their simple scenarios' paths), one per reference. */
  imports: string[];
}

export interface ModularizeResult {
  mains: MainResult[];
  behaviours: Behaviour[];
  /** Inputs whose main does not flatten back to an equivalent scenario, with the first difference: nothing may be written. */
  failures: { input: string; difference: string }[];
  /** Groups that recur but were left inline, and why (they could not be imported exactly). */
  keptInline: { input: string; group: string; reason: string }[];
  totals: { linesBefore: number; linesAfter: number; reduction: number };
}

/** An input read and parsed. */
export interface ParsedInput extends ModularizeInput {
  document: XmlDocument;
  /** The edits that rebase the input's file paths onto its main's folder. */
  pathEdits: TextEdit[];
}

/** One recurring group pooled with others into a shared simple scenario. */
export interface PooledGroup {
  groupText: string;
  groupName: string;
  occurrences: GroupOccurrence[];
  defaults: string[];
  /** The group's own copies of parameters whose value differs between its scenarios: copy's name to the parameter's. */
  copies?: ReadonlyMap<string, string>;
}
