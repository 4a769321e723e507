import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A trafficSignalControllerRef names `controller`, which is none of the `declared` controllers of the scenario. */
export function unknownTrafficSignalControllerWording(
  controller: string,
  declared: readonly string[],
): ProblemWording<'unknown-traffic-signal-controller'> {
  return {
    severity: 'error',
    code: 'unknown-traffic-signal-controller',
    message: `'${controller}' is not a TrafficSignalController of this scenario's RoadNetwork${declared.length > 0 ? ` (it has ${declared.map((name) => `'${name}'`).join(', ')})` : ' (it declares none)'}`,
  };
}

export const UNKNOWN_TRAFFIC_SIGNAL_CONTROLLER = defineDiagnostic({
  code: 'unknown-traffic-signal-controller',
  rule: {
    description: 'A trafficSignalControllerRef names a TrafficSignalController of the scenario.',
    qcRule: QC.signalController,
  },
  severity: 'error',
});
