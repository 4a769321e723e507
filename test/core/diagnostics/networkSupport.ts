import { roadScenario } from '../../support/fixtures';

export { SIGNAL_ROAD as ROAD } from '../../support/roads';

/** A 1.2 scenario on road.xodr with one ManeuverGroup 'G' holding `actions` for `actors`, and `trafficSignals` in its RoadNetwork. */
export function groupScenario(actions: string, parts: { actors?: string; trafficSignals?: string } = {}): string {
  const group = `<ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">${parts.actors ?? '<EntityRef entityRef="Ego"/>'}</Actors>
          <Maneuver name="M">
            <Event name="E" priority="override">
              <Action name="Act">${actions}</Action>
              <StartTrigger/>
            </Event>
          </Maneuver>
        </ManeuverGroup>`;
  return roadScenario({ init: '', groups: [group], trafficSignals: parts.trafficSignals });
}
