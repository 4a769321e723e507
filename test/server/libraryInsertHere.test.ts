import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CodeAction, Command } from 'vscode-languageserver/node';
import { INSERT_LIBRARY_MODULE_COMMAND, InsertHereArguments, LibraryInsertRequest } from '../../common/src/libraryProtocol';
import { builtInLibraryFolder } from '../../server/src/libraries';
import { positionAfter } from '../support/cursor';
import { requireEsmini, runEsmini } from '../support/esmini';
import { checkCleanAndFlatten } from '../support/cliChecks';
import { applyEdits } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

const builtIn = builtInLibraryFolder() ?? '';
const TITLE = 'Insert library module here…';

/** The library's composition bench (an ego, a car beside it, a lead car, a pedestrian; one ManeuverGroup), its road by absolute path. */
function bench(): string {
  return fs
    .readFileSync(path.join(builtIn, 'templates', 'composition-bench.xosc'), 'utf8')
    .replace('filepath="../roads/', `filepath="${builtIn}/roads/`);
}

async function actionsAt(client: TestClient, uri: string, text: string, after: string): Promise<CodeAction[]> {
  const position = positionAfter(text, after);
  return client.request<CodeAction[]>('textDocument/codeAction', {
    textDocument: { uri },
    range: { start: position, end: position },
    context: { diagnostics: [] },
  });
}

const insertHere = (actions: CodeAction[]) => actions.find((action) => action.title === TITLE);

