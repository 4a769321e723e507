import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { Problem } from '../../server/src/core/problems';
import { schemaIndex } from '../../server/src/core/schema/index';
import { typeByElementName } from '../../server/src/core/schema/query';
import { schemaFindingWords } from '../../server/src/core/diagnostics/schemaFindings';
import { checkSchema } from '../../server/src/core/schema/validate';
import { SCHEMA_VERSIONS, SchemaVersion } from '../../server/src/core/schema/model';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../server/src/core/semantics';
import { documentedBounds, inRange, rangeText, readingsOf, VALUE_RANGES, ValueRange } from '../../server/src/core/semantics/ranges';
import { Simulator } from '../../server/src/core/profiles/simulators';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { temporaryWorkspace } from '../support/workspace';
import { textAt } from '../support/textEdits';
import {
  act,
  BARE_XML_DECLARATION,
  element,
  fileHeader,
  maneuver,
  maneuverGroup,
  openScenarioFile,
  parameterDeclarations,
  scenarioDocument,
  story,
  vehicleObject,
} from '../support/fixtures';

/** The out-of-range problems of a scenario (a file of its own in a fresh folder). */
async function outOfRange(text: string, simulator?: Simulator): Promise<Problem[]> {
  const root = temporaryWorkspace({ 'scenario.xosc': text });
  const semantics = await analyzeDocument(
    diskRef(path.join(root, 'scenario.xosc')),
    parseXml(text),
    new CatalogLoader(new ScenarioStore({ scenarioPath: [], root })),
    false,
    simulator,
  );
  return semanticProblems(semantics).filter((problem) => problem.code === 'out-of-range');
}

/** A file of `version` holding one element with one attribute: the range check looks at elements by name, wherever they stand. */
function bare(version: string, elementName: string, attributeName: string, value: string): string {
  const [major, minor] = version.split('.');
  return openScenarioFile(
    `  <${elementName} ${attributeName}="${value}"/>\n`,
    fileHeader({ revMajor: major, revMinor: minor, description: 'd', author: 'a' }),
    BARE_XML_DECLARATION,
  );
}

/** Values just outside the range, one per bound. */
function breaking(range: ValueRange): number[] {
  const values: number[] = [];
  if (range.min !== undefined) values.push(range.minOpen ? range.min : range.min - 1);
  if (range.max !== undefined) values.push(range.maxOpen ? range.max : range.max + 1);
  return values;
}

/** Values inside the range: each closed bound itself, else a value just inside it. */
function keeping(range: ValueRange): number[] {
  const values: number[] = [];
  if (range.min !== undefined) values.push(range.minOpen ? range.min + 0.5 : range.min);
  if (range.max !== undefined) values.push(range.maxOpen ? range.max - 0.5 : range.max);
  return values;
}

const CHECKED = VALUE_RANGES.filter((range) => !range.checkedBy);

