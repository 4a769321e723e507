import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { firstDifference } from '../../server/src/core/equivalence';
import { esminiXodrDir } from '../support/esminiBinaries';
import { requireEsmini, runEsmini } from '../support/esmini';
import {
  act,
  assertNoTrace,
  catalogFile,
  fileHeader,
  maneuver,
  maneuverGroup,
  parameterDeclarations,
  runCli,
  scenario,
  scenarioDocument,
  scenarioObjects,
  speedEvent,
  story,
  vehicleObject,
} from '../support/fixtures';
import { libraryDir, requireCorpus, sharedDir } from '../support/paths';
import { listFiles, temporaryWorkspace } from '../support/workspace';

/**
 * A group that sets one speed, then three more always the same: the same structure whatever its values,
 * and large enough that two uses pay for the simple scenario (modularize extracts nothing that would not).
 */
function speedGroup(name: string, speed: string): string {
  return maneuverGroup(
    name,
    'car',
    maneuver('M', speedEvent('E', speed) + speedEvent('E2', '5') + speedEvent('E3', '6') + speedEvent('E4', '7')),
  );
}

/**
 * esmini's synchronize.xosc in small (issue 28): groups that only reference HWManeuvers' Synchronize_NPC, whose entry
 * reads $AccRate without declaring it (esmini takes it from the referencing scenario). The group's text names no
 * $AccRate; the scenario declares it (synchronizeScenario's accRate).
 */
const SYNCHRONIZE_CATALOG = catalogFile(
  'HWManeuvers',
  `    <Maneuver name="Synchronize_NPC">
      <ParameterDeclarations>
        <ParameterDeclaration name="NPCFreeSpeed" parameterType="double" value="30"/>
        <ParameterDeclaration name="StartTime" parameterType="double" value="1"/>
      </ParameterDeclarations>
${speedEvent(
  'Free_Speed_Event_NPC',
  '$NPCFreeSpeed',
  '              <StartTrigger><ConditionGroup><Condition name="Free_Speed_Condition_NPC" delay="0" conditionEdge="rising">' +
    '<ByValueCondition><SimulationTimeCondition value="$StartTime" rule="greaterThan"/></ByValueCondition>' +
    '</Condition></ConditionGroup></StartTrigger>\n',
).replace(
  'dynamicsShape="step" value="0" dynamicsDimension="time"',
  'dynamicsShape="sinusoidal" value="$AccRate" dynamicsDimension="rate"',
)}    </Maneuver>
`,
);

/** A group referencing Synchronize_NPC, then speed events always the same: enough that its uses pay for a simple scenario. */
function synchronizeGroup(npc: string, speed: string, startTime: string): string {
  return maneuverGroup(
    `Synchronize_${npc}_Sequence`,
    npc,
    `          <CatalogReference catalogName="HWManeuvers" entryName="Synchronize_NPC">
            <ParameterAssignments>
              <ParameterAssignment parameterRef="NPCFreeSpeed" value="${speed}"/>
              <ParameterAssignment parameterRef="StartTime" value="${startTime}"/>
            </ParameterAssignments>
          </CatalogReference>
` + maneuver('Keep', speedEvent('E', speed) + speedEvent('E2', '5') + speedEvent('E3', '6') + speedEvent('E4', '7')),
  );
}

function synchronizeScenario(accRate: string, groups: string): string {
  return scenarioDocument({
    header: fileHeader({ revMinor: '1' }),
    parameters: parameterDeclarations([['AccRate', 'double', accRate]], 4),
    catalogLocations: '    <ManeuverCatalog>\n      <Directory path="Catalogs/Maneuvers"/>\n    </ManeuverCatalog>\n',
    entities: ['NPC1', 'NPC2', 'NPC3'].map((name) => vehicleObject(name)).join(''),
    storyboard: `    <Init>\n      <Actions/>\n    </Init>\n${story('S', act('Synchronize_Act', groups))}    <StopTrigger/>\n`,
  });
}

