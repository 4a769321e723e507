import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { formatProblem, Problem } from '../../server/src/core/problems';
import { parameterValueProblems } from '../../server/src/core/semantics/parameterValues';
import { analyzeDocument, CatalogLoader } from '../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { Flattener } from '../../server/src/core/flatten';
import { temporaryWorkspace } from '../support/workspace';
import { corpusFiles, openscenarioDir } from '../support/openscenarioCorpus';
import { corpusDir } from '../support/paths';
import { fileHeader, openScenarioFile } from '../support/fixtures';

/** A scenario valid against the 1.2 schema, `{DECLARATIONS}` at the root and `{POSITION}`/`{COUNT}`/`{RULE}` in its story. */
const TEMPLATE = openScenarioFile(
  `  <ParameterDeclarations>
{DECLARATIONS}
  </ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="Ego"/>
  </Entities>
  <Storyboard>
    <Init>
      <Actions>
        <Private entityRef="Ego">
          <PrivateAction>
            <TeleportAction>
              <Position>
                <LanePosition roadId="0" laneId="-1" offset="0" s="{POSITION}"/>
              </Position>
            </TeleportAction>
          </PrivateAction>
        </Private>
      </Actions>
    </Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup maximumExecutionCount="{COUNT}" name="G">
          <Actors selectTriggeringEntities="false"/>
        </ManeuverGroup>
        <StartTrigger>
          <ConditionGroup>
            <Condition name="C" delay="0" conditionEdge="none">
              <ByValueCondition>
                <SimulationTimeCondition value="1" rule="{RULE}"/>
              </ByValueCondition>
            </Condition>
          </ConditionGroup>
        </StartTrigger>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
`,
  fileHeader({ description: 'types' }),
);

const DECLARATIONS = [
  ['Host', 'string', 'car_white'],
  ['Numeric', 'string', '50'],
  ['Speed', 'double', '12.5'],
  ['Lanes', 'int', '3'],
  ['WholeText', 'string', '5.0'],
  ['Twice', 'string', '2'],
  ['Fast', 'boolean', 'true'],
  ['Greater', 'string', 'greaterThan'],
]
  .map(([name, type, value]) => `    <ParameterDeclaration name="${name}" parameterType="${type}" value="${value}"/>`)
  .join('\n');

function scenarioWith(position: string, count = '1', rule = 'greaterThan'): string {
  return TEMPLATE.replace('{DECLARATIONS}', DECLARATIONS).replace('{POSITION}', position).replace('{COUNT}', count).replace('{RULE}', rule);
}

async function problemsOf(position: string, count = '1', rule = 'greaterThan'): Promise<Problem[]> {
  const text = scenarioWith(position, count, rule);
  const ref = diskRef(path.join(path.sep, 'virtual', 'types.xosc'));
  const semantics = await analyzeDocument(ref, parseXml(text), new CatalogLoader(new ScenarioStore()), false);
  return parameterValueProblems(semantics, 'auto');
}

function described(problems: Problem[]): string[] {
  return problems.map((problem) => `${problem.severity}: ${problem.message}`);
}

