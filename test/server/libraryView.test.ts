import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  LibraryCollisionsRequest,
  LibraryInsertRequest,
  LibraryModulesRequest,
  NewFromTemplateRequest,
  TemplatesRequest,
} from '../../common/src/libraryProtocol';
import { main } from '../../server/src/cli';
import { builtInLibraryFolder } from '../../server/src/libraries';
import { esminiBinary, requireEsmini, runEsmini } from '../support/esmini';
import { checkCleanAndFlatten } from '../support/cliChecks';
import { applyEdits } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

const builtIn = builtInLibraryFolder() ?? '';

/**
 * The library's composition bench with its car renamed (no entity of the main is then named after the cut-in's actor,
 * so Insert into main asks) and its road named by its absolute path: what Insert into main starts from.
 */
function compositionMain(): string {
  const names: Record<string, string> = { adversary: 'Cutter', lead: 'Lead', pedestrian: 'Walker', ego: 'Ego' };
  return fs
    .readFileSync(path.join(builtIn, 'templates', 'composition-bench.xosc'), 'utf8')
    .replace(
      /(<ScenarioObject name|entityRef)="(adversary|lead|pedestrian|ego)"/g,
      (_, attribute: string, name: string) => `${attribute}="${names[name]}"`,
    )
    .replace('filepath="../roads/', `filepath="${builtIn}/roads/`);
}

