import { defineDiagnostic, ProblemWording } from './definition';

/** What the range check found: the value, as written where that differs, the range and how esmini reads it where it runs it. */
export interface OutOfRangeFacts {
  element: string;
  attribute: string;
  value: number;
  /** The text written, where it is not the number itself (a parameter, an expression). */
  written?: string;
  /** The range as the standard writes it (`[0..inf[`). */
  range: string;
  /** The class of the ASAM model that gives the range, where one does. */
  modelClass?: string;
  /** How the simulator checked reads the value (`by`: esmini, CARLA ScenarioRunner), where it runs it with one meaning: then a warning. */
  reading?: { by: string; text: string };
  /** The simulator checked when what it does with the value is not recorded: `reading` is then another's (esmini's), said as such. */
  notRecordedFor?: string;
}

export function outOfRangeWording({
  element,
  attribute,
  value,
  written,
  range,
  modelClass,
  reading,
  notRecordedFor,
}: OutOfRangeFacts): ProblemWording<'out-of-range'> {
  const from = written === undefined ? '' : ` (from ${written})`;
  const model = modelClass ? ` (class ${modelClass} of the ASAM model)` : '';
  const unknown = notRecordedFor === undefined ? '' : `what ${notRecordedFor} does with it is not recorded here; `;
  const runs = reading === undefined ? '' : ` (RA Consulting's checker reports it as an error); ${unknown}${reading.by} ${reading.text}`;
  return {
    severity: reading === undefined ? 'error' : 'warning',
    code: 'out-of-range',
    message: `${element} ${attribute} ${value}${from} is outside the standard's range ${range}${model}${runs}`,
  };
}

export const OUT_OF_RANGE = defineDiagnostic({
  code: 'out-of-range',
  rule: {
    description:
      "A value lies within the range the ASAM model documents for its attribute in the file's version (core/semantics/ranges.ts, each range with its source); a warning where esmini runs it with one meaning.",
  },
  severity: 'error',
});
