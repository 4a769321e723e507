import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import type { TraceRecord } from '../../common/src/trace';
import { mainOf, storeForInputs } from '../../server/src/cli/inputs';
import { Flattener } from '../../server/src/core/flatten';
import { removeRunFolder, runScenario } from '../../server/src/esmini/run';
import { esminiCatalogs, esminiRoads } from './esmini';
import { act, packageOf, speedChangeGroup } from './fixtures';
import { repoRoot } from './paths';

/** Where the two cut-ins' road and vehicle catalog are found. */
export const TWO_CUT_INS_ROAD_PATH = [esminiRoads, path.join(esminiCatalogs, 'Vehicles')];

/** esmini's program on the main file of `folder` (Run in esmini), 8 s: its log and the trace Run in esmini reads from that log. */
export async function programRun(folder: string): Promise<{ log: string; trace: TraceRecord[] }> {
  const result = await runScenario(new Flattener(storeForInputs([], undefined, [folder])), mainOf(folder), {
    roadPath: TWO_CUT_INS_ROAD_PATH,
    duration: 8,
  });
  try {
    assert.equal(result.outcome, 'ok', result.message);
    return { log: result.log, trace: result.trace ?? [] };
  } finally {
    removeRunFolder(result);
  }
}

/** The times esmini's log starts an element of this name (`[2.350] [info] ChangeLane standbyState -> startTransition -> runningState`). */
export function loggedStarts(log: string, name: string): number[] {
  const pattern = new RegExp(`^\\[([\\d.]+)\\] \\[info\\] ${name} standbyState -> startTransition -> runningState`, 'gm');
  return [...log.matchAll(pattern)].map((match) => Number(match[1]));
}

/**
 * The examples' lane_change.xosc imported by two groups of one main file, for two adversaries; the lead cuts in at a
 * relative distance of `leadGap` m (500: never, in the 8 s the tests run). `examples`: the repository's (inside VS Code,
 * the tests' bundle lies elsewhere).
 */
export function writeTwoCutIns(folder: string, leadGap = 30, examples = path.join(repoRoot, 'examples')): void {
  fs.copyFileSync(path.join(examples, 'lane_change.xosc'), path.join(folder, 'lane_change.xosc'));
  const main = fs.readFileSync(path.join(examples, 'main.xosc'), 'utf8');
  const first = main.indexOf('        <ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">');
  const second = main.indexOf('        <ManeuverGroup maximumExecutionCount="1" name="LeadVehicle">');
  const startTrigger = main.indexOf('        <StartTrigger>', second);
  const cutInGroup = main.slice(first, second);
  const leadGroup = cutInGroup
    .replace('name="CutInVehicle"', 'name="CutInLead"')
    .replaceAll('"adversary"', '"lead"')
    .replace('key="RelativeDistanceCondition.value" value="12"', `key="RelativeDistanceCondition.value" value="${leadGap}"`);
  fs.writeFileSync(path.join(folder, 'main.xosc'), main.slice(0, second) + leadGroup + main.slice(startTrigger));
}

/**
 * esmini's cut-in.xosc with an Act that starts after 3 s and waits on a RelativeClearanceCondition whose lane range
 * runs backwards (`from="1" to="-1"`): the schema allows it, esmini throws on it when it first weighs the condition
 * (OSCCondition.cpp, TrigByRelativeClearance::CheckCondition, LOG_ERROR_AND_QUIT), out of SE_StepDT: an abort.
 * The group is speedChangeGroup's, its Event `E`.
 */
export function writeClearanceCrash(cutIn: string): string {
  const clearance =
    '<RelativeClearanceCondition distanceForward="10" distanceBackward="10" freeSpace="true" oppositeLanes="false">' +
    '<RelativeLaneRange from="1" to="-1"/><EntityRef entityRef="OverTaker"/></RelativeClearanceCondition>';
  const group = speedChangeGroup('ClearanceGroup', 'Ego', '10', 'Ego').replace('<TraveledDistanceCondition value="5"/>', clearance);
  const afterThreeSeconds = `          <ConditionGroup>
            <Condition name="ClearanceActStart" delay="0" conditionEdge="rising">
              <ByValueCondition><SimulationTimeCondition value="3" rule="greaterThan"/></ByValueCondition>
            </Condition>
          </ConditionGroup>
`;
  const storyEnd = cutIn.indexOf('</Story>');
  if (storyEnd < 0) throw new Error('cut-in.xosc has no </Story>');
  const lineStart = cutIn.lastIndexOf('\n', storyEnd) + 1;
  return cutIn.slice(0, lineStart) + act('ClearanceAct', group, afterThreeSeconds) + cutIn.slice(lineStart);
}

/**
 * esmini's cut-in.xosc made into a crash in a step where esmini calls nothing back: OverTaker is deleted in the Init
 * (DeleteEntityAction), and a story of its own waits on a RelativeClearanceCondition with a backwards lane range
 * (as writeClearanceCrash) towards OverTaker, with an Event after it that adds OverTaker back once the time is past
 * 3 s (AddEntityAction). esmini weighs the condition at every step but throws only once OverTaker is among the active
 * entities (TrigByRelativeClearance::CheckCondition reaches its from/to check only for an entity it finds), and it
 * weighs it before the adding Event (storyboard order): it dies in the step after the one that added OverTaker, before
 * anything in that step was reported. The cut-in story goes (its events act on OverTaker); the scenario ends when the
 * clearance Event would.
 */