/** The Scenario Library view's requests (issue 28, item 2): the listing grouped and with its problems, and Insert into main. */
describe('language server: the Scenario Library view and Insert into main (JSON-RPC)', function () {
  this.timeout(180_000);
  let root: string;
  let client: TestClient;

  before(async function () {
    const mine = fs.readFileSync(path.join(builtIn, 'slow-target.xosc'), 'utf8').replace('name: slow-target', 'name: parked-car');
    root = temporaryWorkspace({
      'main.xosc': compositionMain(),
      'mine/parked-car.xosc': mine,
      'mine/broken.xosc': '<?xml version="1.0"?>\n<!-- library module\nname: broken\ntitle: Broken\n-->\n<OpenSCENARIO>',
      'mine/cut-in.xosc': fs.readFileSync(path.join(builtIn, 'cut-in.xosc'), 'utf8'),
    });
    client = await TestClient.start({ root, settings: { library: { folders: ['mine', 'missing'] } } });
    await client.indexed();
  });
  after(() => client?.stop());

  it("lists every built-in module with its doc, keys and picture, the user's folders first, each broken file and missing folder reported", async function () {
    const listing = await client.send(LibraryModulesRequest, {});
    assert.deepEqual(
      listing.libraries.map((library) => library.label),
      ['user', 'user', 'built-in'],
    );
    const builtInNames = fs
      .readdirSync(builtIn)
      .filter((entry) => entry.endsWith('.xosc'))
      .map((entry) => entry.slice(0, -'.xosc'.length));
    const names = listing.modules.map((module) => module.name);
    for (const name of [...builtInNames, 'parked-car']) assert.ok(names.includes(name), `${name} is listed: ${names.join(', ')}`);
    assert.equal(names.filter((name) => name === 'cut-in').length, 1, 'the user cut-in hides the built-in one');
    const cutIn = listing.modules.find((module) => module.name === 'cut-in');
    assert.equal(cutIn?.libraryLabel, 'user');
    assert.deepEqual(cutIn?.hides, [path.join(builtIn, 'cut-in.xosc')]);
    const leadBrake = listing.modules.find((module) => module.name === 'lead-brake');
    assert.ok(leadBrake?.picture && fs.existsSync(leadBrake.picture), 'the picture exists');
    const deceleration = leadBrake.parameters.find((parameter) => parameter.name === 'deceleration');
    assert.equal(deceleration?.unit, 'm/s²');
    assert.match(deceleration?.range ?? '', /\.\./);
    assert.ok(deceleration?.defaultValue, 'a default');
    assert.equal(leadBrake.parameters.find((parameter) => parameter.key === 'EntityRef.entityRef')?.entity, true);
    const problems = listing.problems.map((problem) => `${path.relative(root, problem.file)}:${problem.line ?? ''} ${problem.message}`);
    assert.ok(
      problems.some((problem) => /^mine\/broken\.xosc:\d+ .*no 'maneuverGroup/.test(problem)),
      problems.join('\n'),
    );
    assert.ok(
      problems.some((problem) => /^missing: .*does not exist/.test(problem)),
      problems.join('\n'),
    );
  });

  it("Insert into main guesses the one entity of a role's kind that no role names (the main's only Pedestrian plays 'pedestrian'); of two cars, it asks", async function () {
    const file = path.join(root, 'main.xosc');
    const uri = await client.open(fileUri(file), fs.readFileSync(file, 'utf8'));
    const crossing = await client.send(LibraryInsertRequest, { uri, module: 'pedestrian-crossing' });
    assert.deepEqual(
      crossing.roles.map((role) => [role.name, role.guess]),
      [
        ['pedestrian', 'Walker'],
        ['ego', 'Ego'],
      ],
    );
    // Cutter and Lead are both cars that no role names: which one cuts in is the user's to say.
    const cutIn = await client.send(LibraryInsertRequest, { uri, module: 'cut-in' });
    assert.equal(cutIn.roles.find((role) => role.name === 'adversary')?.guess, undefined);
    await client.close(uri);
  });

  it('Insert into main asks for the roles no entity of the main is named after, then writes three modules that check clean and run in esmini', async function () {
    const file = path.join(root, 'main.xosc');
    let text = fs.readFileSync(file, 'utf8');
    const uri = await client.open(fileUri(file), text);
    const questions = await client.send(LibraryInsertRequest, { uri, module: 'cut-in' });
    assert.deepEqual(questions.acts, ['Story/Act']);
    assert.deepEqual(questions.entities, ['Ego', 'Cutter', 'Lead', 'Walker']);
    assert.deepEqual(
      questions.roles.map((role) => [role.name, role.actor, role.guess]),
      [
        ['adversary', true, undefined],
        ['ego', false, 'Ego'],
      ],
    );
    assert.equal(questions.edit, undefined, 'no edit before every role has its entity');

    const inserts: [string, Record<string, string>][] = [
      ['cut-in', { adversary: 'Cutter', ego: 'Ego' }],
      ['lead-brake', { lead: 'Lead', ego: 'Ego' }],
      ['pedestrian-crossing', { pedestrian: 'Walker', ego: 'Ego' }],
      ['cut-in', { adversary: 'Cutter', ego: 'Ego' }],
    ];
    const groupNames: string[] = [];
    for (const [module, players] of inserts) {
      const answer = await client.send(LibraryInsertRequest, { uri, module, players });
      assert.ok(answer.edit?.changes?.[uri], `an edit of the main for ${module}`);
      text = applyEdits(text, answer.edit.changes[uri]);
      await client.close(uri);
      await client.open(uri, text);
      groupNames.push(answer.groupName ?? '');
      assert.match(text.split('\n')[answer.line ?? -1], new RegExp(`<ManeuverGroup name="${answer.groupName}"`));
    }
    assert.deepEqual(groupNames, ['CutIn', 'LeadBrake', 'PedestrianCrossing', 'CutIn2'], 'a name unique in the Act');
    assert.match(text, /<EntityRef entityRef="Cutter"\/>\s*<\/Actors>\s*<ScenarioReference scenarioFileName="library:cut-in">/);
    assert.match(text, /key="RelativeDistanceCondition.entityRef" value="Ego"/);
    assert.match(text, /key="RelativeObjectPosition.entityRef" value="Walker"/);
    // The second cut-in is only there to show the unique name: taken out again, the three modules remain.
    text = text.replace(/\n *<ManeuverGroup name="CutIn2"[\s\S]*?<\/ManeuverGroup>/, '');
    await client.close(uri);
    await client.open(uri, text);
    assert.deepEqual(
      (await client.diagnosticsOf(uri)).map((diagnostic) => diagnostic.message),
      [],
    );
    fs.writeFileSync(file, text);
    const flat = path.join(root, 'flat.xosc');
    await checkCleanAndFlatten(file, flat);

    requireEsmini(this);
    const steps = await runEsmini(flat, 12);
    const last = steps[steps.length - 1];
    assert.ok(last.time > 11, `esmini ran to ${last.time} s`);
    const [egoY, cutterY] = [last.positions.Ego[1], last.positions.Cutter[1]];
    assert.ok(Math.abs(egoY - cutterY) < 0.1, `the cutter ends in the ego's lane (y ${cutterY} against ${egoY})`);
    const walker = steps.map((step) => step.positions.Walker[1]);
    assert.ok(Math.abs(walker[walker.length - 1] - walker[0]) > 1, 'the pedestrian walked');
    // The notice after the insert: none, as the bench places its entities so that no scripted actors touch (before 30
    // November 2026 it named Cutter and Walker at 7.75 s, Cutter and Lead at 10.05 s).
    const collisions = await client.send(LibraryCollisionsRequest, { uri, esminiPath: esminiBinary });
    assert.deepEqual([collisions.ran, collisions.collisions], [true, []], collisions.message);
    await client.close(uri);
  });

  it('Insert into main of traffic-jam-end asks who plays each of its three actors, writes them all, and the whole queue brakes in esmini', async function () {
    const names: Record<string, string> = { ego: 'Me', jam1: 'Q1', jam2: 'Q2', jam3: 'Q3' };
    const file = path.join(root, 'jam.xosc');
    // Its example main with the entities renamed and its group taken out: the Act holds only its StartTrigger.
    let text = fs
      .readFileSync(path.join(builtIn, 'examples', 'traffic-jam-end.xosc'), 'utf8')
      .replace(/\n *<ManeuverGroup name="TrafficJamEnd"[\s\S]*?<\/ManeuverGroup>/, '')
      .replace(
        /(<ScenarioObject name|entityRef)="(ego|jam1|jam2|jam3)"/g,
        (_, attribute: string, name: string) => `${attribute}="${names[name]}"`,
      )
      .replace('filepath="../roads/', `filepath="${builtIn}/roads/`);
    assert.doesNotMatch(text, /TrafficJamEnd"|"jam[123]"/);
    const uri = await client.open(fileUri(file), text);
    const questions = await client.send(LibraryInsertRequest, { uri, module: 'traffic-jam-end' });
    assert.deepEqual(
      questions.roles.map((role) => [role.name, role.actor]),
      [
        ['jam1', true],
        ['ego', false],
        ['jam2', true],
        ['jam3', true],
      ],
    );
    const answer = await client.send(LibraryInsertRequest, { uri, module: 'traffic-jam-end', players: names });
    assert.ok(answer.edit?.changes?.[uri], 'an edit of the main');
    text = applyEdits(text, answer.edit.changes[uri]);
    await client.close(uri);
    await client.open(uri, text);
    assert.deepEqual(
      (await client.diagnosticsOf(uri)).map((diagnostic) => diagnostic.message),
      [],
    );
    await client.close(uri);
    fs.writeFileSync(file, text);
    const errors: string[] = [];
    const flat = path.join(root, 'jam-flat.xosc');
    assert.equal(
      await main(['flatten', file, '-o', flat, '-q'], { out: () => {}, err: (line) => errors.push(line) }),
      0,
      errors.join('\n'),
    );
    assert.match(
      fs.readFileSync(flat, 'utf8'),
      /<EntityRef entityRef="Q1"\/>\s*<EntityRef entityRef="Q2"\/>\s*<EntityRef entityRef="Q3"\/>/,
    );

    requireEsmini(this);
    const steps = await runEsmini(flat, 6.5);
    const speed = (name: string, index: number) =>
      Math.hypot(
        steps[index + 1].positions[name][0] - steps[index].positions[name][0],
        steps[index + 1].positions[name][1] - steps[index].positions[name][1],
      ) /
      (steps[index + 1].time - steps[index].time);
    for (const name of ['Q1', 'Q2', 'Q3']) {
      assert.ok(speed(name, 0) > 9, `${name} drives at first (${speed(name, 0)} m/s)`);
      assert.ok(speed(name, steps.length - 2) < 0.05, `${name} has braked to the jam's speed 0 (${speed(name, steps.length - 2)} m/s)`);
    }
  });

  it('a misspelt module and a main without an Act are refused with a reason', async function () {
    const uri = await client.open(fileUri(path.join(root, 'other.xosc')), '<OpenSCENARIO><Storyboard/></OpenSCENARIO>');
    await assert.rejects(client.send(LibraryInsertRequest, { uri, module: 'cut-inn' }), /did you mean 'cut-in'/);
    await assert.rejects(
      client.send(LibraryInsertRequest, { uri, module: 'cut-in', players: { adversary: 'A', ego: 'B' } }),
      /no Story with an Act/,
    );
    await client.close(uri);
  });

  it('New Scenario from Template: the templates, then the files to write (the road beside, the distribution naming the new file); an existing file refuses', async function () {
    const templates = await client.send(TemplatesRequest, {});
    for (const name of ['ncap-ccrb', 'ncap-cpna', 'alks-cut-in'])
      assert.ok(
        templates.some((template) => template.name === name),
        name,
      );
    const scenario = path.join(root, 'alks.xosc');
    const { files } = await client.send(NewFromTemplateRequest, { template: 'alks-cut-in', scenario: fileUri(scenario) });
    assert.deepEqual(
      files.map((file) => path.relative(root, file.path)),
      ['alks.xosc', 'straight_1000m.xodr', 'alks.distribution.xosc'],
    );
    assert.match(files[0].text, /<LogicFile filepath="straight_1000m.xodr"\/>/);
    assert.match(files[2].text, /<ScenarioFile filepath="alks.xosc"\/>/);
    await assert.rejects(
      client.send(NewFromTemplateRequest, { template: 'alks-cut-in', scenario: fileUri(path.join(root, 'main.xosc')) }),
      /main.xosc exists/,
    );
    await assert.rejects(client.send(NewFromTemplateRequest, { template: 'nope', scenario: fileUri(scenario) }), /no template 'nope'/);
  });
});
