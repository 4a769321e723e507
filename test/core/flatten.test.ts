import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { canonicalTree, firstDifference } from '../../server/src/core/equivalence';
import { Flattener, originOf } from '../../server/src/core/flatten';
import { formatProblem } from '../../server/src/core/problems';
import { childRef, diskRef, readPackageBytes, ScenarioStore } from '../../server/src/core/sources';
import { parseXml, isWellFormed } from '../../server/src/core/xml';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { packFolder } from '../../server/src/core/pack';
import { temporaryWorkspace } from '../support/workspace';

async function flattenIn(root: string, main = 'main.xosc', force = false) {
  const store = new ScenarioStore({ root, scenarioPath: [] });
  return new Flattener(store).flatten(diskRef(path.join(root, main)), { force });
}

describe('core: flatten (SPEC 4)', () => {
  it('replaces the outer group by the renamed, overridden copy, at its indentation', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(
        outerGroup('Car1', 'car', [
          {
            file: 'simple.xosc',
            groups: [
              {
                name: 'Go',
                parameters: [
                  ['AbsoluteTargetSpeed.value', '33'],
                  ['entityRef', 'car'],
                ],
              },
            ],
          },
        ]),
      ),
    });
    const result = await flattenIn(root);
    assert.equal(result.problems.filter((p) => p.severity === 'error').length, 0, result.problems.map((p) => formatProblem(p)).join('\n'));
    const text = result.text!;
    assert.match(text, /\n {8}<ManeuverGroup name="Car1\.Go" maximumExecutionCount="1">\n {10}<Actors/);
    assert.match(text, /<AbsoluteTargetSpeed value="33"\/>/);
    assert.match(text, /<EntityRef entityRef="car"\/>\n {14}<\/Condition>/);
    assert.doesNotMatch(text, /parameterAttributes|ScenarioReference/);
    const main = fs.readFileSync(path.join(root, 'main.xosc'), 'utf8');
    assert.equal(
      text.slice(0, main.indexOf('<ManeuverGroup')),
      main.slice(0, main.indexOf('<ManeuverGroup')),
      'text before the group is kept as written',
    );
  });

  it('gives the copy the actor of the outer group', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(outerGroup('Car1', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])),
    });
    const tree = canonicalTree((await flattenIn(root)).text!)!;
    const group = JSON.stringify(tree);
    assert.match(
      group,
      /"name":"Actors","attributes":\{"selectTriggeringEntities":"false"\},"children":\[\{"name":"EntityRef","attributes":\{"entityRef":"ego"\}/,
    );
  });

  it('imports both ScenarioReferences of one group, in document order', async () => {
    const root = temporaryWorkspace({
      'a.xosc': scenario(simpleGroup('A')),
      'b.xosc': scenario(simpleGroup('B')),
      'main.xosc': scenario(
        outerGroup('Car', 'car', [
          { file: 'a.xosc', groups: [{ name: 'A' }] },
          { file: 'b.xosc', groups: [{ name: 'B' }] },
        ]),
      ),
    });
    const text = (await flattenIn(root)).text!;
    assert.ok(text.indexOf('name="Car.A"') > 0 && text.indexOf('name="Car.A"') < text.indexOf('name="Car.B"'));
  });

  it('flattens nested packages: dotted names, and the outermost value wins', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'inner/main.xosc': scenario(
        outerGroup('Inner', 'car', [
          {
            file: 'simple.xosc',
            groups: [
              {
                name: 'Go',
                parameters: [
                  ['AbsoluteTargetSpeed.value', '20'],
                  ['WorldPosition.x', '5'],
                ],
              },
            ],
          },
        ]),
      ),
      'main.xosc': scenario(
        outerGroup('Outer', 'ego', [
          { file: 'inner.mosc', groups: [{ name: 'Inner.Go', parameters: [['AbsoluteTargetSpeed.value', '30']] }] },
        ]),
      ),
    });
    const unpacked = await flattenIn(root);
    const text = unpacked.text!;
    assert.match(text, /name="Outer\.Inner\.Go"/);
    assert.match(text, /<AbsoluteTargetSpeed value="30"\/>/, 'outer wins');
    assert.match(text, /<WorldPosition x="5" y="2" z="0"\/>/, 'inner override kept');

    const packed = await packFolder(root, new ScenarioStore({ root, scenarioPath: [] }));
    assert.deepEqual(packed.entries, ['main.xosc', 'inner.mosc'], 'simple.xosc is used by the nested package only, so it goes there');
    const nested = await readPackageBytes((await readPackageBytes(packed.bytes!, 'all.mosc')).entries.get('inner.mosc')!, 'inner.mosc');
    assert.deepEqual([...nested.entries.keys()], ['main.xosc', 'simple.xosc']);
    fs.writeFileSync(path.join(root, 'all.mosc'), packed.bytes!);
    const store = new ScenarioStore({ root: '/nonexistent', scenarioPath: [] });
    const fromPackage = await new Flattener(store).flatten(childRef(diskRef(path.join(root, 'all.mosc')), 'main.xosc'));
    assert.equal(firstDifference(fromPackage.text!, text), undefined);
  });

  it('maps an element of a flattened package back to the file that wrote it', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'inner/main.xosc': scenario(outerGroup('Inner', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])),
      'main.xosc': scenario(outerGroup('Outer', 'ego', [{ file: 'inner.mosc', groups: [{ name: 'Inner.Go' }] }])),
    });
    const store = new ScenarioStore({ root, scenarioPath: [] });
    const flattener = new Flattener(store);
    const inner = flattener.rendered(await flattener.source(diskRef(path.join(root, 'inner/main.xosc')), []));
    const copied = inner.model!.groups.find((g) => g.name === 'Inner.Go')!;
    const speed = [...copied.element.children[1].children[0].children[0].children[0].children].find(
      (e) => e.name === 'AbsoluteTargetSpeed',
    )!;
    const origin = originOf(inner, speed);
    assert.equal(origin.source.ref.disk, path.join(root, 'simple.xosc'));
    assert.equal(origin.element.name, 'AbsoluteTargetSpeed');
    const simpleText = fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8');
    assert.equal(simpleText.slice(origin.element.start, origin.element.start + 20), '<AbsoluteTargetSpeed');
  });

  it('escapes override values so that the output stays well-formed', async () => {
    const value = `a<b & "c" 'd' > é 中`;
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(
        outerGroup('Car', 'car', [
          {
            file: 'simple.xosc',
            groups: [
              {
                name: 'Go',
                parameters: [['value', value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;')]],
              },
            ],
          },
        ]),
      ),
    });
    const text = (await flattenIn(root)).text!;
    assert.ok(isWellFormed(parseXml(text)));
    assert.match(
      JSON.stringify(canonicalTree(text)),
      new RegExp(
        JSON.stringify(value)
          .slice(1, -1)
          .replace(/[.*+?^${}()|[\]\\]/g, '\\$&'),
      ),
    );
  });

  it('keeps CRLF line ends of the main file and the inserted group', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])).replace(/\n/g, '\r\n'),
    });
    const text = (await flattenIn(root)).text!;
    assert.equal(text.split('\r\n').length, text.split('\n').length);
  });

  it('changes one line of output when one value changes', async () => {
    const files = (value: string) => ({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(
        outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['WorldPosition.x', value]] }] }]),
      ),
    });
    const before = (await flattenIn(temporaryWorkspace(files('7')))).text!.split('\n');
    const after = (await flattenIn(temporaryWorkspace(files('8')))).text!.split('\n');
    assert.equal(before.length, after.length);
    assert.deepEqual(
      before.map((line, i) => (line === after[i] ? 0 : 1)).reduce((a: number, b: number) => a + b, 0),
      1,
    );
  });

  it('finds every problem in one run', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(
        outerGroup('A', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Gone' }] }]) +
          outerGroup('B', 'car', [{ file: 'missing.xosc', groups: [{ name: 'Go' }] }]) +
          outerGroup('C', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['nope', '1']] }] }]) +
          outerGroup('D', undefined, [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }]),
      ),
    });
    const result = await flattenIn(root);
    assert.equal(result.text, undefined);
    const codes = result.problems
      .filter((p) => p.severity === 'error')
      .map((p) => p.code)
      .sort();
    assert.deepEqual(codes, ['missing-file', 'no-entity-ref', 'unknown-group', 'unknown-key']);
  });

  it('reports a cycle between plain scenario files with the whole cycle', async () => {
    const root = temporaryWorkspace({
      'main.xosc': scenario(outerGroup('M', 'car', [{ file: 'a.xosc', groups: [{ name: 'X' }] }])),
      'a.xosc': scenario(outerGroup('X', 'car', [{ file: 'b.xosc', groups: [{ name: 'Y' }] }])),
      'b.xosc': scenario(outerGroup('Y', 'car', [{ file: 'a.xosc', groups: [{ name: 'X' }] }])),
    });
    const result = await flattenIn(root);
    const cycle = result.problems.find((p) => p.code === 'cycle');
    assert.ok(cycle);
    assert.match(cycle.message, /a\.xosc -> .*b\.xosc -> .*a\.xosc/);
  });

  it('reports an error where an imported group uses an entity that the main file does not declare (esmini stops at it: SPEC 12)', async () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }]), ['car']),
    });
    const result = await flattenIn(root);
    const problem = result.problems.find((p) => p.code === 'undeclared-entity');
    assert.ok(problem);
    assert.equal(problem.severity, 'error');
    assert.match(problem.message, /'ego'/);
    assert.equal(result.text, undefined, 'an error stops the output');
    assert.notEqual((await flattenIn(root, 'main.xosc', true)).text, undefined, '--force writes it');
  });
});
