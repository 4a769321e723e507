import { SimulatorProfile } from './facts';

// Facts read from esmini/esmini at revision 77028d83e6d402de52f7187e5384d1b1c02b7d1f: the rows marked
// "No" in osc_coverage.txt, kept only where release_notes.md does not announce later support and the
// scenario reader (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp) does
// not implement them either (it does implement VariableCondition, TrafficSignalCondition and
// TrafficSignalStateAction, which osc_coverage.txt still lists as missing).
const COVERAGE = 'osc_coverage.txt';
const READER = 'EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp';

export const ESMINI_PROFILE: SimulatorProfile = {
  simulator: 'esmini',
  name: 'esmini',
  repository: 'esmini/esmini',
  revision: '77028d83e6d402de52f7187e5384d1b1c02b7d1f',
  elements: [
    { element: 'ModifyAction', parent: 'ParameterAction', support: 'unsupported', source: COVERAGE, note: 'only SetAction is implemented for parameters; a VariableAction can modify' },
    { element: 'TrafficSourceAction', support: 'unsupported', source: COVERAGE },
    { element: 'TrafficSinkAction', support: 'unsupported', source: COVERAGE },
    { element: 'TrafficStopAction', support: 'unsupported', source: COVERAGE },
    { element: 'TrafficSignalControllerAction', support: 'unsupported', source: READER, note: 'it logs "TrafficSignalAction ... not supported yet"' },
    { element: 'AnimationAction', support: 'unsupported', source: COVERAGE },
    { element: 'UserDefinedLight', parent: 'LightType', support: 'unsupported', source: READER, note: 'only vehicle lights are implemented' },
    { element: 'SensorReferenceSet', support: 'ignored', source: COVERAGE },
    { element: 'GeoPosition', support: 'unsupported', source: COVERAGE },
    { element: 'ExternalObjectReference', support: 'unsupported', source: COVERAGE },
    { element: 'EntitySelection', support: 'unsupported', source: COVERAGE },
    { element: 'TimeOfDayCondition', support: 'unsupported', source: COVERAGE, note: 'the condition is ignored' },
    { element: 'UserDefinedValueCondition', support: 'unsupported', source: COVERAGE, note: 'the condition is ignored' },
    { element: 'TrafficSignalControllerCondition', support: 'unsupported', source: COVERAGE, note: 'the condition is ignored' },
    { element: 'Stochastic', parent: 'ParameterValueDistribution', support: 'unsupported', source: COVERAGE, note: 'only deterministic distributions are implemented' },
    { element: 'UsedArea', support: 'ignored', source: COVERAGE },
    { element: 'DomeImage', support: 'ignored', source: COVERAGE },
    { element: 'TrafficSignals', parent: 'RoadNetwork', support: 'ignored', source: COVERAGE },
  ],
  attributes: [
    { element: 'Route', attribute: 'closed', supportedValues: ['false'], source: COVERAGE, note: 'closed routes are not implemented' },
    { element: '*', attribute: 'coordinateSystem', unsupportedValues: ['lane'], source: COVERAGE, note: 'it falls back to road coordinates' },
  ],
};
