import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { formatProblem, Problem } from '../../server/src/core/problems';
import { ContentAutomaton } from '../../server/src/core/schema/automaton';
import { schemaIndex } from '../../server/src/core/schema/index';
import { schemaFor, SCHEMA_VERSIONS } from '../../server/src/core/schema/model';
import { schemaProblems } from '../../server/src/core/diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { allowedChildren } from '../../server/src/core/schema/query';
import { checkValue } from '../../server/src/core/schema/values';
import { chooseVersion } from '../../server/src/core/schema/version';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { caseStudyDir, libraryDir, repoRoot, requireCorpus, sharedDir } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

/** One memory of schema checks for the whole file, as the checks of one process shared before. */
const schemaChecks = new SchemaCheckMemory();

const openscenarioDir = path.join(sharedDir, 'corpus', 'openscenario');

function xoscFiles(directory: string): string[] {
  if (!fs.existsSync(directory)) return [];
  const found: string[] = [];
  const walk = (folder: string) => {
    for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
      const full = path.join(folder, entry.name);
      if (entry.isDirectory()) walk(full);
      else if (entry.name.endsWith('.xosc')) found.push(full);
    }
  };
  walk(directory);
  return found.sort();
}

/**
 * Corpus files that really break their schema, with the violation. CARLA's catalogs state version
 * 0.9 (read against 1.0, the nearest) and write a FileHeader date without a time, which xsd:dateTime requires.
 */
const GENUINE_VIOLATIONS: Record<string, string[]> = Object.fromEntries(
  ['EnvironmentCatalog', 'ManeuverCatalog', 'MiscObjectCatalog', 'PedestrianCatalog', 'VehicleCatalog'].map((name) => [
    `openscenario/scenario_runner/${name}.xosc`,
    ['schema-value FileHeader.date (DateTime)'],
  ]),
);

function errorsOf(problems: Problem[]): Problem[] {
  return problems.filter((problem) => problem.severity === 'error');
}

const SCENARIO = (minor: string, storyboard: string, root = '') => `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="${minor}" date="2024-01-01T00:00:00" description="d" author="a"/>
${root}  <CatalogLocations/>
  <RoadNetwork/>
  <Entities/>
  <Storyboard>
${storyboard}  </Storyboard>
</OpenSCENARIO>
`;

