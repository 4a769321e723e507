import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { Problem } from '../../server/src/core/problems';
import { ruleIdOf } from '../../server/src/core/rules';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../server/src/core/semantics';
import { diskRef, nodeFileSystem, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { roadScenario } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';
import { textAt } from '../support/textEdits';

/** A road file with one road, signal 101 on it, and a controller that controls signal 102. */
const ROAD = `<?xml version="1.0"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6"/>
  <road id="1" length="100" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
    <lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes>
    <signals><signal id="101" s="50" t="-3"/></signals>
  </road>
  <controller id="7" name="c"><control signalId="102"/></controller>
</OpenDRIVE>
`;

interface Parts {
  logicFile?: string;
  trafficSignals?: string;
  parameters?: string;
  actors?: string;
  actions?: string;
  init?: string;
}

/** A 1.2 scenario with a road network, one ManeuverGroup, and whatever each case puts in. */
function scenario(parts: Parts): string {
  const group = `<ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">${parts.actors ?? '<EntityRef entityRef="Ego"/>'}</Actors>
          <Maneuver name="M">
            <Event name="E" priority="override">
              <Action name="Act">${parts.actions ?? '<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>'}</Action>
              <StartTrigger/>
            </Event>
          </Maneuver>
        </ManeuverGroup>`;
  return roadScenario({ ...parts, init: parts.init ?? '', groups: [group] });
}

const RULE_CODES = new Set([
  'unknown-traffic-signal',
  'unknown-traffic-signal-controller',
  'no-actor',
  'negative-transition-time',
  'non-positive-phase-duration',
  'out-of-range',
]);

/** The problems of these rules for a scenario written beside `files`. */
async function check(text: string, files: Record<string, string> = { 'road.xodr': ROAD }): Promise<{ problems: Problem[]; text: string }> {
  const root = temporaryWorkspace({ 'scenario.xosc': text, ...files });
  const semantics = await analyzeDocument(
    diskRef(path.join(root, 'scenario.xosc')),
    parseXml(text),
    new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
    false,
  );
  return { problems: semanticProblems(semantics).filter((problem) => RULE_CODES.has(problem.code)), text };
}

/** The text a problem's range covers, up to the end of its first line. */
function firstLineAt(text: string, problem: Problem): string {
  return textAt(text, problem.range).split('\n')[0];
}

function signalAction(name: string): string {
  return `<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="${name}" state="off;off;on"/></TrafficSignalAction></InfrastructureAction></GlobalAction>`;
}

const CONTROLLERS = `<TrafficSignals>
      <TrafficSignalController name="Ctrl">
        <Phase name="go" duration="10"><TrafficSignalState trafficSignalId="201" state="on"/></Phase>
      </TrafficSignalController>
    </TrafficSignals>`;

describe('road-network and value-range rules', () => {
  it("each code names ASAM's Quality Checker rule it stands for; an operator or constant the standard lacks is data_type.allowed_operators", () => {
    const uids = {
      'unknown-traffic-signal': 'reference_control.resolvable_signal_id_in_traffic_signal_state_action',
      'unknown-traffic-signal-controller': 'reference_control.resolvable_traffic_signal_controller_by_traffic_signal_controller_ref',
      'no-actor': 'reference_control.valid_actor_reference_in_private_actions',
      'negative-transition-time': 'data_type.non_negative_transition_time_in_light_state_action',
      'non-positive-phase-duration': 'data_type.positive_duration_in_phase',
      'nonstandard-expression': 'data_type.allowed_operators',
    } as const;
    for (const [code, rule] of Object.entries(uids)) assert.equal(ruleIdOf(code as keyof typeof uids), `asam.net:xosc:1.2.0:${rule}`);
    assert.equal(ruleIdOf('out-of-range'), 'modular2simple:out-of-range');
  });

  it('a TrafficSignalStateAction naming no signal of the road file is an error at its name, with the QC rule', async () => {
    const { problems, text } = await check(scenario({ actions: signalAction('999') }));
    assert.equal(problems.length, 1, JSON.stringify(problems));
    assert.equal(problems[0].code, 'unknown-traffic-signal');
    assert.equal(problems[0].severity, 'error');
    assert.equal(firstLineAt(text, problems[0]), '999');
    assert.equal(ruleIdOf(problems[0].code), 'asam.net:xosc:1.2.0:reference_control.resolvable_signal_id_in_traffic_signal_state_action');
  });

  it("a signal of a road, of the road file's controller, of the scenario's controller, or given by a parameter, resolves", async () => {
    for (const name of ['101', '102', '201', '$Signal']) {
      const { problems } = await check(
        scenario({
          actions: signalAction(name),
          trafficSignals: CONTROLLERS,
          parameters: '<ParameterDeclaration name="Signal" parameterType="string" value="101"/>',
        }),
      );
      assert.deepEqual(problems, [], name);
    }
  });

  it("reads the road file's signals only for a scenario that sets a signal's state", async () => {
    const analyze = async (text: string) => {
      const root = temporaryWorkspace({ 'scenario.xosc': text, 'road.xodr': ROAD });
      const reads: string[] = [];
      const host = {
        ...nodeFileSystem,
        readFile: (file: string, maxBytes?: number) => (reads.push(file), nodeFileSystem.readFile(file, maxBytes)),
      };
      const store = new ScenarioStore({ scenarioPath: [], root, host });
      const semantics = await analyzeDocument(diskRef(path.join(root, 'scenario.xosc')), parseXml(text), new CatalogLoader(store), false);
      return { semantics, roadReads: reads.filter((file) => file.endsWith('road.xodr')).length };
    };
    const without = await analyze(scenario({}));
    assert.equal(
      without.semantics.roadFile?.resolved,
      path.join(path.dirname(without.semantics.ref.disk), 'road.xodr'),
      'the road is found',
    );
    assert.deepEqual([without.roadReads, without.semantics.road], [0, undefined], 'and not read');
    const withAction = await analyze(scenario({ actions: signalAction('999') }));
    assert.equal(withAction.roadReads, 1);
    assert.deepEqual([...(withAction.semantics.road?.signalIds ?? [])].sort(), ['101', '102']);
  });

  it('no road file to read (missing, not OpenDRIVE): the signal rule says nothing', async () => {
    assert.deepEqual((await check(scenario({ actions: signalAction('999'), logicFile: 'gone.xodr' }))).problems, []);
    assert.deepEqual((await check(scenario({ actions: signalAction('999') }), { 'road.xodr': '<NotOpenDrive/>' })).problems, []);
  });

  it('a trafficSignalControllerRef naming no controller of the scenario is an error at the reference', async () => {
    const action =
      '<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalControllerAction trafficSignalControllerRef="Nope" phase="go"/></TrafficSignalAction></InfrastructureAction></GlobalAction>';
    const { problems, text } = await check(scenario({ actions: action, trafficSignals: CONTROLLERS }));
    assert.equal(problems.length, 1, JSON.stringify(problems));
    assert.equal(problems[0].code, 'unknown-traffic-signal-controller');
    assert.equal(firstLineAt(text, problems[0]), 'Nope');
    assert.match(problems[0].message, /'Ctrl'/);
    const clean = await check(scenario({ actions: action.replace('Nope', 'Ctrl'), trafficSignals: CONTROLLERS }));
    assert.deepEqual(clean.problems, []);
  });

  it('a ManeuverGroup with private actions and no actor is an error at its Actors (esmini refuses it too)', async () => {
    const bare = scenario({ actors: '' });
    const { problems, text } = await check(bare);
    assert.equal(problems.length, 1, JSON.stringify(problems));
    assert.equal(problems[0].code, 'no-actor');
    assert.equal(problems[0].severity, 'error');
    assert.equal(firstLineAt(text, problems[0]), '<Actors');
    assert.deepEqual((await check(scenario({}))).problems, []);
  });

  it('a negative LightStateAction transitionTime is an error at the attribute; zero is fine', async () => {
    const light = (time: string) =>
      `<PrivateAction><AppearanceAction><LightStateAction transitionTime="${time}"><LightType><VehicleLight vehicleLightType="headLights"/></LightType><LightState mode="on"/></LightStateAction></AppearanceAction></PrivateAction>`;
    const { problems, text } = await check(scenario({ actions: light('-0.5') }));
    assert.equal(problems.length, 1, JSON.stringify(problems));
    assert.equal(problems[0].code, 'negative-transition-time');
    assert.equal(firstLineAt(text, problems[0]), '-0.5');
    assert.deepEqual((await check(scenario({ actions: light('0') }))).problems, []);
  });

  it('a Phase duration below zero is an error, zero a warning naming both readings, a positive one fine', async () => {
    const withDuration = (duration: string) => scenario({ trafficSignals: CONTROLLERS.replace('duration="10"', `duration="${duration}"`) });
    const negative = await check(withDuration('-1'));
    assert.equal(negative.problems.length, 1);
    assert.equal(negative.problems[0].severity, 'error');
    assert.equal(firstLineAt(negative.text, negative.problems[0]), '-1');
    const zero = await check(withDuration('0'));
    assert.equal(zero.problems[0].severity, 'warning');
    assert.match(zero.problems[0].message, /standard.*ASAM/);
    assert.deepEqual((await check(withDuration('10'))).problems, []);
  });

  it('a value outside its range is an error at the attribute, evaluated through parameters and expressions', async () => {
    const environment = (friction: string) =>
      `<GlobalAction><EnvironmentAction><Environment name="env"><TimeOfDay animation="false" dateTime="2026-01-01T12:00:00"/><Weather><Sun azimuth="0" elevation="1" illuminance="1000"/><Fog visualRange="1000"/><Precipitation precipitationType="dry" precipitationIntensity="0"/></Weather><RoadCondition frictionScaleFactor="${friction}"/></Environment></EnvironmentAction></GlobalAction>`;
    const parameters = '<ParameterDeclaration name="Friction" parameterType="double" value="-0.2"/>';
    const { problems, text } = await check(scenario({ init: environment('$Friction'), parameters }));
    assert.equal(problems.length, 1, JSON.stringify(problems));
    assert.equal(problems[0].code, 'out-of-range');
    assert.equal(firstLineAt(text, problems[0]), '$Friction');
    assert.match(problems[0].message, /frictionScaleFactor -0\.2 \(from \$Friction\) is outside the standard's range \[0\.\.inf\[/);
    const expression = await check(scenario({ init: environment('${1 - 2}') }));
    assert.equal(expression.problems.length, 1);
    assert.deepEqual((await check(scenario({ init: environment('0.8') }))).problems, []);
    const throttle = await check(
      scenario({
        actions:
          '<PrivateAction><ControllerAction><OverrideControllerValueAction><Throttle active="true" value="0.5"/><Brake active="false" value="0"/><Clutch active="false" value="0"/><ParkingBrake active="false" value="0"/><SteeringWheel active="false" value="0"/><Gear active="false" number="0"/></OverrideControllerValueAction></ControllerAction></PrivateAction>',
      }),
    );
    assert.deepEqual(throttle.problems, []);
  });
});