describe("value ranges (the ASAM model's documented ranges, per version)", () => {
  it('writes each range as the standard does', () => {
    assert.equal(rangeText({ min: 0 }), '[0..inf[');
    assert.equal(rangeText({ min: 0, minOpen: true }), ']0..inf[');
    assert.equal(rangeText({ min: 0, max: 1 }), '[0..1]');
    assert.equal(rangeText({ min: 0, minOpen: true, max: 100 }), ']0..100]');
    assert.equal(rangeText({ min: 0, max: 2 * Math.PI, maxOpen: true }), '[0..2PI[');
    assert.equal(rangeText({ min: -Math.PI, max: Math.PI }), '[-PI..PI]');
  });

  it("every rule names an element of its model class and an attribute of it in each version's schema", () => {
    const missing: string[] = [];
    for (const range of VALUE_RANGES)
      for (const version of range.versions) {
        const index = schemaIndex(version);
        const type = typeByElementName(index, range.element);
        if (type !== (range.modelClass ?? range.element) || !index.attribute(type, range.attribute))
          missing.push(`${version} ${range.element}.${range.attribute}`);
      }
    assert.deepEqual(missing, []);
  });

  it('reads a range as the model documents it', () => {
    assert.deepEqual(documentedBounds('[0..inf['), { min: 0 });
    assert.deepEqual(documentedBounds(']0..inf['), { min: 0, minOpen: true });
    assert.deepEqual(documentedBounds('[0;PI]'), { min: 0, max: Math.PI });
    assert.deepEqual(documentedBounds('[170...340]'), { min: 170, max: 340 });
    assert.deepEqual(documentedBounds('[0..2*PI['), { min: 0, max: 2 * Math.PI, maxOpen: true });
    assert.deepEqual(documentedBounds('[0...2 pi['), { min: 0, max: 2 * Math.PI, maxOpen: true });
    assert.deepEqual(documentedBounds('[-PI/2..PI/2]'), { min: -Math.PI / 2, max: Math.PI / 2 });
    assert.deepEqual(documentedBounds(']-inf..inf['), {});
    assert.throws(() => documentedBounds('0 to 1'), /cannot read the documented range "0 to 1"/);
    assert.throws(() => documentedBounds('[0..many]'), /cannot read the bound "many"/);
  });

  it("every range names its source, the model's documentation of its class and attribute, and checks the bounds quoted there (or says why not)", () => {
    for (const range of VALUE_RANGES) {
      const label = `${range.element}.${range.attribute}`;
      const quoted = new RegExp(
        `^ASAM OpenSCENARIO 1\\.\\d(-1\\.\\d)? model, ${range.modelClass ?? range.element}\\.${range.attribute}: Range: (\\S+)(; checked as (\\S+): .+)?$`,
      ).exec(range.source);
      assert.ok(quoted, `${label}: ${range.source}`);
      const checked = documentedBounds(quoted[4] ?? quoted[2]);
      assert.deepEqual(
        { min: range.min, max: range.max, minOpen: range.minOpen ?? false, maxOpen: range.maxOpen ?? false },
        { min: checked.min, max: checked.max, minOpen: checked.minOpen ?? false, maxOpen: checked.maxOpen ?? false },
        label,
      );
    }
    const longitude = VALUE_RANGES.find((range) => range.element === 'GeoPosition' && range.attribute === 'longitude');
    assert.match(longitude?.source ?? '', /Range: \[-PI\/2\.\.PI\/2\]; checked as \[-PI\.\.PI\]: the model swaps/);
    assert.ok(longitude && inRange(2, longitude), 'a longitude of 2 rad (115 degrees east) is kept');
  });

  it("ranges the model does not document are not checked, although RA Consulting's checker data has them", async () => {
    for (const [element, attributeName, value] of [
      ['LightState', 'luminousIntensity', '-1'],
      ['LightState', 'flashingOnDuration', '-1'],
      ['LightState', 'flashingOffDuration', '-1'],
      ['AnimationAction', 'animationDuration', '-1'],
      ['Clutch', 'maxRate', '101'],
      ['SteeringWheel', 'maxRate', '101'],
      ['SteeringWheel', 'maxTorque', '0'],
    ])
      assert.deepEqual(await outOfRange(bare('1.3', element, attributeName, value)), [], `${element} ${attributeName}`);
    assert.equal(VALUE_RANGES.filter((range) => range.element === 'LightState' || range.attribute === 'maxTorque').length, 0);
  });

  it('a value beyond each bound of every rule is an error at the attribute, naming the range; the bounds themselves (closed) or just inside (open) are kept', async () => {
    for (const range of CHECKED) {
      for (const version of range.versions) {
        for (const value of breaking(range)) {
          const text = bare(version, range.element, range.attribute, String(value));
          const problems = await outOfRange(text);
          const label = `${version} ${range.element} ${range.attribute}=${value}`;
          assert.equal(problems.length, 1, label);
          const unconditional = readingsOf(range.esmini).some(
            (reading) => !reading.when && (!reading.versions || reading.versions.includes(version)),
          );
          assert.equal(problems[0].severity, unconditional ? 'warning' : 'error', label);
          assert.equal(textAt(text, problems[0].range), String(value), label);
          assert.ok(
            problems[0].message.includes(`is outside the standard's range ${rangeText(range)}`),
            `${label}: ${problems[0].message}`,
          );
          assert.ok(problems[0].message.startsWith(`${range.element} ${range.attribute} `), label);
        }
        for (const value of keeping(range)) {
          assert.deepEqual(
            await outOfRange(bare(version, range.element, range.attribute, String(value))),
            [],
            `${version} ${range.element} ${range.attribute}=${value}`,
          );
        }
      }
    }
  });

  it('a rule holds only in the versions whose model documents it; a later version is read as 1.3', async () => {
    const checkedIn = (range: ValueRange, version: SchemaVersion) => range.versions.includes(version);
    let scoped = 0;
    for (const range of CHECKED) {
      for (const version of SCHEMA_VERSIONS) {
        if (checkedIn(range, version)) continue;
        scoped++;
        for (const value of breaking(range))
          assert.deepEqual(
            await outOfRange(bare(version, range.element, range.attribute, String(value))),
            [],
            `${version} ${range.element}`,
          );
      }
    }
    assert.ok(scoped > 40, `${scoped} rules of 1.2 on only`);
    // RoadPosition s exists since 1.0; its range [0..inf[ is a rule of 1.2 and 1.3 only.
    assert.deepEqual(await outOfRange(bare('1.1', 'RoadPosition', 's', '-1')), []);
    assert.equal((await outOfRange(bare('1.2', 'RoadPosition', 's', '-1'))).length, 1);
    assert.equal((await outOfRange(bare('1.4', 'RoadPosition', 's', '-1'))).length, 1);
    // Weather and Wind are documented since the 1.1 model; a 1.0 schema has neither.
    assert.equal((await outOfRange(bare('1.1', 'Weather', 'atmosphericPressure', '10000'))).length, 1);
    assert.deepEqual(await outOfRange(bare('1.0', 'Weather', 'atmosphericPressure', '10000')), []);
  });

  it('an attribute of the same name under another element is not checked (a BrakeInput value, a Brake of a force)', async () => {
    assert.deepEqual(await outOfRange(bare('1.3', 'BrakePercent', 'value', '5')), []);
    assert.deepEqual(await outOfRange(bare('1.3', 'Axle', 'maxSteering', '9')), []);
    assert.equal((await outOfRange(bare('1.3', 'Brake', 'value', '5'))).length, 1);
    const [problem] = await outOfRange(bare('1.3', 'Brake', 'value', '5'));
    assert.match(problem.message, /class OverrideBrakeAction of the ASAM model/);
  });

  it("a GeoPosition's longitudeDeg spans a longitude's [-180..180], as the model documents it (RA Consulting's data gives it a latitude's)", async () => {
    assert.deepEqual(await outOfRange(bare('1.3', 'GeoPosition', 'longitudeDeg', '116.4')), []);
    assert.deepEqual(await outOfRange(bare('1.3', 'GeoPosition', 'longitudeDeg', '-180')), []);
    const [problem] = await outOfRange(bare('1.3', 'GeoPosition', 'longitudeDeg', '181'));
    assert.match(problem.message, /\[-180\.\.180\]/);
    assert.equal((await outOfRange(bare('1.3', 'GeoPosition', 'latitudeDeg', '91'))).length, 1);
  });

  it('Phase duration and LightStateAction transitionTime are left to their own rules', async () => {
    assert.deepEqual(await outOfRange(bare('1.3', 'Phase', 'duration', '-1')), []);
    assert.deepEqual(await outOfRange(bare('1.3', 'LightStateAction', 'transitionTime', '-1')), []);
  });
});

