import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { firstDifference } from '../../server/src/core/equivalence';
import { carriedDeclaration, composedValues } from '../../server/src/core/flatten/carry';
import { Flattener } from '../../server/src/core/flatten';
import { Problem } from '../../server/src/core/problems';
import { semanticModelOf } from '../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { descendants as descendantsOf, parseXml } from '../../server/src/core/xml';
import { requireEsmini, runEsmini } from '../support/esmini';
import { runCli } from '../support/fixtures';
import { repoRoot } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

/** The composed fixture: main.xosc imports Accelerate from speed_up.xosc; plain.xosc is what it means, written by hand. */
const fixtureDir = path.join(repoRoot, 'test', 'fixtures', 'semantics');

function fixtureWorkspace(changes: Record<string, (text: string) => string> = {}): string {
  const files: Record<string, string> = {};
  const walk = (directory: string) => {
    for (const entry of fs.readdirSync(directory, { withFileTypes: true })) {
      const full = path.join(directory, entry.name);
      if (entry.isDirectory()) walk(full);
      else files[path.relative(fixtureDir, full)] = fs.readFileSync(full, 'utf8');
    }
  };
  walk(fixtureDir);
  for (const [name, change] of Object.entries(changes)) files[name] = change(files[name]);
  return temporaryWorkspace(files);
}

async function flatten(root: string, outputPath?: string) {
  return new Flattener(new ScenarioStore({ scenarioPath: [], root })).flatten(diskRef(path.join(root, 'main.xosc')), { outputPath });
}

/** The problems about parameters and catalogs: the fixture ships no road file, which every file of it names (`road-file`). */
const codes = (problems: Problem[]) =>
  problems
    .filter((problem) => problem.severity !== 'hint' && problem.code !== 'road-file')
    .map((problem) => `${path.basename(problem.source.disk)}:${problem.range.start.line + 1}:${problem.code}`);