describe('core: the OpenSCENARIO schemas, compiled at build time', () => {
  it('holds the four versions with their ASAM licence headers, and no XSD is read at run time', () => {
    for (const version of SCHEMA_VERSIONS) {
      const schema = schemaFor(version);
      assert.match(schema.header, /ASAM license terms/);
      assert.ok(Object.keys(schema.complexTypes).length > 150, version);
    }
    assert.ok(fs.existsSync(path.join(repoRoot, 'dist', 'openscenario-schemas.json')));
  });

  it('computes the version that introduced each element and attribute by comparing the schemas', () => {
    const root13 = schemaIndex('1.3').childParticles('OpenScenario');
    assert.equal(root13.find((particle) => particle.name === 'VariableDeclarations')?.since, '1.2');
    assert.equal(root13.find((particle) => particle.name === 'MonitorDeclarations')?.since, '1.3');
    assert.equal(root13.find((particle) => particle.name === 'FileHeader')?.since, undefined);
    assert.equal(schemaIndex('1.3').attribute('ActivateControllerAction', 'objectControllerRef')?.since, '1.3');
  });

  it('reads deprecation from the annotations of 1.1 and later: elements, attributes, types and enumeration values', () => {
    assert.equal(schemaIndex('1.0').childParticle('PrivateAction', 'ActivateControllerAction', false)?.deprecated, undefined);
    const activate = schemaIndex('1.3').childParticle('PrivateAction', 'ActivateControllerAction', false);
    assert.equal(activate?.deprecatedSince, '1.1');
    const alongRoute = schemaIndex('1.2').attribute('TimeHeadwayCondition', 'alongRoute');
    assert.equal(alongRoute?.deprecatedSince, '1.1');
    assert.equal(schemaIndex('1.3').simpleType('CloudState')?.deprecated, true);
    const priority = schemaIndex('1.3').simpleType('Priority');
    assert.ok(priority?.alternatives.some((alternative) => alternative.deprecatedValues?.includes('overwrite')));
    assert.ok(
      !schemaIndex('1.1')
        .simpleType('Priority')
        ?.alternatives.some((alternative) => alternative.deprecatedValues?.includes('overwrite')),
    );
  });

  it('checks values: built-in types, enumerations, $parameters everywhere a type admits one, ${expressions} from 1.1', () => {
    const double10 = schemaIndex('1.0').simpleType('Double');
    const double11 = schemaIndex('1.1').simpleType('Double');
    assert.ok(double10 && double11);
    for (const value of ['1', '-2.5e3', ' 4 ', 'INF', '$Speed']) assert.ok(checkValue(double10, value).valid, value);
    for (const value of ['abc', '1,5', '$1a', '']) assert.ok(!checkValue(double10, value).valid, value);
    assert.deepEqual(checkValue(double10, '${$a * 2}'), { valid: false, expressionNotInVersion: true });
    assert.ok(checkValue(double11, '${$a * 2}').valid);
    assert.ok(!checkValue(double11, '${$a < 2}').valid);
    const unsignedShort = schemaIndex('1.3').simpleType('UnsignedShort');
    assert.ok(
      unsignedShort &&
        checkValue(unsignedShort, '65535').valid &&
        !checkValue(unsignedShort, '65536').valid &&
        !checkValue(unsignedShort, '-1').valid,
    );
    const dateTime = schemaIndex('1.0').simpleType('DateTime');
    assert.ok(dateTime && checkValue(dateTime, '2020-03-20T12:00:00').valid && !checkValue(dateTime, '2020-03-20').valid);
    const rule = schemaIndex('1.0').simpleType('Rule');
    assert.ok(
      rule && checkValue(rule, 'greaterThan').valid && checkValue(rule, '$rule').valid && !checkValue(rule, 'greaterThanOrEqual').valid,
    );
    assert.ok(rule && checkValue(schemaIndex('1.2').simpleType('Rule') ?? rule, 'greaterOrEqual').valid);
  });

  it('chooses the schema by FileHeader revMajor/revMinor, the nearest for others, or the pinned one', () => {
    const header = (major: string, minor: string) =>
      parseXml(`<OpenSCENARIO><FileHeader revMajor="${major}" revMinor="${minor}"/></OpenSCENARIO>`);
    assert.equal(chooseVersion(header('1', '0')).version, '1.0');
    assert.equal(chooseVersion(header('1', '2')).version, '1.2');
    assert.deepEqual(
      [chooseVersion(header('0', '9')).version, chooseVersion(header('0', '9')).fallback],
      ['1.0', 'no schema for OpenSCENARIO 0.9'],
    );
    assert.equal(chooseVersion(header('1', '7')).version, '1.3');
    assert.equal(chooseVersion(header('1', '0'), '1.3').version, '1.3');
  });

  it('runs content models as automata: order, choice, occurrences, and what is missing', () => {
    const index = schemaIndex('1.0');
    const automaton: ContentAutomaton = index.automaton('Storyboard');
    const after = (names: string[]) => names.reduce((states, name) => automaton.step(states, name)?.states ?? [], automaton.start);
    assert.ok(automaton.accepts(after(['Init', 'Story', 'Story', 'StopTrigger'])));
    assert.ok(!automaton.accepts(after(['Init', 'StopTrigger'])));
    assert.equal(automaton.step(after(['Init']), 'StopTrigger'), undefined);
    assert.deepEqual(
      automaton.missingBefore(after(['Init']), 'StopTrigger')?.map((particle) => particle.name),
      ['Story'],
    );
    assert.deepEqual(
      automaton.missingToEnd(after(['Init', 'Story'])).map((particle) => particle.name),
      ['StopTrigger'],
    );
    assert.deepEqual(
      allowedChildren(index, 'OpenScenario', ['FileHeader'], 'RoadNetwork').map(
        (entry) => `${entry.particle.name}${entry.required ? '!' : ''}`,
      ),
      ['ParameterDeclarations', 'CatalogLocations!', 'Catalog'],
    );
  });

  it('reports each kind of violation at its name or value', () => {
    const text = SCENARIO(
      '0',
      '    <Init><Actions/></Init>\n    <StopTrigger/>\n    <Story name="s"/>\n',
      '  <ParameterDeclarations><ParameterDeclaration name="p" parameterType="real" value="1" unit="m"/></ParameterDeclarations>\n',
    );
    const problems = schemaProblems(diskRef('/x/a.xosc'), parseXml(text), schemaChecks);
    const summary = problems.map(
      (problem) => `${problem.code}@${problem.range.start.line + 1}:${problem.range.start.character + 1} ${problem.message}`,
    );
    assert.deepEqual(summary, [
      "schema-value@4:72 'real' is not a valid value of ParameterDeclaration.parameterType (ParameterType): expected one of boolean, dateTime, double, integer, string, unsignedInt, unsignedShort, a $parameter",
      "schema-unknown-attribute@4:88 <ParameterDeclaration> has no attribute 'unit' in OpenSCENARIO 1.0",
      // The Story is written, only after the StopTrigger: one order problem, not a missing Story too.
      'schema-order@10:6 <StopTrigger> is out of order in <Storyboard>: <Story> must come before it',
      'schema-missing-element@11:6 <Story> lacks the required element <Act>',
    ]);
  });

  it('validates Catalog and ParameterValueDistribution files (other roots of OpenSCENARIO)', () => {
    const catalog = `<OpenSCENARIO><FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" description="d" author="a"/><Catalog name="C"><Vehicle name="v" vehicleCategory="car"/></Catalog></OpenSCENARIO>`;
    const codes = schemaProblems(diskRef('/x/c.xosc'), parseXml(catalog), schemaChecks).map(
      (problem) => `${problem.code} ${problem.message}`,
    );
    assert.deepEqual(codes, [
      'schema-missing-element <Vehicle> lacks the required elements <BoundingBox>, <Performance>, <Axles>, <Properties>',
    ]);
    const distribution = `<OpenSCENARIO><FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" description="d" author="a"/><ParameterValueDistribution><ScenarioFile filepath="a.xosc"/><Deterministic/></ParameterValueDistribution></OpenSCENARIO>`;
    assert.deepEqual(schemaProblems(diskRef('/x/d.xosc'), parseXml(distribution), schemaChecks), []);
    const distribution10 = distribution.replace('revMinor="1"', 'revMinor="0"');
    assert.deepEqual(
      schemaProblems(diskRef('/x/d.xosc'), parseXml(distribution10), schemaChecks)
        .map((problem) => problem.code)
        .sort(),
      ['schema-missing-element', 'schema-unknown-element'],
    );
  });

  it('the flattened output is checked strictly, each problem at its source: an override value at its ParameterReference', async () => {
    const valid = SCENARIO(
      '0',
      '    <Init><Actions/></Init>\n    <Story name="s"><Act name="a">\n{GROUP}      <StartTrigger/></Act></Story>\n    <StopTrigger/>\n',
    );
    // The simple group names its actor: flattening sets that EntityRef to the main's (a group without one has none, which esmini refuses).
    const simple = valid
      .replace(
        '<Entities/>',
        '<Entities><ScenarioObject name="ego"><MiscObject miscObjectCategory="obstacle" mass="1" name="box"><BoundingBox><Center x="0" y="0" z="0"/><Dimensions width="1" length="1" height="1"/></BoundingBox><Properties/></MiscObject></ScenarioObject></Entities>',
      )
      .replace(
        '{GROUP}',
        `        <ManeuverGroup maximumExecutionCount="1" name="G"><Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors><Maneuver name="M"><Event name="E" priority="overwrite"><Action name="A"><PrivateAction><TeleportAction><Position><WorldPosition parameterAttributes="x" x="1" y="2"/></Position></TeleportAction></PrivateAction></Action><StartTrigger/></Event></Maneuver></ManeuverGroup>\n`,
      );
    // The main declares its actor on one line (an undeclared one is an error of its own), so the lines stay as they were.
    const main = valid
      .replace(
        '<Entities/>',
        '<Entities><ScenarioObject name="ego"><MiscObject miscObjectCategory="obstacle" mass="1" name="box"><BoundingBox><Center x="0" y="0" z="0"/><Dimensions width="1" length="1" height="1"/></BoundingBox><Properties/></MiscObject></ScenarioObject></Entities>',
      )
      .replace(
        '{GROUP}',
        `        <ManeuverGroup maximumExecutionCount="1" name="Outer"><Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>\n          <ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="G"><ParameterReference key="x" value="far"/></ManeuverGroupReference></ScenarioReference>\n        </ManeuverGroup>\n`,
      );
    const root = temporaryWorkspace({ 'main.xosc': main, 'simple.xosc': simple });
    const store = new ScenarioStore({ scenarioPath: [], root });
    const result = await new Flattener(store, 'asam', { version: 'auto' }).flatten(diskRef(path.join(root, 'main.xosc')));
    assert.equal(result.text, undefined);
    const errors = errorsOf(result.problems).map((problem) => formatProblem(problem, root));
    const line = main.split('\n')[10];
    assert.deepEqual(errors, [
      `main.xosc:11:${line.indexOf('"far"') + 2}: error: 'far' is not a valid value of WorldPosition.x (Double): expected xsd:double, a $parameter (set by ParameterReference 'x')`,
    ]);
    // The editor analyses without rendering the output, and finds the same problem at the same place.
    const analysis = await new Flattener(store, 'asam', { version: 'auto' }).analyze(diskRef(path.join(root, 'main.xosc')));
    assert.deepEqual(
      errorsOf(analysis.problems).map((problem) => formatProblem(problem, root)),
      errors,
    );
    const forced = await new Flattener(store, 'asam', { version: 'auto' }).flatten(diskRef(path.join(root, 'main.xosc')), { force: true });
    assert.ok(forced.text?.includes('x="far"'));
    const fine = temporaryWorkspace({ 'main.xosc': main.replace('value="far"', 'value="-5"'), 'simple.xosc': simple });
    const ok = await new Flattener(new ScenarioStore({ scenarioPath: [], root: fine }), 'asam', { version: 'auto' }).flatten(
      diskRef(path.join(fine, 'main.xosc')),
    );
    assert.deepEqual(
      errorsOf(ok.problems).map((problem) => formatProblem(problem)),
      [],
    );
    assert.ok(ok.text?.includes('x="-5"'));
  });
});

