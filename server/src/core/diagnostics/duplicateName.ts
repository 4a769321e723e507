import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A name as evaluated, and as written where that differs (`$Name`): ` (the value of $Name)`. */
export function valueOfWords(name: string, written: string): string {
  return name !== written ? ` (the value of ${written})` : '';
}

/** The related location's note: the first element of the name. */
export function firstOfNameNote(name: string): string {
  return `the first '${name}'`;
}

/** What the name check found: two children of `<parent>` named `name` (`written` as the file writes it). */
export interface DuplicateNameFacts {
  parent: string;
  name: string;
  written: string;
  /** The element names of the first child and of this one. */
  earlier: string;
  child: string;
  /** A storyboard reference of this file names it: a simulator takes one of the two. */
  referenced: boolean;
  /** Checked for esmini, which runs both and resolves a reference to the first: a warning. */
  esmini: boolean;
}

export function duplicateNameWording({
  parent,
  name,
  written,
  earlier,
  child,
  referenced,
  esmini,
}: DuplicateNameFacts): ProblemWording<'duplicate-name'> {
  return {
    severity: esmini || !referenced ? 'warning' : 'error',
    code: 'duplicate-name',
    message: `<${parent}> has two children named '${name}'${valueOfWords(name, written)} (<${earlier}> and <${child}>); the standard wants the names on each level unique, so that a reference names one element${
      referenced ? '' : " (ASAM's Quality Checker reports it as an error; no reference of this file names it, and esmini runs both)"
    }${esmini && referenced ? ' (esmini runs both and resolves a reference to the name to the first)' : ''}`,
    hint: `rename one of them`,
  };
}

/** Two children of one element with one name. */
export const DUPLICATE_NAME = defineDiagnostic({
  code: 'duplicate-name',
  rule: {
    description: 'The children of one element have unique names (Events of a Maneuver, Acts of a Story, entities, ...).',
    qcRule: QC.uniqueNames,
  },
  severity: 'warning',
});