/** The Init's actions of scenario(): the weather, and Ego placed on the road (eight spaces in). */
const RANGES_INIT = `        <GlobalAction>
          <EnvironmentAction>
            <Environment name="env">
              <TimeOfDay animation="false" dateTime="2026-01-01T12:00:00"/>
              <Weather temperature="293" atmosphericPressure="101325">
                <Sun azimuth="3" elevation="1" illuminance="1000"/>
                <Fog visualRange="1000"/>
                <Precipitation precipitationType="dry" precipitationIntensity="0"/>
                <Wind direction="0" speed="3"/>
              </Weather>
              <RoadCondition frictionScaleFactor="0.9"/>
            </Environment>
          </EnvironmentAction>
        </GlobalAction>
        <Private entityRef="Ego">
          <PrivateAction>
            <TeleportAction><Position><RoadPosition roadId="1" s="10" t="0"/></Position></TeleportAction>
          </PrivateAction>
        </Private>
`;

/** The Event of scenario(), twelve spaces in: a speed change, controller overrides and a GeoPosition. */
const RANGES_EVENT = `            <Event name="E" priority="override" maximumExecutionCount="1">
              <Action name="Speed">
                <PrivateAction>
                  <LongitudinalAction>
                    <SpeedAction>
                      <SpeedActionDynamics dynamicsShape="linear" value="$Rate" dynamicsDimension="rate"/>
                      <SpeedActionTarget><AbsoluteTargetSpeed value="20"/></SpeedActionTarget>
                    </SpeedAction>
                  </LongitudinalAction>
                </PrivateAction>
              </Action>
              <Action name="Override">
                <PrivateAction>
                  <ControllerAction>
                    <OverrideControllerValueAction>
                      <Throttle active="true" value="0.5" maxRate="2"/>
                      <Brake active="false"><BrakePercent value="0.2"/></Brake>
                      <Clutch active="false" value="0"/>
                      <ParkingBrake active="false"><BrakeForce value="500"/></ParkingBrake>
                      <SteeringWheel active="false" value="0" maxRate="1" maxTorque="5"/>
                      <Gear active="false"><ManualGear number="1"/></Gear>
                    </OverrideControllerValueAction>
                  </ControllerAction>
                </PrivateAction>
              </Action>
              <Action name="Geo">
                <PrivateAction>
                  <TeleportAction><Position><GeoPosition latitudeDeg="48.1" longitudeDeg="11.5" altitude="0"/></Position></TeleportAction>
                </PrivateAction>
              </Action>
              <StartTrigger>
                <ConditionGroup>
                  <Condition name="C" delay="0" conditionEdge="none">
                    <ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition>
                  </Condition>
                </ConditionGroup>
              </StartTrigger>
            </Event>
`;

