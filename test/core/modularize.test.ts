import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import fc from 'fast-check';
import { firstDifference } from '../../server/src/core/equivalence';
import { Flattener } from '../../server/src/core/flatten';
import { modularize, memoryHost, ModularizeInput, ModularizeResult, notAPlainScenario } from '../../server/src/core/modularize';
import { behaviourName } from '../../server/src/core/modularize/naming';
import { buildModel } from '../../server/src/core/model';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { libraryDir, requireCorpus } from '../support/paths';
import { assertFlattensBack } from '../support/modularizeLibrary';
import { scenario, speedChangeGroup as speedGroup, xmlAttribute as xmlAttributeValue } from '../support/fixtures';

/** The paper's 31 flattened scenarios, each as `OUT/<folder>/result.xosc`. */
function libraryInputs(out: string): ModularizeInput[] {
  return fs
    .readdirSync(libraryDir)
    .filter((folder) => fs.existsSync(path.join(libraryDir, folder, 'result.xosc')))
    .sort()
    .map((folder) => {
      const file = path.join(libraryDir, folder, 'result.xosc');
      return { path: file, output: path.join(out, folder, 'result.xosc'), text: fs.readFileSync(file, 'utf8') };
    });
}

/** Flattens every main of a result with the project's flattener, the outputs read from memory, as a user would after writing them. */
async function flattenAll(result: ModularizeResult): Promise<Map<string, string | undefined>> {
  const files = new Map<string, string>();
  for (const behaviour of result.behaviours) files.set(behaviour.file, behaviour.text);
  for (const main of result.mains) files.set(main.output, main.text);
  const flattener = new Flattener(new ScenarioStore({ host: memoryHost(files), scenarioPath: [] }));
  const flattened = new Map<string, string | undefined>();
  for (const main of result.mains) flattened.set(main.input, (await flattener.flatten(diskRef(main.output))).text);
  return flattened;
}