describe('semantics across a flatten (SPEC 11)', function () {
  this.timeout(60_000);

  it('flattens from the CLI to an output where every $name and catalog reference resolves, equal to the plain scenario', async () => {
    const root = fixtureWorkspace();
    const output = path.join(root, 'out.xosc');
    const run = runCli(['flatten', path.join(root, 'main.xosc'), '-o', output], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const text = fs.readFileSync(output, 'utf8');
    // Carried after the main file's own declaration, in the source's order; BrakeTime is overridden away, Unrelated unused.
    const names = [...text.matchAll(/<ParameterDeclaration name="(\w+)"/g)].map((match) => match[1]);
    assert.deepEqual(names, ['owner', 'TargetSpeed', 'SlowFactor']);
    assert.match(text, /<ManeuverCatalog>\s*<Directory path="catalogs\/Maneuvers"\/>\s*<\/ManeuverCatalog>/);
    const plain = fs.readFileSync(path.join(root, 'plain.xosc'), 'utf8');
    const described = (xml: string) => xml.replace(/description="[^"]*"/, 'description=""');
    assert.equal(firstDifference(described(text), described(plain)), undefined);
    // The output read as a plain scenario: nothing undeclared, every catalog entry found; the fixture ships no road file.
    const check = runCli(['check', output, '--format', 'json'], { cwd: root });
    const report = JSON.parse(check.stdout) as { errors: number; warnings: number; problems: { code: string }[] };
    assert.deepEqual(
      report.problems.map((problem) => problem.code),
      ['road-file'],
      check.stdout,
    );
    assert.equal(report.errors, 0, check.stdout);
    const model = semanticModelOf(parseXml(text));
    assert.ok(model.uses.length >= 4 && model.uses.every((use) => use.declaration), 'every $name resolves');
  });

  it('writes carried catalog directories relative to the output', async () => {
    const root = fixtureWorkspace();
    const result = await flatten(root, path.join(root, 'out', 'deeper', 'result.xosc'));
    assert.ok(result.text, codes(result.problems).join('\n'));
    assert.match(result.text, /<Directory path="\.\.\/\.\.\/catalogs\/Maneuvers"\/>/);
  });

  it('carries nothing when the main file declares what the group needs, and warns naming both places when values differ', async () => {
    const same = await flatten(
      fixtureWorkspace({
        'main.xosc': (text) =>
          text.replace(
            '<ParameterDeclaration name="owner"',
            '<ParameterDeclaration name="TargetSpeed" parameterType="double" value="20"/>\n    <ParameterDeclaration name="owner"',
          ),
      }),
    );
    assert.deepEqual([...(same.text ?? '').matchAll(/name="TargetSpeed"/g)].length, 1);
    assert.deepEqual(codes(same.problems), []);
    const other = await flatten(
      fixtureWorkspace({
        'main.xosc': (text) =>
          text.replace(
            '<ParameterDeclaration name="owner"',
            '<ParameterDeclaration name="TargetSpeed" parameterType="double" value="30"/>\n    <ParameterDeclaration name="owner"',
          ),
      }),
    );
    assert.ok(other.text);
    assert.deepEqual([...other.text.matchAll(/name="TargetSpeed"/g)].length, 1);
    assert.match(other.text, /name="TargetSpeed" parameterType="double" value="30"/);
    const conflict = other.problems.find((problem) => problem.code === 'parameter-conflict');
    assert.ok(conflict, codes(other.problems).join('\n'));
    assert.equal(path.basename(conflict.source.disk), 'main.xosc');
    assert.equal(conflict.range.start.line, 4, 'at the main file declaration');
    assert.equal(path.basename(conflict.related?.[0].source.disk ?? ''), 'speed_up.xosc');
    assert.equal(conflict.related?.[0].range.start.line, 4, 'and at the source declaration');
  });

  it("never declares a name twice: a carried value using a parameter the main file declares reads the main file's", async () => {
    const root = fixtureWorkspace({
      'speed_up.xosc': (text) =>
        text.replace(
          'name="SlowFactor" parameterType="double" value="0.5"',
          'name="SlowFactor" parameterType="double" value="${$TargetSpeed / 40}"',
        ),
      'main.xosc': (text) =>
        text.replace(
          '<ParameterDeclaration name="owner"',
          '<ParameterDeclaration name="TargetSpeed" parameterType="double" value="30"/>\n    <ParameterDeclaration name="owner"',
        ),
    });
    const result = await flatten(root);
    assert.ok(result.text, codes(result.problems).join('\n'));
    const names = [...result.text.matchAll(/<ParameterDeclaration name="(\w+)"/g)].map((match) => match[1]);
    assert.deepEqual(names, ['TargetSpeed', 'owner', 'SlowFactor']);
    assert.deepEqual(codes(result.problems), ['main.xosc:5:parameter-conflict']);
  });

  it('carries through a nested package: what the package carried into its output is carried again', async () => {
    const inner = fixtureWorkspace();
    const files: Record<string, string> = {};
    for (const name of ['main.xosc', 'speed_up.xosc', 'catalogs/Vehicles/VehicleCatalog.xosc', 'catalogs/Maneuvers/ManeuverCatalog.xosc']) {
      files[`inner/${name}`] = fs.readFileSync(path.join(inner, name), 'utf8');
    }
    files['catalogs/Vehicles/VehicleCatalog.xosc'] = files['inner/catalogs/Vehicles/VehicleCatalog.xosc'];
    files['main.xosc'] = files['inner/main.xosc']
      .replace('scenarioFileName="speed_up.xosc"', 'scenarioFileName="inner.mosc"')
      .replace('maneuverGroupName="Accelerate"', 'maneuverGroupName="Drive.Accelerate"')
      .replace('<ParameterReference key="SimulationTimeCondition.value" value="6"/>', '');
    const root = temporaryWorkspace(files);
    const result = await flatten(root);
    assert.ok(result.text, codes(result.problems).join('\n'));
    const names = [...result.text.matchAll(/<ParameterDeclaration name="(\w+)"/g)].map((match) => match[1]);
    assert.deepEqual(names, ['owner', 'TargetSpeed', 'SlowFactor']);
    assert.match(result.text, /<Directory path="inner\/catalogs\/Maneuvers"\/>/);
    assert.match(result.text, /name="Drive.Drive.Accelerate"/);
    assert.match(result.text, /<SimulationTimeCondition value="6"/, "the package main file's override is kept");
    assert.deepEqual(codes(result.problems), []);
  });

  it('reports a reference to a group that flattening renamed at its source position, as an error', async () => {
    const condition = (ref: string) =>
      `<Condition name="AfterAccelerate" delay="0" conditionEdge="none"><ByValueCondition><StoryboardElementStateCondition storyboardElementType="maneuverGroup" storyboardElementRef="${ref}" state="completeState"/></ByValueCondition></Condition>`;
    const root = fixtureWorkspace({
      'main.xosc': (text) =>
        text.replace(
          '<Condition name="End"',
          `${condition('Drive')}\n        </ConditionGroup>\n        <ConditionGroup>\n        <Condition name="End"`,
        ),
    });
    const result = await flatten(root);
    assert.equal(result.text, undefined, codes(result.problems).join('\n'));
    const renamed = result.problems.find((problem) => problem.code === 'renamed-reference');
    assert.ok(renamed, codes(result.problems).join('\n'));
    assert.equal(path.basename(renamed.source.disk), 'main.xosc');
    const line = fs.readFileSync(path.join(root, 'main.xosc'), 'utf8').split('\n')[renamed.range.start.line];
    assert.equal(line.slice(renamed.range.start.character, renamed.range.end.character), 'Drive');
    assert.match(renamed.message, /'Drive.Accelerate'/);
  });

  it('reports an undeclared parameter of an imported group in its source, and writes nothing', async () => {
    const root = fixtureWorkspace({
      'speed_up.xosc': (text) =>
        text.replace('<SpeedActionDynamics dynamicsShape="linear" value="2"', '<SpeedActionDynamics dynamicsShape="linear" value="$Ghost"'),
    });
    const result = await flatten(root);
    assert.equal(result.text, undefined);
    const undeclared = result.problems.find((problem) => problem.code === 'undeclared-parameter');
    assert.ok(undeclared);
    assert.equal(path.basename(undeclared.source.disk), 'speed_up.xosc');
    const line = fs.readFileSync(path.join(root, 'speed_up.xosc'), 'utf8').split('\n')[undeclared.range.start.line];
    assert.equal(line.slice(undeclared.range.start.character, undeclared.range.end.character), '$Ghost');
  });

  it('reads entityRef="$owner" through its parameter: no warning', async () => {
    const root = fixtureWorkspace();
    const analysis = await new Flattener(new ScenarioStore({ scenarioPath: [], root })).analyze(diskRef(path.join(root, 'main.xosc')));
    assert.deepEqual(codes(analysis.problems), []);
    const wrong = fixtureWorkspace({
      'main.xosc': (text) =>
        text.replace('name="owner" parameterType="string" value="Ego"', 'name="owner" parameterType="string" value="Egg"'),
    });
    const wrongAnalysis = await new Flattener(new ScenarioStore({ scenarioPath: [], root: wrong })).analyze(
      diskRef(path.join(wrong, 'main.xosc')),
    );
    assert.ok(
      wrongAnalysis.problems.some((problem) => problem.code === 'undeclared-entity' && /'Egg'/.test(problem.message)),
      codes(wrongAnalysis.problems).join('\n'),
    );
  });

  it('warns where a key sets attributes whose defaults differ, listing them', async () => {
    const root = fixtureWorkspace({
      'speed_up.xosc': (text) =>
        text.replace(
          '<SpeedActionDynamics dynamicsShape="linear" value="2"',
          '<SpeedActionDynamics parameterAttributes="value" dynamicsShape="linear" value="2"',
        ),
      'main.xosc': (text) =>
        text.replace(
          '<ParameterReference key="SimulationTimeCondition.value" value="6"/>',
          '<ParameterReference key="SimulationTimeCondition.value" value="6"/>\n              <ParameterReference key="value" value="3"/>',
        ),
    });
    const result = await flatten(root);
    const mixed = result.problems.find((problem) => problem.code === 'key-mixed-defaults');
    assert.ok(mixed, codes(result.problems).join('\n'));
    assert.match(mixed.message, /'value' sets 2 attributes whose defaults differ: '2' \(1×\), '\$BrakeTime' \(1×\)/);
    assert.equal(mixed.related?.length, 2);
  });

  it('tells where a value of an imported group comes from: an override, or a declaration carried from its source', async () => {
    const root = fixtureWorkspace();
    const flattener = new Flattener(new ScenarioStore({ scenarioPath: [], root }));
    const main = (await flattener.analyze(diskRef(path.join(root, 'main.xosc')))).source;
    const source = main.links[0].source!;
    const elements = source.original!.groups[0].element;
    const find = (name: string) => [elements, ...descendantsOf(elements)].find((element) => element.name === name)!;
    const [overridden] = composedValues(main, find('SimulationTimeCondition'), 'value');
    assert.equal(overridden.result.provenance.kind, 'override');
    assert.ok(overridden.result.ok && overridden.result.value === '6');
    const [carried] = composedValues(main, find('ParameterAssignment'), 'value');
    assert.ok(carried.result.ok && carried.result.value === 20);
    assert.ok(carried.result.provenance.kind === 'carried' && carried.result.provenance.declaration.name === 'TargetSpeed');
    assert.match(carried.result.provenance.from, /speed_up\.xosc$/);
    await flattener.flatten(diskRef(path.join(root, 'main.xosc')));
    assert.equal(path.basename(carriedDeclaration(main, 'SlowFactor')?.source.ref.disk ?? ''), 'speed_up.xosc');
    assert.equal(carriedDeclaration(main, 'BrakeTime'), undefined);
  });

  it('runs in esmini exactly like the plain scenario it was composed from', async function () {
    requireEsmini(this);
    const root = fixtureWorkspace();
    const run = runCli(['flatten', path.join(root, 'main.xosc'), '-o', path.join(root, 'flattened.xosc')], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const flattened = await runEsmini(path.join(root, 'flattened.xosc'), 12);
    const plain = await runEsmini(path.join(root, 'plain.xosc'), 12);
    assert.ok(flattened.length >= 200, `${flattened.length} steps`);
    assert.equal(flattened.length, plain.length);
    assert.deepEqual(flattened, plain);
    // The carried parameters took effect: the catalog maneuver reached $TargetSpeed (20 m/s), then the group slowed down.
    const x = flattened.map((step) => step.positions.Ego[0]);
    assert.ok(x[x.length - 1] - x[0] > 100, `Ego moved ${x[x.length - 1] - x[0]} m`);
  });
});
