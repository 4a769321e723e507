import { defineDiagnostic } from './definition';
import { QC } from './qcRules';

/** Two children of one element with one name. */
export const DUPLICATE_NAME = defineDiagnostic({
  code: 'duplicate-name',
  rule: {
    description: 'The children of one element have unique names (Events of a Maneuver, Acts of a Story, entities, ...).',
    qcRule: QC.uniqueNames,
  },
  severity: 'warning',
});
