import { scenarioRunnerVehicle } from './carla';

/*
 * Small 1.0 scenarios on Town01 whose stories set and compare parameters, as ScenarioRunner 0.9.16 loads them: for the
 * check of ParameterConditions ScenarioRunner compares as text (core/semantics/checks/carlaParameters.ts) and the
 * harness that ticks them (./carlaTree.py story_ticks). Parameters: 'gap' (3) and 'done' (0, set in the Init).
 */

/** A Condition comparing `parameter`. */
export const parameterCondition = (name: string, rule: string, value: string, parameter = 'gap'): string =>
  `<Condition name="${name}" delay="0" conditionEdge="none"><ByValueCondition><ParameterCondition parameterRef="${parameter}" value="${value}" rule="${rule}"/></ByValueCondition></Condition>`;

/** A Condition that holds once its element has run for a second (ScenarioRunner counts from the condition's first tick). */
export const afterASecond = (name: string): string =>
  `<Condition name="${name}" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition></Condition>`;

/** A Condition that holds at its first tick. */
export const atOnce = (name: string): string =>
  `<Condition name="${name}" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="100" rule="lessThan"/></ByValueCondition></Condition>`;

/** An Event whose action sets `parameter` to `value`, started by `trigger` (a Condition). */
export const settingEvent = (name: string, trigger: string, parameter = 'done', value = '1'): string => `
            <Event name="${name}" priority="parallel">
              <Action name="${name}Action"><GlobalAction><ParameterAction parameterRef="${parameter}"><SetAction value="${value}"/></ParameterAction></GlobalAction></Action>
              <StartTrigger><ConditionGroup>${trigger}</ConditionGroup></StartTrigger>
            </Event>`;

/** An Act of one maneuver holding `events`, started by `trigger` (at once by default), with `stop` (a StopTrigger) if given. */
export const storyAct = (name: string, events: string[], trigger = atOnce(`${name}Starts`), stop = ''): string => `
      <Act name="${name}">
        <ManeuverGroup maximumExecutionCount="1" name="${name}Group">
          <Actors selectTriggeringEntities="false"/>
          <Maneuver name="${name}Maneuver">${events.join('')}
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger><ConditionGroup>${trigger}</ConditionGroup></StartTrigger>${stop}
      </Act>`;

/** The scenario of one Story holding `acts`; `init`: more GlobalActions of the Init. */
export const parameterStoryScenario = (acts: string[], init = ''): string => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-11-29T00:00:00" description="story-set parameters" author="modular2simple tests"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="gap" parameterType="double" value="3"/>
    <ParameterDeclaration name="done" parameterType="double" value="0"/>
  </ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork><LogicFile filepath="Town01"/></RoadNetwork>
  <Entities>${scenarioRunnerVehicle('Ego', 'ego_vehicle')}
  </Entities>
  <Storyboard>
    <Init><Actions>
      <GlobalAction><ParameterAction parameterRef="done"><SetAction value="0"/></ParameterAction></GlobalAction>${init}
      <Private entityRef="Ego"><PrivateAction><TeleportAction><Position><WorldPosition x="100" y="-2" z="0" h="0"/></Position></TeleportAction></PrivateAction></Private>
    </Actions></Init>
    <Story name="Story">${acts.join('')}
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
