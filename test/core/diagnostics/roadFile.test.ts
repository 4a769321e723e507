import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { ROAD_FILE, roadFileWording } from '../../../server/src/core/diagnostics/roadFile';
import { Problem } from '../../../server/src/core/problems';
import { Simulator } from '../../../server/src/core/profiles/simulators';
import { ruleIdOf } from '../../../server/src/core/rules';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../../server/src/core/semantics';
import { childRef, diskRef, ScenarioStore } from '../../../server/src/core/sources';
import JSZip from 'jszip';
import { parseXml } from '../../../server/src/core/xml';
import { outerGroup, roadScenario } from '../../support/fixtures';
import { STRAIGHT_ROAD } from '../../support/roads';
import { temporaryWorkspace } from '../../support/workspace';
import { wordingOf } from './support';

/**
 * The road-file problems of `xosc/scenario.xosc` of `text`, written in a workspace of its own with `files`; `roadPath`:
 * folders of the workspace handed as the road path (the store's catalogPath, as `--road-path` and the setting give it).
 */
async function roadProblems(
  text: string,
  files: Record<string, string> = {},
  options: { simulator?: Simulator; roadPath?: string[] } = {},
): Promise<{ problems: Problem[]; root: string }> {
  const root = temporaryWorkspace({ 'xosc/scenario.xosc': text, ...files });
  try {
    const store = new ScenarioStore({
      scenarioPath: [],
      root,
      catalogPath: (options.roadPath ?? []).map((folder) => path.join(root, folder)),
    });
    const semantics = await analyzeDocument(
      diskRef(path.join(root, 'xosc', 'scenario.xosc')),
      parseXml(text),
      new CatalogLoader(store),
      false,
      options.simulator,
    );
    return { problems: semanticProblems(semantics).filter((problem) => problem.code === 'road-file'), root };
  } finally {
    fs.rmSync(root, { recursive: true, force: true });
  }
}

const onRoad = (logicFile: string, parameters?: string) => roadScenario({ logicFile, parameters, groups: [] });

