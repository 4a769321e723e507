import { CarlaRelease, Simulator } from './simulators';

/** How a simulator treats an element where it is written. */
export type Support = 'unsupported' | 'ignored';

/**
 * `error` where the simulator refuses to load or build the scenario (SPEC 12: it means nothing there);
 * a fact without one is a warning: the simulator runs the scenario otherwise than written.
 */
export type FactSeverity = 'error' | 'warning';

/** What a simulator does beyond one element or attribute at a time, with the lines of its source that show it. */
export interface SimulatorFact {
  /** What the simulator does, completing "<simulator's name> ...". */
  does: string;
  source: string;
  /** `error`: it refuses to load or build the scenario; `warning`: it runs it otherwise than written. */
  severity: FactSeverity;
}

/** An element a simulator does not run (anywhere, or in one place only). */
export interface ElementFact {
  element: string;
  /** Only when the element's parent has this name (ModifyAction of a ParameterAction, not of a VariableAction). */
  parent?: string;
  support: Support;
  /** The fact holds only for an action in the Init, or in a Story (or a catalog's Maneuver). */
  in?: 'init' | 'story';
  severity?: FactSeverity;
  /** The releases of the simulator the fact holds for; all when absent. */
  releases?: readonly CarlaRelease[];
  /** Where (Init, Story) the project's export for this simulator can write the element in a form the simulator runs: the finding there offers the export. */
  exportWritesIn?: readonly ('init' | 'story')[];
  note?: string;
  /** The file (and lines) of the simulator's repository that state or show the fact. */
  source: string;
}

/** An attribute whose presence, or some of whose values, a simulator does not honour. */
export interface AttributeFact {
  /** The element name, or '*' for any element. */
  element: string;
  parent?: string;
  attribute: string;
  /** The values that work; any other value is reported. An empty list reports the attribute itself. */
  supportedValues?: string[];
  /** Values that do not work (when the working ones are too many to list). */
  unsupportedValues?: string[];
  /** With element '*': the elements it does not hold for. */
  notOn?: string[];
  /** It does not hold where this other attribute of the element has one of these values. */
  unlessAttribute?: { attribute: string; values: string[] };
  /** The attribute's absence is what the simulator does not run (an optional attribute it reads as if required). */
  whenAbsent?: boolean;
  severity?: FactSeverity;
  note: string;
  source: string;
  /** The values the project's export for this simulator writes in a form the simulator runs (the finding then offers the export). */
  exportWrites?: readonly string[];
}

/** What one simulator accepts, read from its own repository at one revision. */
export interface SimulatorProfile {
  simulator: Exclude<Simulator, 'asam'>;
  /** The name used in every message. */
  name: string;
  repository: string;
  revision: string;
  /** The FileHeader versions a scenario may state, and whether the project's export for this simulator writes that version (its finding then offers the export); undefined when all standard versions are accepted. */
  versions?: { revMajor: string; revMinor: string; source: string; severity?: FactSeverity; exportWrites?: boolean };
  /** The oldest FileHeader revMajor the simulator runs (an error below it: it quits with `refusal`, `{stated}` the file's version); undefined when any is run. */
  oldestRevMajor?: { revMajor: number; source: string; refusal: string };
  elements: ElementFact[];
  attributes: AttributeFact[];
  /** Catalog files are found by the name `<Type>Catalog.xosc` in their directory. */
  catalogFileNames?: { types: string[]; source: string };
  /** Where the simulator computes a value otherwise than the standard, each rule with the lines that show it. */
  valueRules?: Record<ValueRule, ValueRuleFact>;
}

/** A way a simulator computes parameter and expression values that differs from the standard's. */
export type ValueRule =
  | 'substitution'
  | 'keywords'
  | 'numbers'
  | 'textGluing'
  | 'remainder'
  | 'divisionByZero'
  | 'round'
  | 'sign'
  | 'comparisons'
  | 'resultText'
  | 'declarationName'
  | 'intConversion'
  | 'booleanConversion'
  | 'doubleConversion'
  | 'declarationText'
  | 'redeclaration'
  | 'failure';

export interface ValueRuleFact {
  /** What the simulator does, in one clause that completes "esmini ...". */
  does: string;
  /** File and lines of the simulator's repository. */
  source: string;
}