/** Issue 28: the light bulb's *Insert library module here…*, which runs the same command and request as *Insert into Main*. */
describe('language server: Insert library module here… (JSON-RPC)', function () {
  this.timeout(180_000);
  let root: string;
  let client: TestClient;

  before(async function () {
    root = temporaryWorkspace({ 'main.xosc': bench() });
    client = await TestClient.start({ root, initializationOptions: { schema: { version: 'off' }, libraryPicker: true } });
    await client.indexed();
  });
  after(() => client?.stop());

  it('is offered on an Act and on its ManeuverGroups, as the command that picks the module, and nowhere else', async function () {
    const text = bench();
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    const onGroup = insertHere(await actionsAt(client, uri, text, '<ManeuverGroup name="Ego'));
    assert.ok(onGroup?.command, 'offered on the ManeuverGroup start tag');
    assert.equal(onGroup.kind, 'refactor.insertLibraryModule');
    const command = onGroup.command as Command;
    assert.equal(command.command, INSERT_LIBRARY_MODULE_COMMAND);
    const [args] = command.arguments as [InsertHereArguments];
    assert.deepEqual(args, { main: uri, position: positionAfter(text, '<ManeuverGroup name="Ego') });
    assert.ok(insertHere(await actionsAt(client, uri, text, '<Act na')), 'offered on the Act start tag');
    assert.ok(insertHere(await actionsAt(client, uri, text, '</ManeuverGroup>\n ')), 'offered between the group and the StartTrigger');
    for (const elsewhere of ['<Condition name="ActS', '<Private entityRef="le', '<EntityRef entityRef="eg', '<Story na'])
      assert.equal(insertHere(await actionsAt(client, uri, text, elsewhere)), undefined, `not offered at ${elsewhere}`);
    await client.close(uri);
  });

  it('is not offered to an editor without the command', async function () {
    const other = await TestClient.start({ root });
    try {
      await other.indexed();
      const text = bench();
      const uri = await other.open(fileUri(path.join(root, 'main.xosc')), text);
      assert.equal(insertHere(await actionsAt(other, uri, text, '<ManeuverGroup name="Ego')), undefined);
    } finally {
      await other.stop();
    }
  });

  it("the command's request at the action's position writes the module's group there, and the main checks clean, flattens and runs", async function () {
    const file = path.join(root, 'main.xosc');
    let text = bench();
    const uri = await client.open(fileUri(file), text);
    // On the Act's start tag: the group goes first, before EgoBehaviour.
    const first = (insertHere(await actionsAt(client, uri, text, '<Act na'))?.command?.arguments ?? [])[0] as InsertHereArguments;
    const questions = await client.send(LibraryInsertRequest, { uri, module: 'lead-brake', position: first.position });
    assert.deepEqual(
      questions.roles.map((role) => [role.name, role.guess]),
      [
        ['lead', 'lead'],
        ['ego', 'ego'],
      ],
    );
    const insert = async (module: string, position: InsertHereArguments['position'], players: Record<string, string>) => {
      const answer = await client.send(LibraryInsertRequest, { uri, module, position, players });
      assert.ok(answer.edit?.changes?.[uri], `an edit of the main for ${module}`);
      text = applyEdits(text, answer.edit.changes[uri]);
      await client.close(uri);
      await client.open(uri, text);
    };
    await insert('lead-brake', first.position, { lead: 'lead', ego: 'ego' });
    assert.ok(text.indexOf('<ManeuverGroup name="LeadBrake"') < text.indexOf('<ManeuverGroup name="EgoBehaviour"'), 'before EgoBehaviour');

    // On EgoBehaviour: after it, so between it and the Act's StartTrigger.
    const second = (insertHere(await actionsAt(client, uri, text, '<ManeuverGroup name="Ego'))?.command?.arguments ??
      [])[0] as InsertHereArguments;
    await insert('cut-in', second.position, { adversary: 'adversary', ego: 'ego' });
    const order = ['LeadBrake', 'EgoBehaviour', 'CutIn'].map((name) => text.indexOf(`<ManeuverGroup name="${name}"`));
    assert.ok(
      order.every((at, index) => at > 0 && (index === 0 || at > order[index - 1])),
      `groups in order: ${order.join(', ')}`,
    );
    assert.ok(
      text.indexOf('<ManeuverGroup name="CutIn"') <
        text.indexOf('<StartTrigger>\n          <ConditionGroup>\n            <Condition name="ActStart"'),
    );
    assert.match(text, /<ParameterReference key="SpeedActionDynamics.value" value="[^"]+"\/>/, 'the keys at their defaults');
    // The lead starts 100 m (5 s) ahead at the ego's speed: its braking starts below a headway of 6 s, at once.
    assert.match(text, /key="TimeHeadwayCondition.value" value="[^"]+"/);
    text = text.replace(/(key="TimeHeadwayCondition.value" value=")[^"]+"/, '$16"');
    await client.close(uri);
    await client.open(uri, text);
    assert.deepEqual(
      (await client.diagnosticsOf(uri)).map((diagnostic) => diagnostic.message),
      [],
    );

    fs.writeFileSync(file, text);
    const flatText = await checkCleanAndFlatten(file, path.join(root, 'flat.xosc'));
    assert.doesNotMatch(flatText, /ScenarioReference|parameterAttributes/);
    assert.match(flatText, /<ManeuverGroup[^>]*name="LeadBrake.LeadBrake"/);
    assert.match(flatText, /<ManeuverGroup[^>]*name="CutIn.CutIn"/);

    requireEsmini(this);
    const steps = await runEsmini(path.join(root, 'flat.xosc'), 12);
    const last = steps[steps.length - 1];
    assert.ok(last.time > 11, `esmini ran to ${last.time} s`);
    assert.ok(Math.abs(last.positions.ego[1] - last.positions.adversary[1]) < 0.1, 'the adversary cut into the ego lane');
    // The lead, at 20 m/s from 100 m ahead, brakes: it covers well under 12 s x 20 m/s.
    const leadTravel = last.positions.lead[0] - steps[0].positions.lead[0];
    assert.ok(leadTravel < 200, `the lead braked (travelled ${leadTravel.toFixed(1)} m)`);
  });

  it('at a position (a drop), a role no entity is named after has no guess, and the answer binds the entity chosen for it', async function () {
    // The drop's first request: what the client asks in its quick pick (test/e2e libraryDropAsks drives the pick itself).
    const text = bench().replace(/"lead"/g, '"frontCar"');
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    const position = positionAfter(text, '<ManeuverGroup name="Ego');
    const questions = await client.send(LibraryInsertRequest, { uri, module: 'lead-brake', position });
    assert.deepEqual(
      questions.roles.map((role) => [role.name, role.guess]),
      [
        ['lead', undefined],
        ['ego', 'ego'],
      ],
    );
    assert.ok(questions.entities.includes('frontCar'));
    assert.equal(questions.edit, undefined, 'no edit before every role has its entity');
    const answer = await client.send(LibraryInsertRequest, {
      uri,
      module: 'lead-brake',
      position,
      players: { lead: 'frontCar', ego: 'ego' },
    });
    assert.ok(answer.edit?.changes?.[uri], 'an edit of the main');
    const written = applyEdits(text, answer.edit.changes[uri]);
    const group = /<ManeuverGroup name="LeadBrake"[\s\S]*?<\/ManeuverGroup>/.exec(written)?.[0] ?? '';
    assert.match(group, /<Actors selectTriggeringEntities="false">\s*<EntityRef entityRef="frontCar"\/>/);
    assert.match(group, /key="TimeHeadwayCondition.entityRef" value="frontCar"/);
    assert.match(group, /key="EntityRef.entityRef" value="ego"/);
    await client.close(uri);
  });

  it('refuses a position that is no longer on an Act, saying so', async function () {
    const text = bench();
    const uri = await client.open(fileUri(path.join(root, 'main.xosc')), text);
    await assert.rejects(
      client.send(LibraryInsertRequest, {
        uri,
        module: 'lead-brake',
        position: positionAfter(text, '<Private entityRef="le'),
        players: { lead: 'lead', ego: 'ego' },
      }),
      /lead-brake cannot go into .*not on an Act or on a ManeuverGroup of an Act/,
    );
    // The first request, the questions (a drop from the Scenario Library view asks it too), already says so, with the line.
    const inActors = positionAfter(text, '<EntityRef entityRef="eg');
    await assert.rejects(
      client.send(LibraryInsertRequest, { uri, module: 'lead-brake', position: inActors }),
      new RegExp(`lead-brake cannot go into .* at line ${inActors.line + 1}: that is not on an Act or on a ManeuverGroup of an Act`),
    );
    await assert.rejects(
      client.send(LibraryInsertRequest, { uri, module: 'lead-brake', position: { line: -1, character: 'x' } as never }),
      /position: \{ line, character \}/,
    );
    await client.close(uri);
  });
});