describe('core: schema check after an edit inside one value', () => {
  it('moves the other findings and checks the edited value again, as a full check would', () => {
    const source = diskRef('/x/edited.xosc');
    let text = SCENARIO(
      '2',
      '    <Init><Actions><Private entityRef="ego"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="1" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="5"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Private></Actions></Init>\n    <Story name="s"><Act name="a" unknown="u"><ManeuverGroup maximumExecutionCount="1" name="g"><Actors selectTriggeringEntities="false"/></ManeuverGroup><StartTrigger/></Act></Story>\n    <StopTrigger/>\n',
    );
    const summary = (problems: Problem[]) =>
      problems.map(
        (problem) =>
          `${problem.code}@${problem.range.start.line}:${problem.range.start.character}-${problem.range.end.character} ${problem.message}`,
      );
    schemaProblems(source, parseXml(text), schemaChecks);
    const edits: [string, string][] = [
      ['value="5"', 'value="fast"'],
      ['dynamicsShape="step"', 'dynamicsShape="stepwise"'],
      ['value="fast"', 'value="$Speed"'],
      ['value="1"', 'value="1.25e2"'],
      ['dynamicsShape="stepwise"', 'dynamicsShape="linear"'],
      ['name="s"', 'name="a much longer story name"'],
    ];
    edits.forEach(([from, to], step) => {
      text = text.replace(from, to);
      const document = parseXml(text);
      // A file never checked before gets a full check: the reference.
      const full = schemaProblems(diskRef(`/x/fresh_${step}.xosc`), document, schemaChecks);
      assert.deepEqual(summary(schemaProblems(source, document, schemaChecks)), summary(full), `${from} -> ${to}`);
    });
    assert.deepEqual(
      summary(schemaProblems(source, parseXml(text), schemaChecks)).map((line) => line.split(' ')[0].split('@')[0]),
      ['schema-unknown-attribute'],
    );
  });
});

