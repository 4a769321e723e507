/** A SpeedAction to `value` (a number, a $parameter, an expression): a place where the document checks read a value. */
export const speed = (value: string): string =>
  `<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="${value}"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>`;

/** A ManeuverGroup 'G' for `actor` with one Event 'E' holding `actions`, started by no condition. */
export const group = (actions: string, actor = 'Ego'): string =>
  `<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="${actor}"/></Actors><Maneuver name="M"><Event name="E" priority="override"><Action name="A1">${actions}</Action><StartTrigger/></Event></Maneuver></ManeuverGroup>`;

/** A StartTrigger of one ByValueCondition holding `condition`. */
export const trigger = (condition: string): string =>
  `<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>${condition}</ByValueCondition></Condition></ConditionGroup></StartTrigger>`;
