import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { LibraryCollisionsRequest, LibraryInsertRequest, LibraryInsertResult } from '../../common/src/libraryProtocol';
import { LibraryModule, readModule } from '../../server/src/core/library';
import { newMainScenario } from '../../server/src/core/newScenario';
import { builtInLibraryFolder } from '../../server/src/libraries';
import { checkCleanAndFlatten } from '../support/cliChecks';
import { repoRoot } from '../support/paths';
import { esminiBinary, esminiCollisions, requireEsmini, runEsmini, tracksOf } from '../support/esmini';
import { BEHAVIOURS } from '../support/libraryBehaviours';
import { applyEdits } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

const builtIn = builtInLibraryFolder() ?? '';

/** What New Modular Scenario… writes on the library's straight road: an `Ego` alone, on lane -1 at s 10, at $EgoSpeed (10 m/s). */
function newMain(): string {
  return newMainScenario({
    version: '1.3',
    roadFile: path.join(builtIn, 'roads', 'straight_1000m.xodr'),
    ego: { roadId: '0', laneId: -1, s: 10 },
    now: new Date('2026-11-29T00:00:00Z'),
  });
}

/** The module as the composed main sets it: its keys' defaults replaced by the values the main's group gives them. */
function moduleAsComposed(name: string, composed: string): LibraryModule {
  const file = path.join(builtIn, `${name}.xosc`);
  const { module } = readModule(fs.readFileSync(file, 'utf8'), file, { folder: builtIn, label: 'built-in' });
  assert.ok(module, name);
  const group =
    new RegExp(`<ScenarioReference scenarioFileName="library:${name}">[\\s\\S]*?</ScenarioReference>`).exec(composed)?.[0] ?? '';
  assert.ok(group, `the composed main references library:${name}`);
  const values = new Map([...group.matchAll(/<ParameterReference key="([^"]+)" value="([^"]*)"\/>/g)].map((match) => [match[1], match[2]]));
  return {
    ...module,
    parameters: module.parameters.map((parameter) => ({ ...parameter, defaultValue: values.get(parameter.key) ?? parameter.defaultValue })),
  };
}

const entitiesOf = (text: string) => [...text.matchAll(/<ScenarioObject name="([^"]+)"/g)].map((match) => match[1]);

