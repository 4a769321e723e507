import * as assert from 'node:assert/strict';
import { modularize, ModularizeResult } from '../../server/src/core/modularize';
import { act, fileHeader, scenarioDocument, scenarioObjects, speedChangeGroup, story } from '../support/fixtures';
import { assertFlattensBack } from '../support/modularizeLibrary';

/** A scenario of `groups` whose catalog locations and parameter declarations are given (each line four spaces in). */
function sourced(groups: string, catalogs: string, parameters = ''): string {
  return scenarioDocument({
    header: fileHeader({ revMinor: '0' }),
    parameters: parameters || undefined,
    catalogLocations: catalogs,
    entities: scenarioObjects(['ego', 'car']),
    storyboard: story('S', act('A', groups, false)),
  });
}

const vehicles = (folder: string) => `    <VehicleCatalog><Directory path="${folder}"/></VehicleCatalog>\n`;
const controllers = `    <ControllerCatalog><Directory path="catalogs/controllers"/></ControllerCatalog>\n`;
/** speedChangeGroup's shape with another start condition: another behaviour, which may bear the same name. */
const standStillGroup = (name: string, actor: string, speed: string) =>
  speedChangeGroup(name, actor, speed).replace('<TraveledDistanceCondition value="5"/>', '<StandStillCondition duration="1"/>');

async function run(texts: string[]): Promise<ModularizeResult> {
  const inputs = texts.map((text, index) => ({ path: `/virtual/in/s${index}.xosc`, output: `/virtual/out/s${index}.xosc`, text }));
  const result = await modularize(inputs, { simpleFolder: '/virtual/out/simple' });
  // Checked again here, independently of modularize's own proof (SPEC 8).
  await assertFlattensBack(inputs, result);
  assert.ok(result.totals.linesAfter <= result.totals.linesBefore);
  return result;
}

const speed = (value: string) => `    <ParameterDeclaration name="Speed" parameterType="double" value="${value}"/>\n`;

const files = (result: ModularizeResult) => [...new Set(result.behaviours.map((behaviour) => behaviour.file))];

describe('core: modularize shares simple scenarios across sources', function () {
  this.timeout(120_000);

  it('groups of scenarios whose catalog locations differ only in kinds one lacks share one file', async () => {
    const texts = [
      sourced(speedChangeGroup('Lead.Go', 'car', '10'), vehicles('catalogs/vehicles')),
      sourced(speedChangeGroup('Follow.Go', 'car', '10'), vehicles('catalogs/vehicles')),
      sourced(standStillGroup('Lead.Wait', 'car', '10'), vehicles('catalogs/vehicles') + controllers),
      sourced(standStillGroup('Follow.Wait', 'car', '10'), vehicles('catalogs/vehicles') + controllers),
    ];
    const result = await run(texts);
    assert.equal(result.behaviours.length, 2);
    assert.equal(files(result).length, 1);
    // The shared file locates both kinds of catalog, each once.
    const [text] = [result.behaviours[0].text];
    assert.equal(text.match(/<VehicleCatalog>/g)?.length, 1);
    assert.equal(text.match(/<ControllerCatalog>/g)?.length, 1);
  });

  it('a same-named group of another shape shares the file under another name', async () => {
    const texts = [
      sourced(speedChangeGroup('Lead.Go', 'car', '10'), vehicles('catalogs/vehicles')),
      sourced(speedChangeGroup('Follow.Go', 'car', '10'), vehicles('catalogs/vehicles')),
      sourced(standStillGroup('Lead.Go', 'car', '10'), vehicles('catalogs/vehicles')),
      sourced(standStillGroup('Follow.Go', 'car', '10'), vehicles('catalogs/vehicles')),
    ];
    const result = await run(texts);
    assert.equal(result.behaviours.length, 2);
    assert.equal(files(result).length, 1);
    const names = result.behaviours.map((behaviour) => behaviour.groupName);
    assert.equal(new Set(names).size, 2, names.join(', '));
    assert.ok(names.includes('Go'), names.join(', '));
  });

  it('never shares a file between catalogs of one kind in different places', async () => {
    // Three uses each, so that each pays for a file of its own.
    const apart = await run([
      ...['Lead', 'Follow', 'Side'].map((outer) => sourced(speedChangeGroup(`${outer}.Go`, 'car', '10'), vehicles('catalogs/vehicles'))),
      ...['Lead', 'Follow', 'Side'].map((outer) => sourced(standStillGroup(`${outer}.Wait`, 'car', '10'), vehicles('other/vehicles'))),
    ]);
    assert.equal(apart.behaviours.length, 2);
    assert.equal(files(apart).length, 2);
  });

  it('groups of scenarios that declare a parameter they read with different values share one file: the group reads its own copy, each main passes its own reading', async () => {
    // Euro NCAP's Ego_speed_kph in small: 10 in the scenarios of one behaviour, 20 in those of the other.
    const conflicting = await run([
      ...['Lead', 'Follow', 'Side'].map((outer) => sourced(speedChangeGroup(`${outer}.Go`, 'car', '$Speed'), '', speed('10'))),
      ...['Lead', 'Follow', 'Side'].map((outer) => sourced(standStillGroup(`${outer}.Wait`, 'car', '$Speed'), '', speed('20'))),
    ]);
    assert.equal(conflicting.behaviours.length, 2);
    assert.equal(files(conflicting).length, 1);
    const [text] = [conflicting.behaviours[0].text];
    // The file declares Speed as the first scenarios do, and the other group's own copy as its scenarios do.
    assert.match(text, /<ParameterDeclaration name="Speed" parameterType="double" value="10"\/>/);
    assert.match(text, /<ParameterDeclaration name="Speed_Wait" parameterType="double" value="20"\/>/);
    assert.match(text, /<AbsoluteTargetSpeed parameterAttributes="value" value="\$Speed_Wait"\/>/);
    const wait = conflicting.behaviours.find((behaviour) => behaviour.groupName === 'Wait');
    assert.deepEqual(wait?.parameters, ['AbsoluteTargetSpeed.value']);
    for (const main of conflicting.mains.slice(3))
      assert.match(main.text, /<ParameterReference key="(AbsoluteTargetSpeed\.)?value" value="\$Speed"\/>/);
    for (const main of conflicting.mains.slice(0, 3)) assert.doesNotMatch(main.text, /<ParameterReference/);
  });

  it('a group used in scenarios that declare a parameter it reads with different values reads its own copy, each use passing its own reading', async () => {
    // Two scenarios, two uses each of one group reading $Speed: 10 in one, 30 in the other.
    const result = await run(
      ['10', '30'].map((value) =>
        sourced(speedChangeGroup('Lead.Go', 'car', '$Speed') + speedChangeGroup('Follow.Go', 'ego', '$Speed'), '', speed(value)),
      ),
    );
    assert.equal(files(result).length, 1);
    const [behaviour] = result.behaviours;
    assert.match(behaviour.text, /<ParameterDeclaration name="Speed_Go" parameterType="double" value="10"\/>/);
    assert.doesNotMatch(behaviour.text, /name="Speed"/);
    for (const main of result.mains)
      assert.equal(main.text.match(/<ParameterReference key="(AbsoluteTargetSpeed\.)?value" value="\$Speed"\/>/g)?.length, 2);
  });
});
