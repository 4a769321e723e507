import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { modularize, ModularizeResult } from '../../server/src/core/modularize';
import { assertFlattensBack, figuresLine, modularizeLibrary, realLibraries } from '../support/modularizeLibrary';
import {
  act,
  catalogFile,
  element,
  EMPTY_INIT,
  fileHeader,
  scenarioDocument,
  scenarioObjects,
  speedChangeGroup,
  speedEvent,
  story,
} from '../support/fixtures';
import { requireCorpus } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

/** A plain OpenSCENARIO 1.2 scenario with entities ego and car; `storyDeclarations` are its Story's ParameterDeclarations (eight spaces in). */
function scenarioWith(parts: { variables?: string; catalogLocations?: string; storyDeclarations?: string; groups: string }): string {
  return scenarioDocument({
    parameters: '',
    variables: parts.variables,
    catalogLocations: parts.catalogLocations ?? '',
    roadNetwork: '',
    entities: scenarioObjects(['ego', 'car']),
    storyboard: EMPTY_INIT + story('S', act('A', parts.groups), parts.storyDeclarations) + '    <StopTrigger/>\n',
  });
}

/**
 * Four scenarios in a temporary lib/ beside `catalog` (lib/Catalogs/ManeuverCatalog.xosc), each a speedChangeGroup holding
 * `reference` and the parts `partsOf` gives it, modularized into out/.
 */
async function modularizeWithCatalog(
  catalog: string,
  reference: string,
  partsOf: (index: number) => Omit<Parameters<typeof scenarioWith>[0], 'groups'>,
): Promise<ModularizeResult> {
  const files: Record<string, string> = { 'lib/Catalogs/ManeuverCatalog.xosc': catalog };
  ['car', 'ego', 'car', 'ego'].forEach((actor, index) => {
    files[`lib/s${index}.xosc`] = scenarioWith({
      ...partsOf(index),
      groups: speedChangeGroup(`G${index}.Go`, actor, String(10 + index), actor, reference),
    });
  });
  const root = temporaryWorkspace(files);
  const inputs = [0, 1, 2, 3].map((index) => ({
    path: path.join(root, 'lib', `s${index}.xosc`),
    output: path.join(root, 'out', `s${index}.xosc`),
    text: files[`lib/s${index}.xosc`],
  }));
  return modularize(inputs, { simpleFolder: path.join(root, 'out', 'simple') });
}

