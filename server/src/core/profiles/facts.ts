import { Simulator } from './simulators';

/** How a simulator treats an element where it is written. */
export type Support = 'unsupported' | 'ignored';

/** An element a simulator does not run (anywhere, or in the places marked false). */
export interface ElementFact {
  element: string;
  /** Only when the element's parent has this name (ModifyAction of a ParameterAction, not of a VariableAction). */
  parent?: string;
  support: Support;
  /** For actions supported in only one place: whether the Init or a Story (or a catalog's Maneuver) runs it. */
  places?: { init: boolean; story: boolean };
  note?: string;
  /** The file of the simulator's repository that states or shows the fact. */
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
  note: string;
  source: string;
}

/** What one simulator accepts, read from its own repository at one revision. */
export interface SimulatorProfile {
  simulator: Exclude<Simulator, 'asam'>;
  /** The name used in every message. */
  name: string;
  repository: string;
  revision: string;
  /** The FileHeader versions a scenario may state; undefined when all standard versions are accepted. */
  versions?: { revMajor: string; revMinor: string; source: string };
  elements: ElementFact[];
  attributes: AttributeFact[];
  /** Catalog files are found by the name `<Type>Catalog.xosc` in their directory. */
  catalogFileNames?: { types: string[]; source: string };
  /** `${...}` expressions are passed on as text, never evaluated. */
  expressionsNotEvaluated?: { source: string };
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
  | 'failure';

export interface ValueRuleFact {
  /** What the simulator does, in one clause that completes "esmini ...". */
  does: string;
  /** File and lines of the simulator's repository. */
  source: string;
}