describe('core: modularize', function () {
  this.timeout(120_000);

  it("the paper's library: 31 of 31 mains flatten back equivalent, smaller than the authors' 10,810 lines", async function () {
    requireCorpus(this);
    const out = '/virtual/library-out';
    const inputs = libraryInputs(out);
    assert.equal(inputs.length, 31);
    const result = await modularize(inputs, { simpleFolder: path.join(out, 'simple') });
    assert.deepEqual(result.failures, []);
    assert.ok(result.behaviours.length >= 1);
    // Checked again here, independently of modularize's own proof.
    const flattened = await flattenAll(result);
    let equivalent = 0;
    for (const input of inputs) {
      const text = flattened.get(input.path);
      assert.ok(text !== undefined, `${input.path} flattens`);
      assert.equal(firstDifference(text, input.text), undefined, input.path);
      equivalent++;
    }
    assert.equal(equivalent, 31);
    assert.equal(result.totals.linesBefore, 21_243);
    console.log(
      `      library: ${result.totals.linesBefore.toLocaleString('en-US')} -> ${result.totals.linesAfter.toLocaleString('en-US')} lines (${result.totals.reduction} %; the authors by hand: 10,810, 49.1 %)`,
    );
    assert.ok(result.totals.linesAfter < 10_810, `${result.totals.linesAfter} lines`);
    assert.ok(!fs.existsSync(out), 'modularize itself writes nothing');
  });

  it('lists exactly the attributes whose values differ, each with its most common value as default, set only where they differ', async () => {
    const out = '/virtual/out';
    const texts = [
      scenario(speedGroup('Lead.Go', 'car', '10') + speedGroup('Other.Go', 'car', '10')),
      scenario(speedGroup('Follow.Go', 'car', '20')),
    ];
    const inputs = texts.map((text, index) => ({ path: `/virtual/in/s${index}.xosc`, output: `${out}/s${index}.xosc`, text }));
    const result = await modularize(inputs, { simpleFolder: `${out}/simple` });
    assert.deepEqual(result.failures, []);
    assert.equal(result.behaviours.length, 1);
    const [behaviour] = result.behaviours;
    assert.equal(path.basename(behaviour.file), 'speed_after_traveled_distance.xosc');
    assert.deepEqual(behaviour.parameters, ['AbsoluteTargetSpeed.value']);
    assert.equal(behaviour.groupName, 'Go');
    const simple = parseXml(behaviour.text);
    const listed = buildModel(simple).declarations.map((declaration) => `${declaration.element.name}:${declaration.attribute.value}`);
    assert.deepEqual(listed, ['AbsoluteTargetSpeed:value']);
    assert.match(behaviour.text, /<AbsoluteTargetSpeed parameterAttributes="value" value="10"\/>/);
    // The simple scenario declares the entities its group names.
    assert.deepEqual(
      buildModel(simple)
        .entities.map((entity) => entity.name)
        .sort(),
      ['car', 'ego'],
    );
    assert.deepEqual(
      behaviour.uses.map((use) => use.overrides),
      [[], [], [{ key: 'value', value: '20' }]],
    );
    assert.deepEqual(
      behaviour.uses.map((use) => use.outerName),
      ['Lead', 'Other', 'Follow'],
    );
    assert.match(result.mains[1].text, /<ScenarioReference scenarioFileName="simple\/speed_after_traveled_distance\.xosc">/);
    const flattened = await flattenAll(result);
    for (const input of inputs) assert.equal(firstDifference(flattened.get(input.path) as string, input.text), undefined);
  });

  it('a group name without an outer part, and an actor, are reproduced exactly', async () => {
    // Four uses: two would not pay for the simple scenario they need.
    const texts = [
      scenario(speedGroup('Brake', 'car', '10', 'car')),
      scenario(speedGroup('Slow', 'ego', '10', 'ego')),
      scenario(speedGroup('Stop', 'car', '10', 'car')),
      scenario(speedGroup('Halt', 'ego', '10', 'ego')),
    ];
    const inputs = texts.map((text, index) => ({ path: `/virtual/in/s${index}.xosc`, output: `/virtual/out/s${index}.xosc`, text }));
    const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
    assert.deepEqual(result.failures, []);
    assert.equal(result.behaviours.length, 1);
    assert.deepEqual(result.behaviours[0].parameters, ['ManeuverGroup.name', 'EntityRef.entityRef']);
    const flattened = await flattenAll(result);
    for (const input of inputs) assert.equal(firstDifference(flattened.get(input.path) as string, input.text), undefined);
  });

  it('no recurring group: nothing extracted, the mains are the inputs', async () => {
    const inputs = [
      { path: '/virtual/in/a.xosc', output: '/virtual/out/a.xosc', text: scenario(speedGroup('A', 'car', '10')) },
      {
        path: '/virtual/in/b.xosc',
        output: '/virtual/out/b.xosc',
        text: scenario(
          speedGroup('B', 'car', '10').replace('<TraveledDistanceCondition value="5"/>', '<StandStillCondition duration="1"/>'),
        ),
      },
    ];
    const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
    assert.equal(result.behaviours.length, 0);
    assert.deepEqual(
      result.mains.map((main) => main.text),
      inputs.map((input) => input.text),
    );
    assert.equal(result.totals.reduction, 0);
  });

  it('two attributes of one path are told apart by a key that gives the position (Event[2])', async () => {
    // Two Events whose AbsoluteTargetSpeed paths are identical: a plain key would set both.
    const twice = (name: string, first: string, second: string) =>
      speedGroup(name, 'car', first).replace(
        /(<Maneuver name="M">\n)([\s\S]*?<\/Event>\n)/,
        (_all, open: string, event: string) =>
          open + event + event.replace('name="E"', 'name="E2"').replace(`value="${first}"`, `value="${second}"`),
      );
    const inputs = [twice('X.G', '1', '2'), twice('Y.G', '3', '4'), twice('Z.G', '3', '4')].map((groups, index) => ({
      path: `/virtual/in/s${index}.xosc`,
      output: `/virtual/out/s${index}.xosc`,
      text: scenario(groups),
    }));
    const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
    assert.deepEqual(result.failures, []);
    assert.deepEqual(result.keptInline, []);
    assert.equal(result.behaviours.length, 1);
    assert.deepEqual(
      result.behaviours[0].uses.map((use) => use.overrides),
      [
        [
          { key: 'Event[1].Action.PrivateAction.LongitudinalAction.SpeedAction.SpeedActionTarget.AbsoluteTargetSpeed.value', value: '1' },
          { key: 'Event[2].Action.PrivateAction.LongitudinalAction.SpeedAction.SpeedActionTarget.AbsoluteTargetSpeed.value', value: '2' },
        ],
        [],
        [],
      ],
    );
    const flattened = await flattenAll(result);
    for (const input of inputs) assert.equal(firstDifference(flattened.get(input.path) as string, input.text), undefined);
  });

  it('the shortest key that sets the same attributes (entityRef), not the ten-segment path from ManeuverGroup down', async () => {
    // Two conditions of one ConditionGroup: their EntityRefs share one path and always name the same
    // entity, so one short key sets both (the old code wrote the whole path from ManeuverGroup down).
    const twoConditions = (text: string) =>
      text.replace(
        /( *<Condition name="C"[\s\S]*?<\/Condition>\n)/,
        (condition: string) => condition + condition.replace('name="C"', 'name="C2"'),
      );
    const inputs = ['car', 'ego', 'car', 'ego'].map((trigger, index) => ({
      path: `/virtual/in/s${index}.xosc`,
      output: `/virtual/out/s${index}.xosc`,
      text: scenario(twoConditions(speedGroup(`G${index}.Go`, 'car', '10', trigger))),
    }));
    const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
    assert.deepEqual(result.failures, []);
    assert.equal(result.behaviours.length, 1);
    const keys = new Set(result.behaviours[0].uses.flatMap((use) => use.overrides.map((override) => override.key)));
    assert.deepEqual([...keys], ['entityRef']);
    const flattened = await flattenAll(result);
    for (const input of inputs) assert.equal(firstDifference(flattened.get(input.path) as string, input.text), undefined);
  });

  it('any library of such groups: every main flattens back equivalent and unwarned (property)', async () => {
    const groupSpec = fc.record({
      name: fc.constantFrom('Go', 'A.Go', 'B.Go', 'Lead.Brake', 'x.y.Go', 'Go.'),
      actor: fc.constantFrom('ego', 'car'),
      trigger: fc.constantFrom('ego', 'car'),
      speed: fc.constantFrom('10', '20', '5.5', '$speed', 'a<b&"c"'),
      distance: fc.boolean(),
    });
    // Each scenario declares $speed, 3 or 4: a group reading it where the values differ reads a copy of its own.
    const scenarioSpec = fc.record({ groups: fc.array(groupSpec, { minLength: 1, maxLength: 4 }), speed: fc.constantFrom('3', '4') });
    const library = fc.array(scenarioSpec, { minLength: 1, maxLength: 4 });
    let extracted = 0;
    await fc.assert(
      fc.asyncProperty(library, async (scenarios) => {
        const inputs = scenarios.map(({ groups, speed }, index) => {
          const body = groups.map((group) => {
            const text = speedGroup(group.name, group.actor, xmlAttributeValue(group.speed), group.trigger);
            return group.distance ? text : text.replace('<TraveledDistanceCondition value="5"/>', '<StandStillCondition duration="1"/>');
          });
          const text = scenario(body.join('')).replace(
            '<Entities>',
            `<ParameterDeclarations>\n    <ParameterDeclaration name="speed" parameterType="double" value="${speed}"/>\n  </ParameterDeclarations>\n  <Entities>`,
          );
          return {
            path: `/virtual/in/${index % 2 ? 'deep/' : ''}s${index}.xosc`,
            output: `/virtual/out/${index % 2 ? 'deep/' : ''}s${index}.xosc`,
            text,
          };
        });
        const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
        extracted += result.behaviours.length;
        // Equivalent and unwarned (parameter-conflict), checked apart from modularize's own check.
        await assertFlattensBack(inputs, result);
      }),
      { numRuns: 40, seed: 19 },
    );
    assert.ok(extracted >= 20, `${extracted} behaviours extracted in 40 libraries`);
  });

  it('names a behaviour after its actions and what starts it', () => {
    const group = parseXml(speedGroup('G', 'car', '1')).root;
    assert.ok(group);
    assert.equal(
      behaviourName([
        group,
        ...group.children.flatMap(function all(element): (typeof group)[] {
          return [element, ...element.children.flatMap(all)];
        }),
      ]),
      'speed_after_traveled_distance',
    );
  });

  it('tells scenarios from catalogs, distributions and modular mains', () => {
    assert.equal(notAPlainScenario(scenario(speedGroup('G', 'car', '1'))), undefined);
    assert.match(notAPlainScenario('<OpenSCENARIO><FileHeader/><Catalog name="x"/></OpenSCENARIO>') ?? '', /catalog/);
    assert.match(notAPlainScenario('<OpenSCENARIO><FileHeader/><ParameterValueDistribution/></OpenSCENARIO>') ?? '', /distribution/);
    assert.match(
      notAPlainScenario(
        '<OpenSCENARIO><Storyboard><ManeuverGroup name="A"><ScenarioReference scenarioFileName="x.xosc"/></ManeuverGroup></Storyboard></OpenSCENARIO>',
      ) ?? '',
      /modular/,
    );
  });
});
