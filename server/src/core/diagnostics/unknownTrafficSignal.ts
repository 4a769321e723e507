import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A TrafficSignalStateAction names `signal`, which neither the road network `roadFile` nor a controller of the scenario has. */
export function unknownTrafficSignalWording(signal: string, roadFile: string): ProblemWording<'unknown-traffic-signal'> {
  return {
    severity: 'error',
    code: 'unknown-traffic-signal',
    message: `traffic signal '${signal}' is neither a signal of the road network ${roadFile} nor one a TrafficSignalController of the scenario sets`,
    hint: 'name the id of a <signal> of the OpenDRIVE file',
  };
}

export const UNKNOWN_TRAFFIC_SIGNAL = defineDiagnostic({
  code: 'unknown-traffic-signal',
  rule: {
    description: "A TrafficSignalStateAction names a signal of the road network or of the scenario's signal controllers.",
    qcRule: QC.signalId,
  },
  severity: 'error',
});