export function writeAddedEntityCrash(cutIn: string): string {
  const actions = cutIn.indexOf('<Actions>', cutIn.indexOf('<Init>'));
  const storyStart = cutIn.indexOf('<Story name="CutInAndBrakeStory">');
  const storyEnd = cutIn.indexOf('</Story>');
  const stopRef = 'storyboardElementRef="CutInManeuver"';
  if (actions < 0 || storyStart < 0 || storyEnd < 0 || !cutIn.includes(stopRef)) throw new Error('cut-in.xosc is not as expected');
  const deleteOverTaker = '<GlobalAction><EntityAction entityRef="OverTaker"><DeleteEntityAction/></EntityAction></GlobalAction>';
  const clearance =
    '<RelativeClearanceCondition distanceForward="10" distanceBackward="10" freeSpace="true" oppositeLanes="false">' +
    '<RelativeLaneRange from="1" to="-1"/><EntityRef entityRef="OverTaker"/></RelativeClearanceCondition>';
  const story = `<Story name="ClearanceStory">
         <Act name="ClearanceAct">
            <ManeuverGroup maximumExecutionCount="1" name="ClearanceGroup">
               <Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
               <Maneuver name="ClearanceManeuver">
                  <Event name="ClearanceEvent" priority="overwrite">
                     <Action name="ClearanceSlowDown">
                        <PrivateAction><LongitudinalAction><SpeedAction>
                           <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
                           <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget>
                        </SpeedAction></LongitudinalAction></PrivateAction>
                     </Action>
                     <StartTrigger><ConditionGroup>
                        <Condition name="ClearanceCondition" delay="0" conditionEdge="none">
                           <ByEntityCondition>
                              <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities>
                              <EntityCondition>${clearance}</EntityCondition>
                           </ByEntityCondition>
                        </Condition>
                     </ConditionGroup></StartTrigger>
                  </Event>
                  <Event name="AddOverTaker" priority="parallel">
                     <Action name="AddOverTakerAction">
                        <GlobalAction><EntityAction entityRef="OverTaker"><AddEntityAction>
                           <Position><LanePosition roadId="0" laneId="-2" offset="0" s="25"/></Position>
                        </AddEntityAction></EntityAction></GlobalAction>
                     </Action>
                     <StartTrigger><ConditionGroup>
                        <Condition name="AddAfterThreeSeconds" delay="0" conditionEdge="rising">
                           <ByValueCondition><SimulationTimeCondition value="3" rule="greaterThan"/></ByValueCondition>
                        </Condition>
                     </ConditionGroup></StartTrigger>
                  </Event>
               </Maneuver>
            </ManeuverGroup>
            <StartTrigger><ConditionGroup>
               <Condition name="ClearanceActStart" delay="0" conditionEdge="none">
                  <ByValueCondition><SimulationTimeCondition value="-1" rule="greaterThan"/></ByValueCondition>
               </Condition>
            </ConditionGroup></StartTrigger>
         </Act>
      `;
  return (
    cutIn.slice(0, actions + '<Actions>'.length) +
    deleteOverTaker +
    cutIn.slice(actions + '<Actions>'.length, storyStart) +
    story +
    cutIn
      .slice(storyEnd)
      .replace('storyboardElementType="maneuver"', 'storyboardElementType="event"')
      .replace(stopRef, 'storyboardElementRef="ClearanceEvent"')
  );
}

/**
 * writeTwoCutIns' main as an intermediate main in `inner/`, imported by a top main in `folder` (main.xosc's copy) whose
 * group `Outer` takes `CutInVehicle.CutIn` from it through a ScenarioReference: two levels of nesting. Returns the files.
 */
export function writeNestedCutIn(folder: string): { top: string; inner: string; simple: string } {
  const innerFolder = path.join(folder, 'inner');
  fs.mkdirSync(innerFolder);
  writeTwoCutIns(innerFolder);
  const inner = path.join(innerFolder, 'main.xosc');
  const text = fs.readFileSync(inner, 'utf8');
  const first = text.indexOf('        <ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">');
  const second = text.indexOf('        <ManeuverGroup maximumExecutionCount="1" name="CutInLead">');
  const startTrigger = text.indexOf('        <StartTrigger>', second);
  const reference = text.indexOf('          <ScenarioReference', first);
  const referenceEnd = text.indexOf('</ScenarioReference>', reference) + '</ScenarioReference>'.length;
  const outer =
    text.slice(first, reference).replace('name="CutInVehicle"', 'name="Outer"') +
    '          <ScenarioReference scenarioFileName="inner/main.xosc">\n' +
    '            <ManeuverGroupReference maneuverGroupName="CutInVehicle.CutIn"/>\n' +
    '          </ScenarioReference>' +
    text.slice(referenceEnd, second);
  const top = path.join(folder, 'main.xosc');
  fs.writeFileSync(top, text.slice(0, first) + outer + text.slice(startTrigger));
  return { top, inner, simple: path.join(innerFolder, 'lane_change.xosc') };
}

/**
 * writeNestedCutIn with the intermediate main packed: `inner.mosc` holds its main.xosc and lane_change.xosc, and the
 * top main imports `CutInVehicle.CutIn` from the package. Returns the top main and the package's main text.
 */
export async function writeNestedCutInPackage(folder: string): Promise<{ top: string; pack: string; innerText: string }> {
  const { top, inner, simple } = writeNestedCutIn(folder);
  const innerText = fs.readFileSync(inner, 'utf8');
  const pack = path.join(folder, 'inner.mosc');
  fs.writeFileSync(pack, await packageOf({ 'main.xosc': innerText, 'lane_change.xosc': fs.readFileSync(simple, 'utf8') }));
  fs.rmSync(path.dirname(inner), { recursive: true });
  const text = fs.readFileSync(top, 'utf8');
  assert.ok(text.includes('scenarioFileName="inner/main.xosc"'));
  fs.writeFileSync(top, text.replace('scenarioFileName="inner/main.xosc"', 'scenarioFileName="inner.mosc"'));
  return { top, pack, innerText };
}