/** The Act's StartTrigger of scenario() (ten spaces in): at once. */
const RANGES_ACT_START = `          <ConditionGroup>
            <Condition name="Start" delay="0" conditionEdge="none">
              <ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition>
            </Condition>
          </ConditionGroup>
`;

/** A schema-valid 1.3 scenario in which each family of ranges has a value: weather, entity, storyboard, controller overrides, positions. */
function scenario(version = '3'): string {
  return scenarioDocument({
    declaration: BARE_XML_DECLARATION,
    header: fileHeader({ revMinor: version, description: 'ranges', author: 't' }),
    parameters: parameterDeclarations([['Rate', 'double', '4']], 4),
    catalogLocations: '',
    roadNetwork: '',
    entities: vehicleObject('Ego', { centerX: '1.4', centerZ: '0.9', length: '4.5', maxSpeed: '60', maxDeceleration: '9' }),
    storyboard:
      element('Init', element('Actions', RANGES_INIT, 6), 4) +
      story('S', act('A', maneuverGroup('G', 'Ego', maneuver('M', RANGES_EVENT)), RANGES_ACT_START)) +
      '    <StopTrigger/>\n',
  });
}

/** Each family: the written value replaced, the text the problem covers, and the range its message names. */
const FAMILIES: { family: string; from: string; to: string; at: string; range: string; warning?: true }[] = [
  { family: 'weather', from: 'temperature="293"', to: 'temperature="400"', at: '400', range: '[170..340]', warning: true },
  {
    family: 'weather',
    from: 'atmosphericPressure="101325"',
    to: 'atmosphericPressure="10000"',
    at: '10000',
    range: '[80000..120000]',
    warning: true,
  },
  { family: 'sun', from: 'azimuth="3"', to: 'azimuth="7"', at: '7', range: '[0..2PI]' },
  {
    family: 'wind (open upper bound)',
    from: 'direction="0"',
    to: 'direction="${2 * 3.141592653589793}"',
    at: '${2 * 3.141592653589793}',
    range: '[0..2PI[',
  },
  { family: 'fog', from: 'visualRange="1000"', to: 'visualRange="-1"', at: '-1', range: '[0..inf[' },
  { family: 'road condition', from: 'frictionScaleFactor="0.9"', to: 'frictionScaleFactor="-0.1"', at: '-0.1', range: '[0..inf[' },
  { family: 'dimensions', from: 'length="4.5"', to: 'length="-4.5"', at: '-4.5', range: '[0..inf[' },
  { family: 'performance', from: 'maxDeceleration="9"', to: 'maxDeceleration="-9"', at: '-9', range: '[0..inf[' },
  {
    family: 'axle (open lower bound)',
    from: 'wheelDiameter="0.6" trackWidth="1.8" positionX="3"',
    to: 'wheelDiameter="0" trackWidth="1.8" positionX="3"',
    at: '0',
    range: ']0..inf[',
  },
  { family: 'axle', from: 'maxSteering="0.5"', to: 'maxSteering="4"', at: '4', range: '[0..PI]', warning: true },
  {
    family: 'execution count',
    from: 'priority="override" maximumExecutionCount="1"',
    to: 'priority="override" maximumExecutionCount="0"',
    at: '0',
    range: '[1..inf[',
  },
  {
    family: 'execution count',
    from: 'maximumExecutionCount="1" name="G"',
    to: 'maximumExecutionCount="0" name="G"',
    at: '0',
    range: '[1..inf[',
  },
  { family: 'condition delay', from: 'name="C" delay="0"', to: 'name="C" delay="-2"', at: '-2', range: '[0..inf[' },
  {
    family: 'transition dynamics (through a parameter)',
    from: 'value="4"/>',
    to: 'value="-4"/>',
    at: '$Rate',
    range: '[0..inf[',
    warning: true,
  },
  {
    family: 'clutch override',
    from: '<Clutch active="false" value="0"/>',
    to: '<Clutch active="false" value="2"/>',
    at: '2',
    range: '[0..1]',
    warning: true,
  },
  {
    family: 'controller override',
    from: 'value="0.5" maxRate="2"',
    to: 'value="1.5" maxRate="2"',
    at: '1.5',
    range: '[0..1]',
    warning: true,
  },
  { family: 'road position', from: 's="10"', to: 's="-10"', at: '-10', range: '[0..inf[' },
  { family: 'geo position', from: 'latitudeDeg="48.1"', to: 'latitudeDeg="91"', at: '91', range: '[-90..90]' },
];