describe("core: a parameter's value against the schema type of the attribute it stands in", () => {
  it('passes what converts: a double, an int or a numeric string in a double, an enumeration value in an enumeration', async () => {
    for (const name of ['Speed', 'Lanes', 'Numeric']) assert.deepEqual(described(await problemsOf(`$${name}`)), [], name);
    assert.deepEqual(described(await problemsOf('1', '$Twice', '$Greater')), []);
    assert.deepEqual(described(await problemsOf('1', '$Lanes')), []);
  });

  it('a string that is no number in a double is an error at the use, naming the declaration', async () => {
    const [problem, ...others] = await problemsOf('$Host');
    assert.deepEqual(others, []);
    assert.equal(problem.severity, 'error');
    assert.equal(problem.code, 'type-mismatch');
    assert.equal(
      problem.message,
      "'car_white', the value of parameter 'Host' (declared string), cannot be converted to the attribute's type double (LanePosition.s)",
    );
    const lines = scenarioWith('$Host').split('\n');
    assert.equal(
      problem.range.start.line,
      lines.findIndex((line) => line.includes('s="$Host"')),
    );
    assert.equal(problem.related?.[0].message, "'Host' is declared here with the value 'car_white'");
    assert.equal(
      problem.related?.[0].range.start.line,
      lines.findIndex((line) => line.includes('name="Host"')),
    );
  });

  it('5.0 for an integer is a warning; a boolean in a double and a word in an unsignedInt or an enumeration are errors', async () => {
    assert.deepEqual(described(await problemsOf('1', '$WholeText')), [
      "warning: '5.0', the value of parameter 'WholeText' (declared string), is a number with a fraction of zero for the attribute's type unsignedInt: the standard wants an integer, esmini reads it as 5 (ManeuverGroup.maximumExecutionCount)",
    ]);
    assert.match(
      described(await problemsOf('$Fast')).join('\n'),
      /^error: 'true', the value of parameter 'Fast' \(declared boolean\), cannot be converted to the attribute's type double/,
    );
    assert.match(
      described(await problemsOf('1', '$Host')).join('\n'),
      /^error: 'car_white'.*cannot be converted to the attribute's type unsignedInt/,
    );
    assert.match(
      described(await problemsOf('1', '1', '$Host')).join('\n'),
      /^error: 'car_white'.*cannot be converted to the attribute's type Rule \(one of .*greaterThan/,
    );
  });

  it('checks a ParameterReference value `$name` against the imported attribute it sets, at the reference', async () => {
    const simple = scenarioWith('1').replace(
      '<SimulationTimeCondition value="1"',
      '<SimulationTimeCondition parameterAttributes="value" value="1"',
    );
    const main = simple
      .replace(/<ManeuverGroup maximumExecutionCount="1" name="G">[\s\S]*?<\/ManeuverGroup>/, '')
      .replace(
        '<ParameterDeclarations>',
        '<ParameterDeclarations>\n    <ParameterDeclaration name="Late" parameterType="string" value="soon"/>',
      )
      .replace(
        '<Act name="A">',
        '<Act name="A">\n        <ManeuverGroup maximumExecutionCount="1" name="Outer">\n          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>\n          <ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="G"><ParameterReference key="value" value="$Late"/></ManeuverGroupReference></ScenarioReference>\n        </ManeuverGroup>',
      );
    const root = temporaryWorkspace({
      'simple.xosc': simple.replace(
        '<Actors selectTriggeringEntities="false"/>',
        '<Actors selectTriggeringEntities="false"/>\n          <Maneuver name="M"><Event name="E" priority="override"><Action name="X"><UserDefinedAction><CustomCommandAction type="t"/></UserDefinedAction></Action><StartTrigger><ConditionGroup><Condition name="C2" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition parameterAttributes="value" value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver>',
      ),
      'main.xosc': main,
    });
    try {
      const analysis = await new Flattener(new ScenarioStore(), 'asam', { version: 'auto' }).analyze(diskRef(path.join(root, 'main.xosc')));
      const found = analysis.problems
        .filter((problem) => problem.code === 'type-mismatch')
        .map((problem) => `${path.basename(problem.source.disk)}:${problem.range.start.line}: ${problem.message}`);
      const line = main.split('\n').findIndex((text) => text.includes('value="$Late"'));
      assert.deepEqual(found, [
        `main.xosc:${line}: 'soon', the value of parameter 'Late' (declared string), cannot be converted to the attribute's type double (SimulationTimeCondition.value) (set by ParameterReference 'value')`,
      ]);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('finds nothing in the real corpus: every esmini and CARLA scenario, catalog and library file', async function () {
    this.timeout(120_000);
    const library = path.join(corpusDir, 'library');
    if (!fs.existsSync(openscenarioDir) || !fs.existsSync(library)) this.skip();
    const files = [...corpusFiles()];
    const walk = (directory: string) => {
      for (const entry of fs.readdirSync(directory, { withFileTypes: true })) {
        const full = path.join(directory, entry.name);
        if (entry.isDirectory()) walk(full);
        else if (entry.name.endsWith('.xosc')) files.push(full);
      }
    };
    walk(library);
    const store = new ScenarioStore();
    const loader = new CatalogLoader(store);
    const found: string[] = [];
    let checked = 0;
    for (const file of files) {
      const ref = diskRef(file);
      const semantics = await analyzeDocument(ref, parseXml(fs.readFileSync(file, 'utf8')), loader, false);
      checked += semantics.model.sites.filter((site) => site.form.kind === 'parameter').length;
      found.push(...parameterValueProblems(semantics, 'auto').map((problem) => formatProblem(problem)));
    }
    assert.deepEqual(found, []);
    assert.ok(files.length > 150 && checked > 300, `${files.length} files, ${checked} uses checked`);
  });
});