describe('diagnostics: road-file', () => {
  it('names the path, the folders looked in (the scenario first, at most three others) and what esmini does', () => {
    assert.deepEqual(roadFileWording('../xodr/road.xodr', ['/s'], 'warning', false), {
      severity: 'warning',
      code: 'road-file',
      message:
        'road file \'../xodr/road.xodr\' is not found beside this file (/s): esmini stops at such a scenario ("Failed to locate OpenDRIVE file")',
      hint: 'correct the path, or add the folder that holds the file to the road path (--road-path, the modular2simple.esmini.roadPath setting)',
    });
    assert.equal(
      roadFileWording('Town05', ['/s', '/a', '/b', '/c', '/d', '/e'], 'error', true).message,
      "road file 'Town05' is found neither beside this file (/s) nor in /a, /b, /c, 2 more folders; 'Town05' is a CARLA map, which esmini loads only from a file of that exact name: esmini stops at such a scenario (\"Failed to locate OpenDRIVE file\")",
    );
    assert.equal(ROAD_FILE.severity, 'warning');
    assert.equal(ruleIdOf('road-file'), 'modular2simple:road-file');
  });

  it('reports a road found nowhere at its filepath: a warning by the standard, an error for esmini, nothing for CARLA', async () => {
    const text = onRoad('../xodr/road.xodr');
    const { problems, root } = await roadProblems(text);
    const lines = text.split('\n');
    const line = lines.findIndex((each) => each.includes('<LogicFile'));
    assert.deepEqual(
      problems.map((problem) => [problem.range.start.line, problem.range.start.character]),
      [[line, lines[line].indexOf('../xodr')]],
    );
    assert.deepEqual(problems.map(wordingOf), [roadFileWording('../xodr/road.xodr', [path.join(root, 'xosc')], 'warning', false)]);
    assert.deepEqual(
      (await roadProblems(text, {}, { simulator: 'esmini' })).problems.map((problem) => problem.severity),
      ['error'],
    );
    // ScenarioRunner looks beside the scenario only: its profile's own rule says so (profiles/carla.ts roadFileMissing).
    assert.deepEqual((await roadProblems(text, {}, { simulator: 'carla' })).problems, []);
  });

  it('finds the road as esmini does: the path from the scenario, its file name there, in a road folder or a catalog folder', async () => {
    // The path relative to the scenario's folder (esmini's rule), not to the working directory.
    assert.deepEqual((await roadProblems(onRoad('../xodr/road.xodr'), { 'xodr/road.xodr': STRAIGHT_ROAD })).problems, []);
    // The file name alone in the scenario's folder (esmini's LocateFile tries it after the path).
    assert.deepEqual((await roadProblems(onRoad('C:/elsewhere/road.xodr'), { 'xosc/road.xodr': STRAIGHT_ROAD })).problems, []);
    // A road folder: run hands it to esmini as --path.
    assert.deepEqual(
      (await roadProblems(onRoad('../xodr/road.xodr'), { 'roads/road.xodr': STRAIGHT_ROAD }, { roadPath: ['roads'] })).problems,
      [],
    );
    // A catalog folder of the scenario: run hands it as --path too, and esmini finds the road there by its file name.
    const withCatalogs = onRoad('../xodr/road.xodr').replace(
      '<CatalogLocations/>',
      '<CatalogLocations><VehicleCatalog><Directory path="../catalogs"/></VehicleCatalog></CatalogLocations>',
    );
    assert.deepEqual((await roadProblems(withCatalogs, { 'catalogs/road.xodr': STRAIGHT_ROAD })).problems, []);
    // A folder of that name is no road file.
    assert.equal((await roadProblems(onRoad('road.xodr'), { 'xosc/road.xodr/file.txt': 'x' })).problems.length, 1);
  });

  it('is silent on a CARLA map by the standard and for CARLA, and an error for esmini, which needs a file of that name', async () => {
    for (const town of ['Town01', 'Town10HD_Opt', 'Town15']) assert.deepEqual((await roadProblems(onRoad(town))).problems, [], town);
    const esmini = await roadProblems(onRoad('Town05'), {}, { simulator: 'esmini' });
    assert.deepEqual(esmini.problems.map(wordingOf), [roadFileWording('Town05', [path.join(esmini.root, 'xosc')], 'error', true)]);
    assert.deepEqual((await roadProblems(onRoad('Town05'), { 'xosc/Town05': STRAIGHT_ROAD }, { simulator: 'esmini' })).problems, []);
    // Not a CARLA map: a road file like any other.
    assert.equal((await roadProblems(onRoad('Town99'))).problems.length, 1);
  });

  it('reads a $parameter path through its value, and says nothing of one whose value is not known', async () => {
    const declared = '<ParameterDeclaration name="Road" parameterType="string" value="gone.xodr"/>';
    const { problems } = await roadProblems(onRoad('$Road', declared), { 'xosc/road.xodr': STRAIGHT_ROAD });
    assert.match(problems[0]?.message ?? '', /^road file 'gone\.xodr' /);
    const found = '<ParameterDeclaration name="Road" parameterType="string" value="road.xodr"/>';
    assert.deepEqual((await roadProblems(onRoad('$Road', found), { 'xosc/road.xodr': STRAIGHT_ROAD })).problems, []);
    assert.deepEqual((await roadProblems(onRoad('${$Folder + /road.xodr}'))).problems, []);
    assert.deepEqual((await roadProblems(onRoad('$Undeclared'))).problems, []);
  });

  it("finds a road that the scenario's package holds (a self-contained package), as a run writes it beside the scenario", async () => {
    const text = onRoad('roads/road.xodr');
    const zip = new JSZip();
    zip.file('main.xosc', text);
    zip.file('roads/road.xodr', STRAIGHT_ROAD);
    const root = temporaryWorkspace({ 'pkg.mosc': await zip.generateAsync({ type: 'uint8array' }) });
    try {
      const problemsOf = async (main: string) =>
        semanticProblems(
          await analyzeDocument(
            childRef(diskRef(path.join(root, 'pkg.mosc')), main),
            parseXml(main === 'main.xosc' ? text : onRoad('roads/gone.xodr')),
            new CatalogLoader(new ScenarioStore({ root })),
            false,
          ),
        ).filter((problem) => problem.code === 'road-file');
      assert.deepEqual(await problemsOf('main.xosc'), []);
      assert.equal((await problemsOf('other.xosc')).length, 1);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('names, in its hint, a file of that name that a package the scenario references holds, and how to extract it (issue 27)', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', onRoad('roads/road.xodr'));
    zip.file('roads/road.xodr', STRAIGHT_ROAD);
    const root = temporaryWorkspace({ 'app/drive.mosc': await zip.generateAsync({ type: 'uint8array' }) });
    try {
      const outside = (logicFile: string) =>
        roadScenario({ logicFile, groups: [outerGroup('Car', 'Ego', [{ file: 'drive.mosc', groups: [{ name: 'Drive' }] }])] });
      const problemsOf = async (logicFile: string) =>
        semanticProblems(
          await analyzeDocument(
            diskRef(path.join(root, 'app', 'main.xosc')),
            parseXml(outside(logicFile)),
            new CatalogLoader(new ScenarioStore({ root })),
            true,
            'esmini',
          ),
        ).filter((problem) => problem.code === 'road-file');
      const app = path.join(root, 'app');
      const held = [{ packageFile: path.join(app, 'drive.mosc'), entries: ['roads/road.xodr'] }];
      // By its path from the package's root, or by its file name anywhere in the package.
      for (const logicFile of ['roads/road.xodr', 'road.xodr']) {
        const problems = await problemsOf(logicFile);
        assert.deepEqual(problems.map(wordingOf), [roadFileWording(logicFile, [app], 'error', false, held)], logicFile);
        assert.match(
          problems[0].hint ?? '',
          new RegExp(
            `holds roads/road\\.xodr, .*: unzip -j ${path.join(app, 'drive.mosc').replace(/[.\\/]/g, '\\$&')} roads/road\\.xodr -d `,
          ),
        );
      }
      // A file the package does not hold: the usual hint.
      assert.match((await problemsOf('other.xodr'))[0].hint ?? '', /^correct the path, or add the folder/);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('says, in its hint, that a package the scenario references could not be read, with its line and why, and nothing of a readable one (issue 27: it was taken for a package holding nothing)', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', onRoad('road.xodr'));
    const root = temporaryWorkspace({
      'app/broken.mosc': 'PK\u0003\u0004 not a ZIP archive',
      'app/drive.mosc': await zip.generateAsync({ type: 'uint8array' }),
    });
    try {
      const app = path.join(root, 'app');
      const problemsOf = async (packageName: string, files: Record<string, string> = {}) => {
        for (const [name, text] of Object.entries(files)) fs.writeFileSync(path.join(app, name), text);
        const text = roadScenario({
          logicFile: 'road.xodr',
          groups: [outerGroup('Car', 'Ego', [{ file: packageName, groups: [{ name: 'Drive' }] }])],
        });
        const line = text.slice(0, text.indexOf('<ScenarioReference')).split('\n').length;
        const problems = semanticProblems(
          await analyzeDocument(
            diskRef(path.join(app, 'main.xosc')),
            parseXml(text),
            new CatalogLoader(new ScenarioStore({ root })),
            true,
            'esmini',
          ),
        ).filter((problem) => problem.code === 'road-file');
        return { problems, line };
      };
      const broken = await problemsOf('broken.mosc');
      assert.equal(broken.problems.length, 1);
      assert.match(
        broken.problems[0].hint ?? '',
        new RegExp(
          `; the package ${path.join(app, 'broken.mosc').replace(/[.\/]/g, '\\$&')} this file references on line ${broken.line} could not be read \\(.*broken\\.mosc is not a readable ZIP archive .*\\), so whether it holds 'road\\.xodr' is not known: repair it and check again$`,
        ),
      );
      // A readable package without the road: the usual hint alone.
      assert.equal((await problemsOf('drive.mosc')).problems[0].hint, roadFileWording('road.xodr', [app], 'error', false).hint);
      // The road found: nothing, whatever the package.
      assert.deepEqual((await problemsOf('broken.mosc', { 'road.xodr': STRAIGHT_ROAD })).problems, []);
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });

  it('for a road in a package stored inside another package, a hint whose commands, run as written, extract the road where esmini finds it (issue 27: unzip cannot read the inner package)', async function () {
    const zipped = async (files: Record<string, string | Uint8Array>) => {
      const zip = new JSZip();
      for (const [name, contents] of Object.entries(files)) zip.file(name, contents);
      return zip.generateAsync({ type: 'uint8array' });
    };
    const importing = roadScenario({
      logicFile: 'road.xodr',
      groups: [outerGroup('Car', 'Ego', [{ file: 'inner.mosc', groups: [{ name: 'Drive' }] }])],
    });
    const inner = await zipped({ 'main.xosc': onRoad('road.xodr'), 'road.xodr': STRAIGHT_ROAD });
    // One level (outer.mosc holds main.xosc and inner.mosc), and two (main.xosc and inner.mosc inside mid.mosc inside outer.mosc).
    const one = await zipped({ 'main.xosc': importing, 'inner.mosc': inner });
    const two = await zipped({
      'main.xosc': onRoad('road.xodr'),
      'sub/mid.mosc': await zipped({ 'main.xosc': importing, 'inner.mosc': inner }),
    });
    const root = temporaryWorkspace({ 'one/o u.mosc': one, 'two/outer.mosc': two });
    const unzip = spawnSync('unzip', ['-v']).status === 0;
    try {
      for (const [folder, main, stored] of [
        [
          'one',
          childRef(diskRef(path.join(root, 'one', 'o u.mosc')), 'main.xosc'),
          `'inner.mosc' this file references, stored inside ${path.join(root, 'one', 'o u.mosc')}`,
        ],
        [
          'two',
          childRef(childRef(diskRef(path.join(root, 'two', 'outer.mosc')), 'sub/mid.mosc'), 'main.xosc'),
          `'inner.mosc' inside 'sub/mid.mosc' this file references, stored inside ${path.join(root, 'two', 'outer.mosc')}`,
        ],
      ] as const) {
        const problemsOf = async () =>
          semanticProblems(
            await analyzeDocument(main, parseXml(importing), new CatalogLoader(new ScenarioStore({ root })), true, 'esmini'),
          ).filter((problem) => problem.code === 'road-file');
        const [problem] = await problemsOf();
        const hint = problem?.hint ?? '';
        assert.ok(hint.startsWith(`the package ${stored}, holds road.xodr, `), hint);
        const command = /\((?:[^(]*?): (cd .*)\), or correct the path$/.exec(hint)?.[1];
        assert.match(command ?? '', /&& unzip -j \d\/inner\.mosc road\.xodr -d /, hint);
        if (!unzip) continue;
        // mktemp -d makes its folder in TMPDIR: the workspace's, removed with it.
        fs.mkdirSync(path.join(root, 'tmp'), { recursive: true });
        const ran = spawnSync('sh', ['-c', command as string], {
          encoding: 'utf8',
          env: { ...process.env, TMPDIR: path.join(root, 'tmp') },
        });
        assert.equal(ran.status, 0, ran.stderr);
        assert.equal(fs.readFileSync(path.join(root, folder, 'road.xodr'), 'utf8'), STRAIGHT_ROAD);
        assert.deepEqual(await problemsOf(), [], `${folder}: the hint followed, the road is found`);
      }
      // A main on disk whose referenced package holds the road in a package stored in it.
      fs.mkdirSync(path.join(root, 'three'));
      fs.writeFileSync(path.join(root, 'three', 'outer.mosc'), one);
      const top = roadScenario({
        logicFile: 'road.xodr',
        groups: [outerGroup('Top', 'Ego', [{ file: 'outer.mosc', groups: [{ name: 'Car' }] }])],
      });
      const topProblems = async () =>
        semanticProblems(
          await analyzeDocument(
            diskRef(path.join(root, 'three', 'top.xosc')),
            parseXml(top),
            new CatalogLoader(new ScenarioStore({ root })),
            true,
            'esmini',
          ),
        ).filter((problem) => problem.code === 'road-file');
      const hint = (await topProblems())[0]?.hint ?? '';
      assert.ok(
        hint.startsWith(
          `the package ${path.join(root, 'three', 'outer.mosc')} this file references holds road.xodr in its package 'inner.mosc', `,
        ),
        hint,
      );
      const command = /\((?:[^(]*?): (cd .*)\), or correct the path$/.exec(hint)?.[1] ?? '';
      assert.match(command, /&& unzip -j 1\/inner\.mosc road\.xodr -d /, hint);
      if (unzip) {
        const ran = spawnSync('sh', ['-c', command], { encoding: 'utf8', env: { ...process.env, TMPDIR: path.join(root, 'tmp') } });
        assert.equal(ran.status, 0, ran.stderr);
        assert.deepEqual(await topProblems(), [], 'three: the hint followed, the road is found');
      }
      if (!unzip) this.skip();
    } finally {
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});
