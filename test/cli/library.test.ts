import { strict as assert } from 'node:assert';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { builtInLibraryFolder } from '../../server/src/libraries';
import { runCli } from '../support/fixtures';
import { temporaryFolder } from '../support/temporaryDirectory';

/** `modular2simple library` and `library:NAME` in a main file, over the program itself (issue 28, item 6). */
describe('cli: library list, show, path and library:NAME', function () {
  this.timeout(120_000);
  const builtIn = builtInLibraryFolder() ?? '';
  let root: string;
  let userLibrary: string;

  before(() => {
    root = temporaryFolder('m2s-library-cli-');
    userLibrary = path.join(root, 'mine');
    fs.mkdirSync(userLibrary);
    // The user's own cut-in, its gap 33 m by default: it hides the built-in one.
    fs.writeFileSync(
      path.join(userLibrary, 'cut-in.xosc'),
      fs
        .readFileSync(path.join(builtIn, 'cut-in.xosc'), 'utf8')
        .replace('value="20" freespace="true"', 'value="33" freespace="true"')
        .replace('<LogicFile filepath="roads/', `<LogicFile filepath="${builtIn}/roads/`),
    );
    fs.writeFileSync(
      path.join(userLibrary, 'broken.xosc'),
      '<?xml version="1.0"?>\n<!-- library module\nname: broken\n-->\n<OpenSCENARIO>\n<FileHeader',
    );
    fs.writeFileSync(path.join(userLibrary, 'plain.xosc'), '<?xml version="1.0"?>\n<OpenSCENARIO/>\n');
    const main = fs
      .readFileSync(path.join(builtIn, 'examples', 'cut-in.xosc'), 'utf8')
      .replace(/<ParameterReference key="RelativeDistanceCondition.value"[^>]*>\n\s*/, '');
    fs.writeFileSync(path.join(root, 'main.xosc'), main.replace('filepath="../roads/', `filepath="${builtIn}/roads/`));
    fs.writeFileSync(path.join(root, 'misspelt.xosc'), main.replace('library:cut-in', 'library:cutin'));
  });

  it('list --format json names each module with its file, example main, picture and doc', () => {
    const run = runCli(['library', 'list', '--format', 'json'], { cwd: root, env: { SCENARIO_LIBRARY_PATH: '' } });
    assert.equal(run.status, 0, run.stderr);
    const listed = JSON.parse(run.stdout) as {
      modules: { name: string; file: string; example: string; picture: string; doc: string; reference: string }[];
    };
    const cutIn = listed.modules.find((module) => module.name === 'cut-in');
    assert.ok(cutIn, run.stdout);
    assert.equal(cutIn.file, path.join(builtIn, 'cut-in.xosc'));
    assert.equal(cutIn.example, path.join(builtIn, 'examples', 'cut-in.xosc'));
    assert.equal(cutIn.picture, path.join(builtIn, 'pictures', 'cut-in.svg'));
    assert.equal(cutIn.reference, 'library:cut-in');
    assert.match(cutIn.doc, /changes into the ego's lane/);
    for (const module of listed.modules) assert.ok(fs.existsSync(module.example), module.name);
  });

  it('show NAME gives the doc, every key with its unit, range and default, the example and the picture', () => {
    const run = runCli(['library', 'show', 'cut-in'], { cwd: root, env: { SCENARIO_LIBRARY_PATH: '' } });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /^library:cut-in: Cut-in \(Vehicles ahead\)/);
    assert.match(run.stdout, /RelativeDistanceCondition\.value\s+gap: .* \(default 20 m, 2\.\.100 m\)/);
    assert.match(run.stdout, /LaneChangeActionDynamics\.value\s+laneChangeTime: .* \(default 3 s, 0\.5\.\.10 s\)/);
    assert.match(run.stdout, /picture: .*pictures\/cut-in\.svg/);
  });

  it('a misspelt name: exit 1 and "did you mean"', () => {
    const run = runCli(['library', 'show', 'cutin'], { cwd: root, env: { SCENARIO_LIBRARY_PATH: '' } });
    assert.equal(run.status, 1);
    assert.match(run.stderr, /no library module 'cutin': did you mean 'cut-in'\?/);
  });

  it("path lists the folders in the order they are searched: the user's, SCENARIO_LIBRARY_PATH's, the built-in one", () => {
    const other = path.join(root, 'other');
    const run = runCli(['library', 'path', '--library', userLibrary], { cwd: root, env: { SCENARIO_LIBRARY_PATH: other } });
    assert.equal(run.status, 0, run.stderr);
    assert.deepEqual(run.stdout.trim().split('\n'), [userLibrary, other, builtIn]);
  });

  it("a folder that does not exist and broken files are each named (file and line); the rest is listed; the user's module hides the built-in one, and says so", () => {
    const missing = path.join(root, 'no-such-library');
    const run = runCli(['library', 'list', '--library', missing, '--library', userLibrary], {
      cwd: root,
      env: { SCENARIO_LIBRARY_PATH: '' },
    });
    assert.equal(run.status, 1);
    assert.match(run.stderr, /^no-such-library: error: the user library folder does not exist/m);
    assert.match(run.stderr, /broken\.xosc:\d+: error: /);
    assert.match(run.stderr, /plain\.xosc:1: error: no doc block/);
    assert.doesNotMatch(run.stderr, /internal error|\n\s+at /);
    assert.match(run.stdout, /cut-in +Cut-in: .*\(hides .*library\/cut-in\.xosc\)/);
    assert.match(run.stdout, /mine\/cut-in\.xosc; example \(none\)/);
    assert.match(run.stdout, /lead-brake/);
    const shown = runCli(['library', 'show', 'cut-in', '--library', userLibrary], { cwd: root, env: { SCENARIO_LIBRARY_PATH: '' } });
    assert.match(shown.stdout, /file: .*mine\/cut-in\.xosc \(user library\)\n {2}hides: .*library\/cut-in\.xosc/);
    assert.match(shown.stdout, /default 33 m/);
  });

  it("library:NAME in a main flattens from the built-in library, or from the user's when it holds the name", () => {
    const builtInRun = runCli(['flatten', 'main.xosc'], { cwd: root, env: { SCENARIO_LIBRARY_PATH: '' } });
    assert.equal(builtInRun.status, 0, builtInRun.stderr);
    assert.match(builtInRun.stdout, /<RelativeDistanceCondition entityRef="ego" relativeDistanceType="longitudinal" value="20"/);
    assert.doesNotMatch(builtInRun.stdout, /library:|parameterAttributes/);
    const userRun = runCli(['flatten', 'main.xosc'], { cwd: root, env: { SCENARIO_LIBRARY_PATH: userLibrary } });
    assert.equal(userRun.status, 0, userRun.stderr);
    assert.match(userRun.stdout, /value="33"/);
  });

  it('library:NAME that no library holds is an error naming the folders searched and the closest module', () => {
    const run = runCli(['check', 'misspelt.xosc'], { cwd: root, env: { SCENARIO_LIBRARY_PATH: '' } });
    assert.equal(run.status, 1);
    assert.match(
      run.stderr,
      new RegExp(`misspelt\\.xosc:\\d+:\\d+: error: cannot find 'library:cutin'; searched ${builtIn} \\(built-in library\\)`),
    );
    assert.match(run.stderr, /did you mean 'library:cut-in'\?/);
  });
});