describe('corpus: every file validates against its own version', function () {
  before(function () {
    requireCorpus(this);
  });

  for (const file of xoscFiles(path.join(sharedDir, 'corpus'))) {
    const name = path.relative(path.join(sharedDir, 'corpus'), file);
    it(name, () => {
      const problems = errorsOf(schemaProblems(diskRef(file), parseXml(fs.readFileSync(file, 'utf8')), schemaChecks));
      const found = problems.map((problem) => `${problem.code} ${/of ([\w.]+ \(\w+\))/.exec(problem.message)?.[1] ?? problem.message}`);
      assert.deepEqual(found, GENUINE_VIOLATIONS[name] ?? [], problems.map((problem) => formatProblem(problem)).join('\n'));
    });
  }

  it('holds the esmini and scenario_runner files, the library and the case study', () => {
    assert.ok(xoscFiles(openscenarioDir).length >= 100);
  });

  it('the library results and the case study flatten to schema-valid outputs (checked strictly)', async () => {
    const names = fs.readdirSync(libraryDir).filter((name) => name.startsWith('modular_'));
    for (const name of names) {
      const store = new ScenarioStore({ scenarioPath: [libraryDir], root: path.join(libraryDir, name) });
      const result = await new Flattener(store, 'asam', { version: 'auto' }).flatten(
        childRef(diskRef(path.join(libraryDir, name, 'result.mosc')), 'main.xosc'),
      );
      assert.ok(result.text, name);
      assert.deepEqual(
        errorsOf(result.problems).map((problem) => formatProblem(problem)),
        [],
        name,
      );
    }
    const store = new ScenarioStore({ scenarioPath: [], root: caseStudyDir });
    const caseStudy = await new Flattener(store, 'asam', { version: 'auto' }).flatten(diskRef(path.join(caseStudyDir, 'main.xosc')), {
      force: true,
    });
    assert.ok(caseStudy.text);
    assert.deepEqual(
      caseStudy.problems.filter((problem) => problem.code.startsWith('schema-') && problem.severity === 'error'),
      [],
    );
  });
});
