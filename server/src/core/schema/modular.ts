import { ComplexType, SimpleType } from './model';

/**
 * The modular extension (SPEC 2) as content models in the compiled schemas' own form: a
 * ScenarioReference stands in a ManeuverGroup where a Maneuver may stand.
 */
export const MODULAR_TYPES: Record<string, ComplexType> = {
  '#ScenarioReference': {
    attributes: [{ name: 'scenarioFileName', type: '#FileName', required: true }],
    content: { kind: 'element', name: 'ManeuverGroupReference', type: '#ManeuverGroupReference', min: 1, max: -1 },
  },
  '#ManeuverGroupReference': {
    attributes: [{ name: 'maneuverGroupName', type: '#Name', required: true }],
    content: { kind: 'element', name: 'ParameterReference', type: '#ParameterReference', min: 0, max: -1 },
  },
  '#ParameterReference': {
    attributes: [
      { name: 'key', type: '#Name', required: true },
      { name: 'value', type: '#Name', required: true },
    ],
  },
};

/** Where the extension's top element may stand: its parent's type, and the standard element whose place it takes. */
export const MODULAR_PLACEMENT = {
  element: 'ScenarioReference',
  type: '#ScenarioReference',
  parentType: 'ManeuverGroup',
  standsFor: 'Maneuver',
} as const;

/** The attribute every element may carry in a simple scenario (SPEC 2). */
export const MODULAR_ATTRIBUTE = 'parameterAttributes';

export const MODULAR_SIMPLE_TYPES: Record<string, SimpleType> = {
  '#FileName': { alternatives: [{ builtin: 'string' }], parameter: false, expression: false },
  '#Name': { alternatives: [{ builtin: 'string' }], parameter: false, expression: false },
};