/** Every file below a folder with its bytes, to show that nothing changed. */
function snapshot(root: string): Map<string, string> {
  return new Map(listFiles(root).map((file) => [file, fs.readFileSync(path.join(root, file), 'latin1')]));
}

describe('cli: modularize', function () {
  this.timeout(180_000);

  it("the paper's library: writes the mains and simple scenarios, each main flattens back equivalent, the reduction printed", function () {
    requireCorpus(this);
    const root = temporaryWorkspace();
    const folders = fs
      .readdirSync(libraryDir)
      .filter((folder) => fs.existsSync(path.join(libraryDir, folder, 'result.xosc')))
      .sort();
    const inputs = folders.map((folder) => path.join(libraryDir, folder, 'result.xosc'));
    const before = snapshot(libraryDir);
    const run = runCli(['modularize', ...inputs, '-o', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assertNoTrace(run.stderr);
    const total = /^total \(SPEC 9\)\s+21,243\s+([\d,]+)\s+([\d.]+) %$/m.exec(run.stdout);
    assert.ok(total, run.stdout);
    const after = Number(total[1].replace(/,/g, ''));
    console.log(`      ${total[0].replace(/\s+/g, ' ')} (the authors by hand: 10,810)`);
    assert.ok(after < 10_810, `${after} lines`);
    assert.match(run.stdout, /simple scenarios?( holding \d+ behaviours)? in out\/simple:/);
    assert.match(run.stdout, /used in: out\/modular_hero_back\/result\.xosc/);
    // Every main flattens, from another working directory and without SCENARIO_PATH, to its input.
    let equivalent = 0;
    for (const folder of folders) {
      const flattened = runCli(['flatten', path.join(root, 'out', folder, 'result.xosc')], { cwd: sharedDir });
      assert.equal(flattened.status, 0, flattened.stderr);
      assert.equal(
        firstDifference(flattened.stdout, fs.readFileSync(path.join(libraryDir, folder, 'result.xosc'), 'utf8')),
        undefined,
        folder,
      );
      equivalent++;
    }
    assert.equal(equivalent, 31);
    assert.deepEqual(snapshot(libraryDir), before, 'inputs never change');
    assert.deepEqual(
      listFiles(root).filter((file) => !file.startsWith('out/')),
      [],
      'no temporary folder left',
    );
  });

  it('--format json and --dry-run: the same report, nothing written', () => {
    const root = temporaryWorkspace({
      'lib/a.xosc': scenario(speedGroup('A.Go', '10')),
      'lib/b.xosc': scenario(speedGroup('B.Go', '20') + speedGroup('C.Go', '10')),
    });
    const run = runCli(['modularize', 'lib', '-o', 'out', '--dry-run', '--format', 'json'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const report = JSON.parse(run.stdout) as {
      written: boolean;
      simpleScenarios: { file: string; parameterAttributes: string[]; uses: { main: string; overrides: unknown[] }[] }[];
      totals: { linesBefore: number; linesAfter: number };
    };
    assert.equal(report.written, false);
    assert.equal(report.simpleScenarios.length, 1);
    assert.equal(path.relative(root, report.simpleScenarios[0].file), path.join('out', 'simple', 'speed.xosc'));
    assert.deepEqual(report.simpleScenarios[0].parameterAttributes, ['AbsoluteTargetSpeed.value']);
    assert.deepEqual(
      report.simpleScenarios[0].uses.map((use) => path.relative(root, use.main)),
      ['out/a.xosc', 'out/b.xosc', 'out/b.xosc'],
    );
    assert.ok(report.totals.linesBefore > 0);
    assert.ok(!fs.existsSync(path.join(root, 'out')));
  });

  it("stats counts modularize's own output: each main against its flattening, the simple scenario once, the totals of modularize's report", () => {
    const root = temporaryWorkspace({
      'lib/a.xosc': scenario(speedGroup('A.Go', '10')),
      'lib/deep/b.xosc': scenario(speedGroup('B.Go', '20') + speedGroup('C.Go', '10')),
    });
    const made = runCli(['modularize', 'lib', '-o', 'out', '--format', 'json'], { cwd: root });
    assert.equal(made.status, 0, made.stderr);
    const report = JSON.parse(made.stdout) as { totals: { linesBefore: number; linesAfter: number } };
    const run = runCli(['stats', 'out', '--format', 'json'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const stats = JSON.parse(run.stdout) as {
      layout: string;
      rows: { scenario: string; modularLines: number; flattenedLines: number }[];
      shared: { file: string; lines: number }[];
      totals: { modularLines: number; flattenedLines: number };
    };
    assert.equal(stats.layout, 'files');
    assert.deepEqual(
      stats.rows.map((row) => row.scenario),
      ['a.xosc', path.join('deep', 'b.xosc')],
    );
    for (const row of stats.rows) {
      assert.equal(
        row.flattenedLines,
        fs
          .readFileSync(path.join(root, 'lib', row.scenario), 'utf8')
          .trimEnd()
          .split('\n').length,
        row.scenario,
      );
      assert.ok(row.modularLines < row.flattenedLines, row.scenario);
    }
    assert.deepEqual(
      stats.shared.map((item) => path.relative(root, item.file)),
      [path.join('out', 'simple', 'speed.xosc')],
    );
    assert.deepEqual(stats.totals, { ...stats.totals, modularLines: report.totals.linesAfter, flattenedLines: report.totals.linesBefore });
    const text = runCli(['stats', 'out'], { cwd: root });
    assert.equal(text.status, 0, text.stderr);
    assert.match(text.stdout, /\+ simple\/speed\.xosc/);
    assert.doesNotMatch(text.stdout, /total +0 +0/);
  });

  it("stats counts no catalog the mains read as a shared simple scenario, in either layout (esmini's samples' VehicleCatalog was counted as one)", () => {
    const cars = catalogFile(
      'VehicleCatalog',
      vehicleObject('car')
        .replace(/<\/?ScenarioObject[^>]*>/g, '')
        .replace(/^\s*\n/gm, ''),
    );
    const withCatalog = (directory: string, groups: string): string =>
      scenarioDocument({
        header: fileHeader({ revMinor: '0' }),
        catalogLocations: `    <VehicleCatalog><Directory path="${directory}"/></VehicleCatalog>\n`,
        entities: `    <ScenarioObject name="ego"><CatalogReference catalogName="VehicleCatalog" entryName="car"/></ScenarioObject>\n${scenarioObjects(['car'])}`,
        storyboard: story('S', act('A', groups, false)),
      });
    const root = temporaryWorkspace({
      'catalogs/VehicleCatalog.xosc': cars,
      'lib/a.xosc': withCatalog('../catalogs', speedGroup('A.Go', '10')),
      'lib/b.xosc': withCatalog('../catalogs', speedGroup('B.Go', '20') + speedGroup('C.Go', '10')),
      'paper/one/main.xosc': withCatalog('../../catalogs', ''),
    });
    const made = runCli(['modularize', 'lib', '-o', 'out', '--format', 'json'], { cwd: root });
    assert.equal(made.status, 0, made.stderr);
    const report = JSON.parse(made.stdout) as { totals: { linesBefore: number; linesAfter: number } };
    const run = runCli(['stats', 'out', '--format', 'json'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const stats = JSON.parse(run.stdout) as { shared: { file: string }[]; totals: { modularLines: number; flattenedLines: number } };
    assert.deepEqual(
      stats.shared.map((item) => path.relative(root, item.file)),
      [path.join('out', 'simple', 'speed.xosc')],
    );
    assert.deepEqual(stats.totals, { ...stats.totals, modularLines: report.totals.linesAfter, flattenedLines: report.totals.linesBefore });
    fs.writeFileSync(
      path.join(root, 'paper', 'one', 'main.xosc'),
      fs
        .readFileSync(path.join(root, 'out', 'a.xosc'), 'utf8')
        .replace('"../catalogs"', '"../../catalogs"')
        .replace('simple/speed.xosc', 'speed.xosc'),
    );
    fs.copyFileSync(path.join(root, 'out', 'simple', 'speed.xosc'), path.join(root, 'paper', 'speed.xosc'));
    const paper = runCli(['stats', 'paper', '--format', 'json'], { cwd: root });
    assert.equal(paper.status, 0, paper.stderr);
    const paperStats = JSON.parse(paper.stdout) as { layout: string; shared: { file: string }[] };
    assert.equal(paperStats.layout, 'folders');
    assert.deepEqual(
      paperStats.shared.map((item) => path.relative(root, item.file)),
      [path.join('paper', 'speed.xosc')],
    );
  });

  it('stats says why it has nothing to count, and exits 1: an empty folder, a folder of plain scenarios', () => {
    const root = temporaryWorkspace({ 'empty/readme.txt': 'nothing', 'plain/a.xosc': scenario(speedGroup('A.Go', '10')) });
    const empty = runCli(['stats', 'empty'], { cwd: root });
    assert.equal(empty.status, 1);
    assert.equal(empty.stdout, '', 'no table of zeros beside the error');
    assert.match(
      empty.stderr,
      /holds no scenario: neither folders NAME\/ with a main\.xosc \(the paper's layout\) nor \.xosc scenario files/,
    );
    const plain = runCli(['stats', 'plain'], { cwd: root });
    assert.equal(plain.status, 1);
    assert.match(plain.stderr, /no scenario of .*plain imports groups \(no ScenarioReference\): there is nothing modular to count/);
  });

  it('folders: catalogs and distributions are left alone, sub-folders keep their place, the mains resolve the simple scenarios', () => {
    const root = temporaryWorkspace({
      'lib/a.xosc': scenario(speedGroup('A.Go', '10')),
      'lib/deep/b.xosc': scenario(speedGroup('B.Go', '20')),
      'lib/Catalogs/cars.xosc':
        '<?xml version="1.0"?>\n<OpenSCENARIO><FileHeader revMajor="1" revMinor="0" date="2020-01-01T00:00:00" description="" author=""/><Catalog name="cars"/></OpenSCENARIO>\n',
    });
    const run = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /lib\/Catalogs\/cars\.xosc: left alone: a catalog/);
    assert.deepEqual(listFiles(path.join(root, 'out')), ['a.xosc', 'deep/b.xosc', 'simple/speed.xosc']);
    assert.match(fs.readFileSync(path.join(root, 'out/deep/b.xosc'), 'utf8'), /scenarioFileName="\.\.\/simple\/speed\.xosc"/);
    for (const name of ['a.xosc', 'deep/b.xosc']) {
      const flattened = runCli(['flatten', path.join(root, 'out', name)], { cwd: '/' });
      assert.equal(flattened.status, 0, flattened.stderr);
      assert.equal(firstDifference(flattened.stdout, fs.readFileSync(path.join(root, 'lib', name), 'utf8')), undefined);
    }
  });

  it('file paths of the mains and simple scenarios are rebased onto their folders: they reach the same road', () => {
    const withRoad = (groups: string) =>
      scenario(groups).replace('  <Entities>', '  <RoadNetwork>\n    <LogicFile filepath="roads/r.xodr"/>\n  </RoadNetwork>\n  <Entities>');
    const root = temporaryWorkspace({
      'lib/a.xosc': withRoad(speedGroup('A.Go', '10')),
      'lib/b.xosc': withRoad(speedGroup('B.Go', '20')),
      'lib/roads/r.xodr': '<OpenDRIVE/>',
      'elsewhere/deep/.keep': '',
    });
    const run = runCli(['modularize', 'lib', '-o', 'elsewhere/deep/out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const road = path.join(root, 'lib/roads/r.xodr');
    for (const file of ['elsewhere/deep/out/a.xosc', 'elsewhere/deep/out/simple/speed.xosc']) {
      const written = /<LogicFile filepath="([^"]+)"\/>/.exec(fs.readFileSync(path.join(root, file), 'utf8'));
      assert.ok(written, file);
      assert.equal(path.resolve(path.dirname(path.join(root, file)), written[1]), road, file);
    }
    // Flattened beside its input, the main's output names the road as the input does.
    const flattened = runCli(['flatten', 'elsewhere/deep/out/b.xosc', '-o', 'lib/b.flat.xosc'], { cwd: root });
    assert.equal(flattened.status, 0, flattened.stderr);
    assert.equal(
      firstDifference(fs.readFileSync(path.join(root, 'lib/b.flat.xosc'), 'utf8'), fs.readFileSync(path.join(root, 'lib/b.xosc'), 'utf8')),
      undefined,
    );
  });

  it("a group whose catalog entry reads a parameter of its scenario: the simple scenario declares it, flattens alone, and the mains flatten back (esmini's synchronize.xosc)", () => {
    const groups = (speeds: string[]) =>
      speeds.map((speed, index) => synchronizeGroup(`NPC${index + 1}`, speed, String(index + 1))).join('');
    const files = {
      'lib/Catalogs/Maneuvers/HWManeuvers.xosc': SYNCHRONIZE_CATALOG,
      'lib/synchronize.xosc': synchronizeScenario('3', groups(['30', '25', '20'])),
      'lib/synchronize_slow.xosc': synchronizeScenario('3', groups(['15', '12'])),
    };
    const root = temporaryWorkspace(files);
    // The source flattens (its catalog entry finds $AccRate in the scenario), and its groups name no $AccRate.
    assert.doesNotMatch(synchronizeGroup('NPC1', '30', '1'), /AccRate/);
    const run = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assertNoTrace(run.stderr);
    assert.ok(fs.existsSync(path.join(root, 'out', 'simple')), `nothing extracted: ${run.stdout}`);
    const simple = listFiles(path.join(root, 'out', 'simple'));
    assert.ok(simple.length > 0, `nothing extracted: ${run.stdout}`);
    for (const file of simple) {
      const text = fs.readFileSync(path.join(root, 'out', 'simple', file), 'utf8');
      assert.match(text, /<ParameterDeclaration name="AccRate" parameterType="double" value="3"\/>/, file);
      const alone = runCli(['flatten', path.join('out', 'simple', file)], { cwd: root });
      assert.equal(alone.status, 0, `${file} does not flatten on its own: ${alone.stderr}`);
      assert.doesNotMatch(alone.stderr, /error/, file);
    }
    for (const name of ['synchronize.xosc', 'synchronize_slow.xosc']) {
      const main = fs.readFileSync(path.join(root, 'out', name), 'utf8');
      assert.match(main, /<ScenarioReference /, `${name} imports nothing`);
      // Flattened beside its input, so that its catalog folder is written as the input writes it.
      const flat = path.join('lib', name.replace('.xosc', '.flat.xosc'));
      const flattened = runCli(['flatten', path.join('out', name), '-o', flat], { cwd: root });
      assert.equal(flattened.status, 0, flattened.stderr);
      assert.equal(
        firstDifference(fs.readFileSync(path.join(root, flat), 'utf8'), files[`lib/${name}` as keyof typeof files]),
        undefined,
        name,
      );
    }
  });

  it('scenarios that declare a parameter their common group reads with different values: one simple scenario reads its own copy, each main passes $Speed, check finds no warning', () => {
    const withSpeed = (value: string) =>
      scenarioDocument({
        header: fileHeader({ revMinor: '0' }),
        parameters: parameterDeclarations([['Speed', 'double', value]], 4),
        entities: '    <ScenarioObject name="ego"/>\n    <ScenarioObject name="car"/>\n',
        storyboard: story('S', act('A', speedGroup('Lead.Go', '$Speed') + speedGroup('Follow.Go', '$Speed'), false)),
      });
    const root = temporaryWorkspace({ 'lib/slow.xosc': withSpeed('10'), 'lib/fast.xosc': withSpeed('30') });
    const run = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assertNoTrace(run.stderr);
    assert.deepEqual(listFiles(path.join(root, 'out', 'simple')), ['speed.xosc']);
    const simple = fs.readFileSync(path.join(root, 'out', 'simple', 'speed.xosc'), 'utf8');
    // Declared as the first input (fast.xosc) declares Speed: only a default, each main passes its own.
    assert.match(simple, /<ParameterDeclaration name="Speed_Go" parameterType="double" value="30"\/>/);
    assert.match(simple, /<AbsoluteTargetSpeed parameterAttributes="value" value="\$Speed_Go"\/>/);
    for (const name of ['slow.xosc', 'fast.xosc']) {
      const main = fs.readFileSync(path.join(root, 'out', name), 'utf8');
      assert.equal(main.match(/<ParameterReference key="[\w.]*value" value="\$Speed"\/>/g)?.length, 2, main);
      const flattened = runCli(['flatten', path.join('out', name)], { cwd: root });
      assert.equal(flattened.status, 0, flattened.stderr);
      assert.equal(firstDifference(flattened.stdout, fs.readFileSync(path.join(root, 'lib', name), 'utf8')), undefined, name);
    }
    const check = runCli(['check', 'out', '--format', 'json'], { cwd: root });
    const report = JSON.parse(check.stdout) as {
      problems: { file: string; line: number; severity: string; code: string; message: string }[];
    };
    assert.deepEqual(
      report.problems.filter((problem) => problem.severity !== 'info'),
      [],
    );
  });

  it('no recurring group: nothing extracted, said so, nothing written', () => {
    const root = temporaryWorkspace({ 'lib/a.xosc': scenario(speedGroup('A', '10')), 'lib/b.xosc': scenario('') });
    const run = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /no ManeuverGroup recurs across the 2 scenarios: nothing extracted, nothing written/);
    assert.ok(!fs.existsSync(path.join(root, 'out')));
  });

  it('groups that recur but would not pay: each left inline with its reason, not called unique', () => {
    // One small event: two uses save less than the simple scenario they need.
    const small = (name: string, speed: string) => speedGroup(name, speed).replace(/( *<Event name="E2"[\s\S]*<\/Event>\n)/, '');
    const root = temporaryWorkspace({ 'lib/a.xosc': scenario(small('A.Go', '10')), 'lib/b.xosc': scenario(small('B.Go', '20')) });
    const run = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /2 recurring groups left inline, each for the reason below: nothing extracted, nothing written/);
    assert.match(
      run.stdout,
      /kept inline: A\.Go in lib\/a\.xosc: extracting it would not pay: its simple scenario \(\d+ lines\) outweighs the \d+ lines its 2 uses would save/,
    );
    assert.doesNotMatch(run.stdout, /no ManeuverGroup recurs/);
    assert.ok(!fs.existsSync(path.join(root, 'out')));
  });

  it('an input that does not parse: named with its line, nothing written', () => {
    const root = temporaryWorkspace({
      'lib/a.xosc': scenario(speedGroup('A.Go', '10')),
      'lib/b.xosc': scenario(speedGroup('B.Go', '10')),
      'lib/broken.xosc': '<OpenSCENARIO>\n  <Storyboard>\n</OpenSCENARIO>\n',
    });
    const run = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assertNoTrace(run.stderr);
    assert.match(run.stderr, /lib\/broken\.xosc:2:3: error: element <Storyboard> is not closed/);
    assert.match(run.stderr, /nothing was written/);
    assert.ok(!fs.existsSync(path.join(root, 'out')));
  });

  it('an OUT that exists is refused unless --force; inputs are never overwritten', () => {
    const files = { 'lib/a.xosc': scenario(speedGroup('A.Go', '10')), 'lib/b.xosc': scenario(speedGroup('B.Go', '20')) };
    const root = temporaryWorkspace({ ...files, 'out/keep.txt': 'mine' });
    const refused = runCli(['modularize', 'lib', '-o', 'out'], { cwd: root });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(refused.stderr, /out exists; nothing was written \(--force writes into it\)/);
    assert.deepEqual(listFiles(path.join(root, 'out')), ['keep.txt']);
    const forced = runCli(['modularize', 'lib', '-o', 'out', '--force'], { cwd: root });
    assert.equal(forced.status, 0, forced.stderr);
    assert.deepEqual(listFiles(path.join(root, 'out')), ['a.xosc', 'b.xosc', 'keep.txt', 'simple/speed.xosc']);
    // OUT the input folder itself: every main would replace its input.
    const over = runCli(['modularize', 'lib', '-o', 'lib', '--force'], { cwd: root });
    assert.equal(over.status, 1, over.stderr);
    assert.match(over.stderr, /refusing to write lib\/a\.xosc: it is an input/);
    for (const [name, text] of Object.entries(files)) assert.equal(fs.readFileSync(path.join(root, name), 'utf8'), text);
    assert.ok(!fs.existsSync(path.join(root, 'lib', 'simple')));
  });

  it('usage: no input, no -o, an unknown option', () => {
    assert.equal(runCli(['modularize', '-o', 'out']).status, 2);
    assert.equal(runCli(['modularize', 'lib']).status, 2);
    const unknown = runCli(['modularize', 'lib', '-o', 'out', '--frobnicate']);
    assert.equal(unknown.status, 2);
    assert.match(unknown.stderr, /unknown option '--frobnicate'/);
    const noValue = runCli(['modularize', 'lib', '-o']);
    assert.equal(noValue.status, 2);
    assert.match(noValue.stderr, /--output needs a value/);
  });

  it("esmini's scenarios: files that share groups run in esmini exactly as the originals once modularized and flattened", async function () {
    requireEsmini(this);
    const source = path.join(sharedDir, 'corpus', 'openscenario', 'esmini');
    if (!fs.existsSync(source)) this.skip();
    // The scenarios name ../xodr and ../xosc/Catalogs: the corpus goes in as xosc/ beside xodr/, OUT beside them.
    const root = temporaryWorkspace();
    fs.cpSync(source, path.join(root, 'xosc'), { recursive: true });
    fs.symlinkSync(esminiXodrDir, path.join(root, 'xodr'));
    const run = runCli(['modularize', 'xosc', '-o', 'out', '--format', 'json'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const report = JSON.parse(run.stdout) as { simpleScenarios: unknown[]; files: { input: string; main: string; imports: number }[] };
    assert.ok(report.simpleScenarios.length >= 3, `${report.simpleScenarios.length} simple scenarios`);
    const sharing = new Set(report.files.filter((file) => file.imports > 0).map((file) => path.basename(file.input)));
    const chosen = ['acc-test.xosc', 'alks-test.xosc', 'cut-in_external.xosc', 'cut-in_sloppy.xosc'];
    for (const name of chosen) assert.ok(sharing.has(name), `${name} imports a shared group (${[...sharing].join(', ')})`);
    fs.mkdirSync(path.join(root, 'flat'));
    for (const name of chosen) {
      const flattened = runCli(['flatten', path.join('out', name), '-o', path.join('flat', name)], { cwd: root });
      assert.equal(flattened.status, 0, flattened.stderr);
      const original = await runEsmini(path.join(root, 'xosc', name), 30);
      const modular = await runEsmini(path.join(root, 'flat', name), 30);
      assert.ok(original.length > 10, `${name}: ${original.length} steps`);
      assert.deepEqual(modular, original, name);
    }
  });
});
