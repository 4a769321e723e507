import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { LibraryModule, readModule } from '../../server/src/core/library';
import { insertModuleGroup, mainShape, moduleRoles, scriptedActors } from '../../server/src/core/libraryInsert';
import { parseXml } from '../../server/src/core/xml';
import { repoRoot } from '../support/paths';

const library = { folder: path.join(repoRoot, 'library'), label: 'built-in' };

function builtInModule(name: string): LibraryModule {
  const file = path.join(library.folder, `${name}.xosc`);
  const { module, problems } = readModule(fs.readFileSync(file, 'utf8'), file, library);
  assert.deepEqual(problems, []);
  assert.ok(module);
  return module;
}

/** A main with entities Me, Q1, Q2, Q3 and one Act closed by `closing`, holding `inside`. */
const mainWith = (inside: string, closing: string) => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <Entities>
    <ScenarioObject name="Me"/>
    <ScenarioObject name="Q1"/>
    <ScenarioObject name="Q2"/>
    <ScenarioObject name="Q3"/>
  </Entities>
  <Storyboard>
    <Story name="Story">
      <Act name="Act">${inside}${closing}
    </Story>
  </Storyboard>
</OpenSCENARIO>
`;

function inserted(text: string, module: LibraryModule, players: Record<string, string>): string {
  const group = insertModuleGroup(text, module, { players });
  return text.slice(0, group.offset) + group.text + text.slice(group.offset);
}

describe('Insert into main (core/libraryInsert)', () => {
  it('writes the group inside an Act whose end tag holds whitespace (</Act >, </Act then > on the next line)', () => {
    const module = builtInModule('lead-brake');
    for (const [inside, closing] of [
      ['', '</Act >'],
      ['\n      ', '</Act\n      >'],
      ['\n', '</Act\t>'],
    ]) {
      const text = mainWith(inside, closing);
      const result = inserted(text, module, { lead: 'Q1', ego: 'Me' });
      const document = parseXml(result);
      assert.deepEqual(
        document.problems.map((problem) => problem.message),
        [],
        `well-formed after inserting before ${JSON.stringify(closing)}:\n${result}`,
      );
      assert.deepEqual(mainShape(result).acts[0].groups, ['LeadBrake'], `the group is inside the Act:\n${result}`);
      assert.ok(result.includes(closing), 'the end tag is kept as written');
    }
  });

  it("traffic-jam-end: every actor of the module's queue is a role, written in Actors and set by its key", () => {
    const module = builtInModule('traffic-jam-end');
    assert.deepEqual(module.actors, ['jam1', 'jam2', 'jam3']);
    assert.deepEqual(
      moduleRoles(module).map((role) => [role.name, role.actor]),
      [
        ['jam1', true],
        ['ego', false],
        ['jam2', true],
        ['jam3', true],
      ],
    );
    const result = inserted(mainWith('\n      ', '</Act>'), module, { jam1: 'Q1', jam2: 'Q2', jam3: 'Q3', ego: 'Me' });
    assert.match(
      result,
      /<Actors selectTriggeringEntities="false">\s*<EntityRef entityRef="Q1"\/>\s*<EntityRef entityRef="Q2"\/>\s*<EntityRef entityRef="Q3"\/>\s*<\/Actors>/,
    );
    assert.match(result, /key="Actors.EntityRef\[2\].entityRef" value="Q2"/);
    assert.match(result, /key="Actors.EntityRef\[3\].entityRef" value="Q3"/);
    assert.match(result, /key="TimeHeadwayCondition.entityRef" value="Q1"/);
    assert.match(result, /key="TriggeringEntities.EntityRef.entityRef" value="Me"/);
  });

  it('a module with one actor writes that one', () => {
    const module = builtInModule('cut-in');
    assert.deepEqual(module.actors, ['adversary']);
    const result = inserted(mainWith('\n      ', '</Act>'), module, { adversary: 'Q1', ego: 'Me' });
    assert.match(result, /<Actors selectTriggeringEntities="false">\s*<EntityRef entityRef="Q1"\/>\s*<\/Actors>/);
  });
  it("the main's scripted actors: its groups' actors, but for the ego a library group names without acting in it", () => {
    const group = (name: string, actor: string, keys: Record<string, string>, file = 'library:cut-in') =>
      `<ManeuverGroup name="${name}" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="${actor}"/></Actors><ScenarioReference scenarioFileName="${file}"><ManeuverGroupReference maneuverGroupName="G">${Object.entries(
        keys,
      )
        .map(([key, value]) => `<ParameterReference key="${key}" value="${value}"/>`)
        .join('')}</ManeuverGroupReference></ScenarioReference></ManeuverGroup>`;
    const text = `<OpenSCENARIO><Entities/><Storyboard><Story name="S"><Act name="A">${[
      group('CutIn', 'adversary', { 'RelativeDistanceCondition.entityRef': 'Ego', 'EntityRef.entityRef': 'adversary' }),
      group('LeadBrake', 'lead', { 'EntityRef.entityRef': 'Ego', 'TimeHeadwayCondition.value': '1.5' }, 'library:lead-brake'),
      // The ego's own group (its speed): an actor there, still the driver under test the modules name.
      group('EgoDrive', 'Ego', {}, 'own.xosc'),
      // A group of the user's that names an entity without acting in it: that entity stays scripted.
      group('Follow', 'follower', { 'EntityRef.entityRef': 'adversary' }, 'own.xosc'),
    ].join('')}</Act></Story></Storyboard></OpenSCENARIO>`;
    assert.deepEqual([...scriptedActors(text)].sort(), ['adversary', 'follower', 'lead']);
  });
});