/** Issue 28: composing from a main New Modular Scenario… wrote, which has only its ego: each module's actor is added as its example main has it. */
describe('language server: Insert into Main adds the entity a role lacks, as the example main has it (JSON-RPC)', function () {
  this.timeout(180_000);
  let root: string;
  let client: TestClient;

  before(async function () {
    root = temporaryWorkspace({ 'main.xosc': newMain() });
    client = await TestClient.start({ root, initializationOptions: { schema: { version: 'off' }, libraryPicker: true } });
    await client.indexed();
  });
  after(() => client?.stop());

  const MODULES = ['cut-in', 'lead-brake', 'pedestrian-crossing'];

  /** The three modules inserted into `text` as the client does it: a guess where there is one, else the new entity offered. */
  async function compose(text: string, order = MODULES): Promise<{ text: string; asked: LibraryInsertResult['roles'][]; uri: string }> {
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    const asked: LibraryInsertResult['roles'][] = [];
    for (const module of order) {
      const questions = await client.send(LibraryInsertRequest, { uri, module });
      asked.push(questions.roles);
      const players = Object.fromEntries(questions.roles.map((role) => [role.name, role.guess ?? role.newEntity ?? '']));
      const create = questions.roles.filter((role) => !role.guess && role.newEntity).map((role) => role.name);
      const answer = await client.send(LibraryInsertRequest, { uri, module, players, create });
      assert.ok(answer.edit?.changes?.[uri], `an edit of the main for ${module}`);
      text = applyEdits(text, answer.edit.changes[uri]);
      assert.match(text.split('\n')[answer.line ?? -1] ?? '', /<ManeuverGroup name=/, `line ${answer.line} is the new group's first`);
      await client.close(uri);
      await client.open(uri, text);
    }
    assert.deepEqual(
      (await client.diagnosticsOf(uri)).map((diagnostic) => diagnostic.message),
      [],
    );
    await client.close(uri);
    return { text, asked, uri };
  }

  /**
   * The composed main checked clean, run in esmini, and each module's behaviour asserted with the library's own assertions,
   * and no two of its scripted actors (all but the Ego, the system under test, which no driver drives here) touching;
   * `mirrored`: on a road of left-hand traffic, esmini's tracks mirrored back across the road's reference line (y -y) first.
   */
  async function behavesAsItsExamples(
    context: Mocha.Context,
    text: string,
    mirrored = false,
  ): Promise<Map<string, { time: number; x: number; y: number }[]>> {
    const file = path.join(root, 'main.xosc');
    fs.writeFileSync(file, text);
    await checkCleanAndFlatten(file, path.join(root, 'flat.xosc'));
    requireEsmini(context);
    const tracks = tracksOf(await runEsmini(path.join(root, 'flat.xosc'), 14));
    // On this main's values and names (its Ego plays `ego`).
    tracks.set('ego', tracks.get('Ego') ?? []);
    const asserted = new Map(
      [...tracks].map(([name, track]) => [name, mirrored ? track.map((point) => ({ ...point, y: -point.y })) : track]),
    );
    for (const module of MODULES) BEHAVIOURS[module](moduleAsComposed(module, text), asserted, []);
    const collisions = await esminiCollisions(path.join(root, 'flat.xosc'));
    assert.ok(collisions.length > 0, "esmini's collision detection names the Ego's collisions (it ran)");
    assert.deepEqual(
      collisions
        .filter((collision) => !collision.entities.includes('Ego'))
        .map((collision) => `${collision.entities.join(' and ')} at ${collision.time} s`),
      [],
      'scripted actors collide',
    );
    return tracks;
  }

  it('a cut-in, a lead brake and a pedestrian crossing into a main with only an ego: each adds its actor, placed as in its example (the lead behind the cut-in car, no faster); clean, each behaves as in its example in esmini, and no two scripted actors touch', async function () {
    const { text, asked } = await compose(newMain());
    // Ego plays `ego` (its name, case aside); each actor has no entity to play it: none is free (Ego plays the ego, the
    // adversary acts in the cut-in already), so the new one is the only answer and no question is asked.
    assert.deepEqual(
      asked.map((roles) => roles.map((role) => [role.name, role.guess, role.newEntity, role.newEntityOnly])),
      [
        [
          ['adversary', undefined, 'adversary', true],
          ['ego', 'Ego', undefined, undefined],
        ],
        [
          ['lead', undefined, 'lead', true],
          ['ego', 'Ego', undefined, undefined],
        ],
        [
          ['pedestrian', undefined, 'pedestrian', true],
          ['ego', 'Ego', undefined, undefined],
        ],
      ],
    );
    assert.deepEqual(entitiesOf(text), ['Ego', 'adversary', 'lead', 'pedestrian']);
    assert.deepEqual(
      [
        ...text.matchAll(
          /<Private entityRef="([^"]+)">[\s\S]*?<LanePosition roadId="0" laneId="(-?\d+)" s="([\d.]+)"[\s\S]*?<AbsoluteTargetSpeed value="([^"]+)"/g,
        ),
      ].map((match) => match.slice(1)),
      [
        ['Ego', '-1', '10', '$EgoSpeed'],
        // The cut-in's car 35 m ahead in the lane beside, 3 m/s slower than the ego (its example: 20 and 17 m/s).
        ['adversary', '-2', '45', '7'],
        // The lead 34.5 m ahead in the ego's lane (level with the cut-in's car at most), 2 m/s slower than the cut-in's car
        // (its example: 16 and 14 m/s), which enters the lane ahead of it and never into it; 8 m/s (2 slower than the ego)
        // before 29 November 2026, when the cut-in's car cut in onto it (4.45 s) and ran into it braking.
        ['lead', '-1', '44.5', '5'],
        // The pedestrian 80 m ahead on the sidewalk, standing (its example's ego drives at 10 m/s, as this one).
        ['pedestrian', '-4', '90', '0'],
      ],
    );
    assert.match(text, /<Vehicle name="vehicle\.audi\.tt"/, "the example's vehicle, as it writes it");
    assert.match(text, /<Pedestrian name="walker\.pedestrian\.0001"/);
    // The cut-in's speed key moves with its car's Init speed, so that the gap closes as in the example.
    assert.match(
      text,
      /scenarioFileName="library:cut-in">\s*<ManeuverGroupReference maneuverGroupName="CutIn">\s*<ParameterReference key="AbsoluteTargetSpeed.value" value="7"\/>/,
    );
    for (const [name, actor] of [
      ['CutIn', 'adversary'],
      ['LeadBrake', 'lead'],
      ['PedestrianCrossing', 'pedestrian'],
    ])
      assert.match(
        text,
        new RegExp(
          `<ManeuverGroup name="${name}" maximumExecutionCount="1">\\s*<Actors selectTriggeringEntities="false">\\s*<EntityRef entityRef="${actor}"/>`,
        ),
      );
    await behavesAsItsExamples(this, text);
  });

  it('the lead brake inserted before the cut-in: the cut-in moves the lead behind its car, no faster, the places the other order gives; clean, each behaves as in its example, and no two scripted actors touch', async function () {
    const { text } = await compose(newMain(), ['lead-brake', 'cut-in', 'pedestrian-crossing']);
    assert.deepEqual(
      [
        ...text.matchAll(
          /<Private entityRef="([^"]+)">[\s\S]*?<LanePosition roadId="0" laneId="(-?\d+)" s="([\d.]+)"[\s\S]*?<AbsoluteTargetSpeed value="([^"]+)"/g,
        ),
      ].map((match) => match.slice(1)),
      [
        ['Ego', '-1', '10', '$EgoSpeed'],
        // As if alone at first (8 m/s, 2 slower than the ego); the cut-in's car then takes it to 5 m/s, 2 slower than that
        // car (before 30 November 2026 it stayed at 8 m/s, and the cut-in's car cut in onto it at 4.45 s).
        ['lead', '-1', '44.5', '5'],
        ['adversary', '-2', '45', '7'],
        ['pedestrian', '-4', '90', '0'],
      ],
    );
    await behavesAsItsExamples(this, text);
  });

  it('after an insert, the main as the editor has it run in esmini names the scripted actors that touch (not the ego), for the notice; none in the composition, two where the lead drives as if alone', async function () {
    requireEsmini(this);
    const { text } = await compose(newMain());
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    const composed = await client.send(LibraryCollisionsRequest, { uri, esminiPath: esminiBinary });
    assert.deepEqual([composed.ran, composed.collisions], [true, []], composed.message);
    // The lead at 8 m/s, 2 slower than the ego, as placed before 29 November 2026: the cut-in's car cuts in onto it.
    const alone = text.replace(/(<Private entityRef="lead">[\s\S]*?<AbsoluteTargetSpeed value=")5"/, '$18"');
    assert.notEqual(alone, text);
    await client.close(uri);
    await client.open(uri, alone);
    const touching = await client.send(LibraryCollisionsRequest, { uri, esminiPath: esminiBinary });
    assert.deepEqual(touching.collisions, [
      { entities: ['adversary', 'lead'], time: 4.45 },
      { entities: ['adversary', 'lead'], time: 8.6 },
    ]);
    // No esmini: no run, said; nothing thrown (the notice is never shown, the log says why).
    const none = await client.send(LibraryCollisionsRequest, { uri, esminiPath: path.join(root, 'no-esmini') });
    assert.equal(none.ran, false);
    assert.match(none.message, /esmini/);
    await client.close(uri);
    assert.deepEqual(
      fs.readdirSync(root).filter((name) => !['flat.xosc', 'main.xosc'].includes(name)),
      [],
      'the runs leave nothing in the workspace',
    );
  });

  it('a main on a road of left-hand traffic (rule="LHT"): each actor placed as a driver there expects it, mirrored (the cut-in from the left, the pedestrian from the left sidewalk); clean, and each behaves as in its example in esmini, mirrored', async function () {
    // The library's straight road for left-hand traffic: lanes 1..3 driven along s, a sidewalk beyond (lane 4).
    const road = path.join(repoRoot, 'test', 'fixtures', 'library', 'straight_lht_1000m.xodr');
    const onTheLeft = newMain()
      .replace(/filepath="[^"]*"/, `filepath="${road}"`)
      .replace('laneId="-1"', 'laneId="1"');
    const { text } = await compose(onTheLeft);
    assert.deepEqual(
      [
        ...text.matchAll(
          /<Private entityRef="([^"]+)">[\s\S]*?<LanePosition roadId="0" laneId="(-?\d+)" s="([\d.]+)"(?: offset="([^"]+)")?/g,
        ),
      ].map((match) => match.slice(1)),
      [
        ['Ego', '1', '10', '0'],
        // The cut-in's car 35 m ahead in the lane beside the ego's on its left (the slower lane there), where it was on its right.
        ['adversary', '2', '45', '0'],
        ['lead', '1', '44.5', '0'],
        // The pedestrian 80 m ahead on the sidewalk of the ego's side, its left, 0.75 m towards the road, facing the road.
        ['pedestrian', '4', '90', '-0.75'],
      ],
    );
    assert.match(text, /laneId="4" s="90" offset="-0.75">\s*<Orientation type="relative" h="-1.571" p="0" r="0"\/>/);
    const tracks = await behavesAsItsExamples(this, text, true);
    // esmini drives each vehicle along its lane's direction (lanes 1..3 along s there): forwards, left of the reference line.
    for (const name of ['Ego', 'adversary', 'lead']) {
      const track = tracks.get(name) ?? [];
      assert.ok(
        track.length > 10 && track[0].y > 0 && track[0].y < 10.5,
        `${name} starts on a lane of the left side: ${JSON.stringify(track[0])}`,
      );
      assert.ok(track[track.length - 1].x > track[0].x + 10, `${name} drives along s`);
    }
  });

  it('an ego placed by a WorldPosition (as many real scenarios place it): each actor is placed relative to it by a RelativeLanePosition; clean, and each behaves as in its example in esmini', async function () {
    const { text } = await compose(newMain().replace(/<LanePosition [^>]*\/>/, '<WorldPosition x="10" y="-1.75" z="0" h="0"/>'));
    assert.deepEqual(
      [...text.matchAll(/<Private entityRef="([^"]+)">[\s\S]*?<(RelativeLanePosition|WorldPosition) ([^>]*?)\/?>/g)].map((match) =>
        match.slice(1).join(' '),
      ),
      [
        'Ego WorldPosition x="10" y="-1.75" z="0" h="0"',
        'adversary RelativeLanePosition entityRef="Ego" dLane="-1" ds="35" offset="0"',
        'lead RelativeLanePosition entityRef="Ego" dLane="0" ds="34.5" offset="0"',
        'pedestrian RelativeLanePosition entityRef="Ego" dLane="-3" ds="80" offset="0.75"',
      ],
    );
    assert.match(
      text,
      /<RelativeLanePosition entityRef="Ego" dLane="-3" ds="80" offset="0.75">\s*<Orientation type="relative" h="1.5708" p="0" r="0"\/>\s*<\/RelativeLanePosition>/,
    );
    await behavesAsItsExamples(this, text);
  });

  it("an ego named otherwise, whose own group drives it, still plays the module's ego (by its kind); only the actor is new", async function () {
    const text = newMain().replace(/"Ego"/g, '"Hero"');
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    const questions = await client.send(LibraryInsertRequest, { uri, module: 'cut-in' });
    assert.deepEqual(
      questions.roles.map((role) => [role.name, role.guess, role.newEntity, role.newEntityOnly]),
      [
        ['adversary', undefined, 'adversary', true],
        ['ego', 'Hero', undefined, undefined],
      ],
    );
    await client.close(uri);
  });

  it('an answer naming an existing entity as new is refused, saying which name is free; a role that is guessed has no offer', async function () {
    const text = newMain()
      .replace(/"Ego"/g, '"Adversary"')
      .replace(/\$EgoSpeed/, '10');
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    const questions = await client.send(LibraryInsertRequest, { uri, module: 'cut-in' });
    assert.deepEqual(
      questions.roles.map((role) => [role.name, role.guess, role.newEntity]),
      [
        ['adversary', 'Adversary', undefined],
        ['ego', undefined, 'ego'],
      ],
    );
    await assert.rejects(
      client.send(LibraryInsertRequest, { uri, module: 'cut-in', players: { adversary: 'Adversary', ego: 'adversary' }, create: ['ego'] }),
      /cut-in cannot go into .*the main already declares an entity 'adversary': name the new one otherwise \(adversary2\)/,
    );
    await assert.rejects(
      client.send(LibraryInsertRequest, { uri, module: 'cut-in', players: { adversary: 'x', ego: 'Adversary' }, create: ['nobody'] }),
      /create: the names of roles of cut-in \(adversary, ego\)/,
    );
    await client.close(uri);
  });
});
