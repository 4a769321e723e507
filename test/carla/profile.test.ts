import { strict as assert } from 'node:assert';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { harnessVerdicts, HarnessVerdict, requireCarlaHarness } from '../support/carla';
import { esminiCatalogs, esminiRoads } from '../support/esmini';
import { runCli } from '../support/fixtures';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { libraryDir, requireCorpus } from '../support/paths';

/*
 * check --simulator carla against ScenarioRunner's own loader (../shared/carla/check.py): every file the
 * harness refuses gets a CARLA error, and no file it builds gets an error at all.
 */

interface CheckedProblem {
  file: string;
  severity: string;
  code: string;
  message: string;
}

/** `check --simulator carla --format json` over the files, in one run; the problems by file. */
function checkForCarla(files: string[], release: '0.9.15' | '0.9.16'): Map<string, CheckedProblem[]> {
  const run = runCli(['check', '--simulator', 'carla', '--carla', release, '--format', 'json', ...files]);
  assert.ok(run.status === 0 || run.status === 1, `check exited ${run.status}: ${run.stderr.slice(-2000)}`);
  const problems = (JSON.parse(run.stdout) as { problems: CheckedProblem[] }).problems;
  const byFile = new Map<string, CheckedProblem[]>();
  for (const problem of problems) byFile.set(path.resolve(problem.file), [...(byFile.get(path.resolve(problem.file)) ?? []), problem]);
  return byFile;
}

/** The disagreements of the profile with the harness: a refused file without a CARLA error, a built file with any error. */
function disagreements(verdicts: Map<string, HarnessVerdict>, checked: Map<string, CheckedProblem[]>): string[] {
  const found: string[] = [];
  for (const [file, verdict] of verdicts) {
    const errors = (checked.get(file) ?? []).filter((problem) => problem.severity === 'error');
    if (verdict.status === 'OK' && errors.length > 0)
      found.push(`${file}: ScenarioRunner builds it, yet ${errors.map((problem) => problem.message).join(' | ')}`);
    if (verdict.status === 'FAIL' && !errors.some((problem) => problem.code === 'simulator'))
      found.push(`${file}: ScenarioRunner refuses it (${verdict.stage}: ${verdict.reason}), yet no CARLA error`);
  }
  return found;
}

function scenarioFiles(folder: string): string[] {
  return fs
    .readdirSync(folder)
    .filter((name) => name.endsWith('.xosc') && !/Catalog\.xosc$/.test(name))
    .map((name) => path.join(folder, name));
}

describe('check --simulator carla agrees with ScenarioRunner', function () {
  this.timeout(600_000);
  let workspace: string;
  let esminiFiles: string[];
  const runnerFiles = () => scenarioFiles(path.join(openscenarioDir, 'scenario_runner'));
  const libraryResults = () =>
    fs
      .readdirSync(libraryDir)
      .filter((name) => name.startsWith('modular_'))
      .map((name) => path.join(libraryDir, name, 'result.xosc'));

  before(function () {
    requireCorpus(this);
    requireCarlaHarness(this);
    // esmini's samples as esmini lays them out (xosc/ with its Catalogs beside xodr/), so their roads and catalogs resolve.
    workspace = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-carla-profile-'));
    const xosc = path.join(workspace, 'xosc');
    fs.mkdirSync(xosc);
    fs.cpSync(esminiCatalogs, path.join(xosc, 'Catalogs'), { recursive: true });
    fs.symlinkSync(esminiRoads, path.join(workspace, 'xodr'));
    esminiFiles = scenarioFiles(path.join(openscenarioDir, 'esmini')).map((file) => {
      const copy = path.join(xosc, path.basename(file));
      fs.copyFileSync(file, copy);
      return copy;
    });
  });

  after(() => {
    if (workspace) fs.rmSync(workspace, { recursive: true, force: true });
  });

  it('0.9.16: esmini samples, ScenarioRunner examples, the paper library: refused ones get an error, built ones none', async () => {
    const files = [...esminiFiles, ...runnerFiles(), ...libraryResults()];
    const verdicts = new Map([...(await harnessVerdicts(files))].filter(([, verdict]) => verdict.status !== 'SKIP'));
    assert.ok(verdicts.size >= 100, `the harness judged ${verdicts.size} files`);
    const built = [...verdicts.values()].filter((verdict) => verdict.status === 'OK').length;
    assert.ok(built >= 10 && built < verdicts.size, `${built} of ${verdicts.size} built: both kinds are checked`);
    assert.deepEqual(disagreements(verdicts, checkForCarla([...verdicts.keys()], '0.9.16')), []);
  });

  it('0.9.15 (the harness with --fix-sr-bugs): the route actions build, and the profile reports no error on them', async () => {
    const files = [...runnerFiles(), ...libraryResults()];
    const verdicts = new Map([...(await harnessVerdicts(files, { fixSrBugs: true }))].filter(([, verdict]) => verdict.status !== 'SKIP'));
    assert.ok([...verdicts.values()].filter((verdict) => verdict.status === 'OK').length >= 40);
    assert.deepEqual(disagreements(verdicts, checkForCarla([...verdicts.keys()], '0.9.15')), []);
  });
});