describe('value ranges in a schema-valid scenario', () => {
  it('the scenario is valid against the 1.3 schema and keeps every range', async () => {
    const text = scenario();
    const schema = checkSchema(parseXml(text), { modular: false });
    assert.deepEqual(
      schema.findings.filter((finding) => finding.severity === 'error').map((finding) => schemaFindingWords(finding).message),
      [],
    );
    assert.deepEqual(await outOfRange(text), []);
  });

  for (const { family, from, to, at, range, warning } of FAMILIES) {
    it(`${family}: ${to} is ${warning ? 'a warning (esmini reads it with one meaning)' : 'an error'} at the value naming ${range}`, async () => {
      const text = scenario().replace(from, to);
      assert.notEqual(text, scenario(), from);
      const problems = await outOfRange(text);
      assert.equal(problems.length, 1, JSON.stringify(problems));
      assert.equal(problems[0].severity, warning ? 'warning' : 'error');
      assert.equal(textAt(text, problems[0].range), at);
      assert.ok(problems[0].message.includes(`outside the standard's range ${range}`), problems[0].message);
    });
  }

  it('a negative rate, which esmini takes as its magnitude, is a warning saying what each reads (SPEC 12); a negative time stays an error', async () => {
    const negative = scenario().replace('value="4"/>', 'value="-4"/>');
    for (const simulator of [undefined, 'esmini'] as const) {
      const [problem] = await outOfRange(negative, simulator);
      assert.equal(problem.severity, 'warning');
      assert.match(
        problem.message,
        /range \[0\.\.inf\[ \(class TransitionDynamics of the ASAM model\) \(RA Consulting's checker reports it as an error\); esmini takes the rate's magnitude/,
      );
    }
    const time = negative.replace('dynamicsDimension="rate"', 'dynamicsDimension="time"');
    const [timed] = await outOfRange(time, 'esmini');
    assert.equal(timed.severity, 'error');
    assert.doesNotMatch(timed.message, /esmini/);
  });

  it("with the simulator carla, a negative speed rate is worded for ScenarioRunner, which reads it as a duration (issue 27: it was esmini's reading); a lane change's, whose reading is not recorded, says so", async () => {
    const negative = scenario().replace('value="4"/>', 'value="-4"/>');
    const [speed] = await outOfRange(negative, 'carla');
    assert.equal(speed.severity, 'warning');
    assert.match(
      speed.message,
      /\(RA Consulting's checker reports it as an error\); CARLA ScenarioRunner reads a SpeedAction's rate as a duration in seconds: .* ends the action when that many seconds have passed, at its first tick for a negative rate \(srunner\/tools\/openscenario_parser\.py:1314-1320, srunner\/scenariomanager\/scenarioatomics\/atomic_behaviors\.py:516, 560\)$/,
    );
    assert.doesNotMatch(speed.message, /esmini/);
    const laneChange = bare('1.0', 'LaneChangeActionDynamics', 'value', '-4').replace(
      'value="-4"',
      'dynamicsShape="linear" value="-4" dynamicsDimension="rate"',
    );
    const [lane] = await outOfRange(laneChange, 'carla');
    assert.equal(lane?.severity, 'warning', JSON.stringify(lane));
    assert.match(lane.message, /; what CARLA ScenarioRunner does with it is not recorded here; esmini takes the rate's magnitude/);
  });

  it('a maxSteering in degrees (esmini uses it nowhere) and a negative lateral distance (esmini takes its magnitude from 1.1 on) are warnings', async () => {
    const degrees = scenario().replace('maxSteering="0.5"', 'maxSteering="30"');
    const [steering] = await outOfRange(degrees);
    assert.equal(steering.severity, 'warning');
    assert.match(steering.message, /uses it nowhere/);
    const [lateral] = await outOfRange(bare('1.1', 'LateralDistanceAction', 'distance', '-2.0'));
    assert.equal(lateral.severity, 'warning');
    assert.match(
      lateral.message,
      /LateralDistanceAction distance -2 \(from -2\.0\) is outside the standard's range \[0\.\.inf\[.*esmini uses the absolute value/,
    );
  });

  it('in a 1.0 file a negative distance is not taken as its magnitude: esmini keeps the sign (it puts the entity on the other side; measured with esmini 3.6)', async () => {
    // esmini 3.6 on a 1.0 file, LateralDistanceAction -2 m from a car at y=-1.535: the ego ends at y=-3.48 (+2 m: y=0.41), with no warning; in a 1.1 file -2 and 2 both give 0.41.
    const [lateral] = await outOfRange(bare('1.0', 'LateralDistanceAction', 'distance', '-2.0'), 'esmini');
    assert.equal(lateral?.severity, 'warning', JSON.stringify(lateral));
    assert.doesNotMatch(lateral.message, /esmini uses the absolute value/);
    assert.match(lateral.message, /esmini keeps the sign in a 1\.0 file.*to the right of the referenced entity/);
    // LongitudinalDistanceAction -20 m behind a car at x=140.5 in a 1.0 file: the ego ends ahead of it, at x=160.5 (20 m: 120.5).
    for (const attributeName of ['distance', 'timeGap']) {
      const [longitudinal] = await outOfRange(bare('1.0', 'LongitudinalDistanceAction', attributeName, '-20'), 'esmini');
      assert.equal(longitudinal?.severity, 'warning', JSON.stringify(longitudinal));
      assert.doesNotMatch(longitudinal.message, /esmini uses the absolute value/);
      assert.match(longitudinal.message, /esmini keeps the sign in a 1\.0 file.*ahead of the referenced entity/);
    }
    const [later] = await outOfRange(bare('1.2', 'LongitudinalDistanceAction', 'distance', '-20'), 'esmini');
    assert.match(later.message, /esmini uses the absolute value/);
  });

  it('in a 1.1 file the rules of 1.2 on (RoadPosition s) do not apply, the rules of 1.0 on (Dimensions) do', async () => {
    const older = scenario('1').replace('s="10"', 's="-10"').replace('length="4.5"', 'length="-4.5"');
    const problems = await outOfRange(older);
    assert.deepEqual(
      problems.map((problem) => textAt(older, problem.range)),
      ['-4.5'],
    );
  });
});