describe('core: modularize on real libraries (issue 28)', function () {
  this.timeout(300_000);

  it('every library on this machine: no larger, every main flattens back equivalent and unwarned, what is left inline said why', async function () {
    requireCorpus(this);
    const { libraries, missing } = realLibraries();
    for (const name of missing) console.log(`      (${name} skipped: absent)`);
    for (const library of libraries) {
      const { figures } = await modularizeLibrary(library);
      console.log(`      ${figuresLine(figures)}`);
      assert.equal(figures.equivalent, figures.scenarios, library.name);
      assert.equal(figures.conflicted, 0, `${library.name}: mains warned of a parameter conflict`);
      assert.ok(figures.linesAfter <= figures.linesBefore, `${library.name}: ${figures.linesBefore} -> ${figures.linesAfter}`);
      for (const kept of figures.keptInline) assert.ok(kept.reason.length > 0, `${kept.group} in ${kept.input}`);
      if (library.name.startsWith("the paper's library")) assert.ok(figures.reduction >= 54.4, `${figures.reduction} %`);
    }
  });

  it('leaves a group inline when its simple scenario would outweigh what its uses save, and says so', async () => {
    // Two uses of a 33-line group: the simple scenario it needs is longer than the 46 lines they would save.
    const inputs = ['car', 'ego'].map((actor, index) => ({
      path: `/virtual/in/s${index}.xosc`,
      output: `/virtual/out/s${index}.xosc`,
      text: scenarioWith({ groups: speedChangeGroup(`G${index}.Go`, actor, '10', actor) }),
    }));
    const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
    assert.equal(result.behaviours.length, 0);
    assert.ok(result.totals.linesAfter <= result.totals.linesBefore);
    assert.equal(result.keptInline.length, 2);
    assert.match(
      result.keptInline[0].reason,
      /would not pay: its simple scenario \(\d+ lines\) outweighs the \d+ lines its 2 uses would save/,
    );
    // Four uses pay for it.
    const four = ['car', 'ego', 'car', 'ego'].map((actor, index) => ({
      path: `/virtual/in/s${index}.xosc`,
      output: `/virtual/out/s${index}.xosc`,
      text: scenarioWith({ groups: speedChangeGroup(`G${index}.Go`, actor, '10', actor) }),
    }));
    const paying = await modularize(four, { simpleFolder: '/virtual/out/simple' });
    assert.equal(paying.behaviours.length, 1);
    assert.ok(paying.totals.linesAfter < paying.totals.linesBefore);
    await assertFlattensBack(four, paying);
  });

  it('accepts a Story that declares name="$owner", the lenient form check and flatten accept', async () => {
    const inputs = ['car', 'ego', 'car', 'ego'].map((owner, index) => ({
      path: `/virtual/in/s${index}.xosc`,
      output: `/virtual/out/s${index}.xosc`,
      text: scenarioWith({
        storyDeclarations: `        <ParameterDeclaration parameterType="string" name="$owner" value="${owner}"/>\n`,
        groups: speedChangeGroup(`G${index}.Go`, '$owner', String(10 + index), '$owner'),
      }),
    }));
    const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
    assert.deepEqual(result.keptInline, []);
    assert.equal(result.behaviours.length, 1);
    // The owner differs between the scenarios: the group reads a copy of its own, declared as the first scenario declares $owner.
    assert.match(result.behaviours[0].text, /<ParameterDeclaration parameterType="string" name="owner_Go" value="car"\/>/);
    await assertFlattensBack(inputs, result);
  });

  it("carries the variables a group's catalog entry uses (a catalog declares none): the extracted group flattens back", async () => {
    // As in Euro NCAP's scenarios: each group references a catalog maneuver that sets a variable of the scenario.
    const catalog = catalogFile(
      'ManeuverCatalog',
      `    <Maneuver name="Flag">
      <Event name="SetFlag" priority="override">
        <Action name="Set">
          <GlobalAction>
            <VariableAction variableRef="done">
              <SetAction value="true"/>
            </VariableAction>
          </GlobalAction>
        </Action>
        <StartTrigger>
          <ConditionGroup>
            <Condition name="Always" delay="0" conditionEdge="none">
              <ByValueCondition>
                <SimulationTimeCondition value="1" rule="greaterThan"/>
              </ByValueCondition>
            </Condition>
          </ConditionGroup>
        </StartTrigger>
      </Event>
    </Maneuver>
`,
      fileHeader({ description: 'maneuvers' }),
    );
    const variables = `    <VariableDeclaration name="done" variableType="boolean" value="false"/>
    <VariableDeclaration name="unused" variableType="double" value="0"/>
`;
    const catalogLocations = element('ManeuverCatalog', '      <Directory path="Catalogs"/>\n', 4);
    const reference = `          <CatalogReference catalogName="ManeuverCatalog" entryName="Flag"/>\n`;
    const result = await modularizeWithCatalog(catalog, reference, () => ({ variables, catalogLocations }));
    assert.deepEqual(result.keptInline, []);
    assert.equal(result.behaviours.length, 1);
    assert.match(result.behaviours[0].text, /<VariableDeclaration name="done" variableType="boolean" value="false"\/>/);
    assert.deepEqual(result.failures, []);
    assert.ok(result.totals.linesAfter < result.totals.linesBefore);
  });

  it("declares no parameter of the scenario for a ParameterAssignment's parameterRef, which names the catalog entry's own", async () => {
    // As in Euro NCAP's CPNA: a ParameterAssignment parameterRef="VRU_initS" while the scenario declares a VRU_initS of its own.
    const catalog = catalogFile(
      'ManeuverCatalog',
      `    <Maneuver name="Wait">
      <ParameterDeclarations>
        <ParameterDeclaration name="Delay" parameterType="double" value="1"/>
      </ParameterDeclarations>
${speedEvent('Slow', '3', '              <StartTrigger><ConditionGroup><Condition name="After" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="$Delay" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>\n')}    </Maneuver>
`,
    );
    const reference = `          <CatalogReference catalogName="ManeuverCatalog" entryName="Wait">
            <ParameterAssignments>
              <ParameterAssignment parameterRef="Delay" value="2"/>
            </ParameterAssignments>
          </CatalogReference>
`;
    const result = await modularizeWithCatalog(catalog, reference, (index) => ({
      catalogLocations: element('ManeuverCatalog', '      <Directory path="Catalogs"/>\n', 4),
      storyDeclarations: `        <ParameterDeclaration name="Delay" parameterType="double" value="${5 + index}"/>\n`,
    }));
    assert.deepEqual(result.keptInline, []);
    assert.equal(result.behaviours.length, 1);
    assert.doesNotMatch(result.behaviours[0].text, /<ParameterDeclaration name="Delay/);
    // modularize's own check: each main flattens back to its input rebased onto out/, unwarned.
    assert.deepEqual(result.failures, []);
  });
});
