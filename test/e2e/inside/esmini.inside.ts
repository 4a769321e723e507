import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { RunEsminiRequest, type RunEsminiResult } from '../../../common/src/protocol';
import { HARNESS_ENV } from '../titles';
import {
  api,
  type InsideTests,
  offersRequest,
  open,
  positionOf,
  replaceText,
  requireServerFeature,
  revertAndClose,
  TEST_MS,
  waitFor,
  waitForPage,
  workspaceRoot,
} from './helpers';
import { pageBoxes, pageShows, screenshot } from './harnessClient';

/** esmini as the test setup builds it beside the CLI under test (it may be absent). */
export function projectEsmini(): { repository: string; esmini: string } {
  const repository = path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
  return { repository, esmini: path.join(repository, '.cache', 'esmini', 'bin', 'esmini') };
}

/** esmini as the test setup builds it beside the CLI under test, and the shared road files; skips the test without them. */
export function esminiOrSkip(context: Mocha.Context): { repository: string; esmini: string; roads: string } {
  const { repository, esmini } = projectEsmini();
  const roads = path.resolve(repository, '..', 'shared', 'esmini', 'xodr');
  if (!fs.existsSync(esmini) || !fs.existsSync(roads)) {
    assert.ok(!process.env.M2S_REQUIRE_ESMINI, `M2S_REQUIRE_ESMINI is set, but ${esmini} or ${roads} is absent`);
    console.log(`skipped: ${esmini} or ${roads} is absent`);
    context.skip();
  }
  return { repository, esmini, roads };
}

/** esmini's cut-in.xosc laid out as esmini's own corpus is (xosc/ with its Catalogs beside xodr/), in the workspace's `folder`. */
export function esminiCutInFolder(repository: string, roads: string, folder: string): string {
  const corpus = path.resolve(repository, '..', 'shared', 'corpus', 'openscenario', 'esmini');
  fs.mkdirSync(path.join(folder, 'xosc', 'Catalogs', 'Vehicles'), { recursive: true });
  fs.mkdirSync(path.join(folder, 'xodr'), { recursive: true });
  fs.copyFileSync(path.join(corpus, 'cut-in.xosc'), path.join(folder, 'xosc', 'cut-in.xosc'));
  fs.copyFileSync(
    path.join(corpus, 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'),
    path.join(folder, 'xosc', 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'),
  );
  fs.copyFileSync(path.join(roads, 'e6mini.xodr'), path.join(folder, 'xodr', 'e6mini.xodr'));
  return path.join(folder, 'xosc', 'cut-in.xosc');
}

/** The Run lenses of a document, once the server's diagnostics have set how many there are. */
async function runLenses(uri: vscode.Uri, wanted: number): Promise<vscode.CodeLens[]> {
  return waitFor(`${wanted} Run lens(es)`, async () => {
    const found = await vscode.commands.executeCommand<vscode.CodeLens[]>('vscode.executeCodeLensProvider', uri, 100);
    const runs = found.filter((lens) => lens.command?.command.startsWith('modular2simple.runEsmini'));
    return runs.length === wanted ? runs : undefined;
  });
}

/** The language server's own diagnostics of a file (not esmini's from a run). */
function ownDiagnostics(uri: vscode.Uri): vscode.Diagnostic[] {
  return vscode.languages.getDiagnostics(uri).filter((diagnostic) => diagnostic.source !== 'esmini');
}

/** Run in esmini from the CodeLens: esmini's errors on the scenario's lines, the run in the bird's-eye view. */
export const esminiTests: InsideTests = {
  runEsmini: async function () {
    this.timeout(2 * TEST_MS);
    requireServerFeature(this, 'runEsmini', offersRequest(RunEsminiRequest));
    const { esmini, roads } = esminiOrSkip(this);
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
    await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
    await settings.update('roadPath', [roads], vscode.ConfigurationTarget.Workspace);
    await settings.update('duration', 5, vscode.ConfigurationTarget.Workspace);
    try {
      const simple = await open('lane_change.xosc');
      await replaceText(simple.document, 'dynamicsShape="linear" value="3"', 'dynamicsShape="wobbly" value="3"');
      const line = positionOf(simple.document, 'dynamicsShape="wobbly"').line;
      const main = await open('main.xosc');
      const lenses = await waitFor('the Run in esmini lens', async () => {
        const found = await vscode.commands.executeCommand<vscode.CodeLens[]>('vscode.executeCodeLensProvider', main.document.uri, 100);
        return found.find((lens) => lens.command?.command === 'modular2simple.runEsmini');
      });
      assert.equal(lenses.command?.title, '▶ Run in esmini');
      const esminiDiagnostics = () =>
        vscode.languages.getDiagnostics(simple.document.uri).filter((diagnostic) => diagnostic.source === 'esmini');
      const broken = await vscode.commands.executeCommand<RunEsminiResult>(
        lenses.command?.command ?? '',
        ...(lenses.command?.arguments ?? []),
      );
      // esmini stops at the unknown shape before it simulates anything: the run did not happen.
      assert.equal(broken?.outcome, 'failed', broken?.message);
      const [error] = esminiDiagnostics();
      assert.ok(error, 'no esmini diagnostic on the simple scenario');
      assert.equal(error.range.start.line, line);
      assert.equal(error.severity, vscode.DiagnosticSeverity.Error);
      assert.match(error.message, /wobbly/);
      await screenshot('run-esmini-error');

      await vscode.window.showTextDocument(simple.document);
      await vscode.commands.executeCommand('workbench.action.files.revert');
      const clean = await vscode.commands.executeCommand<RunEsminiResult>('modular2simple.runEsmini', main.document.uri);
      assert.equal(clean?.outcome, 'ok', clean?.message);
      assert.deepEqual(esminiDiagnostics(), [], 'the next run replaces the esmini diagnostics');
      assert.ok(clean?.csvFile && fs.existsSync(clean.csvFile));
      assert.equal(api().lastEsminiRun()?.result.csvFile, clean.csvFile);
      // Run it and see it: the trajectories of the four entities in the bird's-eye view.
      await waitFor("the run in the bird's-eye view", () => (api().birdsEye.stats?.trajectories === 4 ? true : undefined));
      await screenshot("bird's-eye view after Run in esmini");
    } finally {
      for (const key of ['path', 'roadPath', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
      await revertAndClose();
    }
  },

  runEsminiClean: async function () {
    this.timeout(2 * TEST_MS);
    requireServerFeature(this, 'runEsmini', offersRequest(RunEsminiRequest));
    const { repository, esmini, roads } = esminiOrSkip(this);
    // test/fixtures/modularRun as users lay it out (xosc/ beside xodr/), and in roadPath a different road under e6mini's name.
    const folder = path.join(workspaceRoot(), 'modularRun');
    for (const file of ['main.xosc', 'cut_in_group.xosc']) {
      fs.mkdirSync(path.join(folder, 'xosc'), { recursive: true });
      fs.copyFileSync(path.join(repository, 'test', 'fixtures', 'modularRun', 'xosc', file), path.join(folder, 'xosc', file));
    }
    const road = path.join(folder, 'xodr', 'e6mini.xodr');
    fs.mkdirSync(path.dirname(road), { recursive: true });
    fs.copyFileSync(path.join(roads, 'e6mini.xodr'), road);
    fs.mkdirSync(path.join(folder, 'roads'), { recursive: true });
    fs.copyFileSync(path.join(roads, 'straight_500m.xodr'), path.join(folder, 'roads', 'e6mini.xodr'));
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
    await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
    await settings.update('roadPath', ['modularRun/roads'], vscode.ConfigurationTarget.Workspace);
    await settings.update('duration', 6, vscode.ConfigurationTarget.Workspace);
    try {
      const main = await open('modularRun/xosc/main.xosc');
      const lens = await waitFor('the Run in esmini lens', async () => {
        const found = await vscode.commands.executeCommand<vscode.CodeLens[]>('vscode.executeCodeLensProvider', main.document.uri, 100);
        return found.find((candidate) => candidate.command?.command === 'modular2simple.runEsmini');
      });
      const result = await vscode.commands.executeCommand<RunEsminiResult>(lens.command?.command ?? '', ...(lens.command?.arguments ?? []));
      assert.equal(result?.outcome, 'ok', result?.message);
      assert.match(result.message, /^esmini: 0 errors, 0 warnings; 6\.00 s simulated/);
      assert.deepEqual(result.problems, []);
      // esmini's remarks about its road (rail-poles) and 3D models are information, not problems of the scenario.
      assert.ok(
        result.remarks?.some((remark) => remark.message.startsWith('Unsupported object type: rail-pole')),
        JSON.stringify(result.remarks),
      );
      const esminiDiagnostics = vscode.languages
        .getDiagnostics()
        .flatMap(([, diagnostics]) => diagnostics.filter((diagnostic) => diagnostic.source === 'esmini'));
      assert.deepEqual(esminiDiagnostics, [], 'no esmini diagnostic anywhere');
      // What a person sees: the information toast, and no error toast.
      await waitForPage('esmini: 0 errors, 0 warnings', '.notifications-toasts');
      assert.ok(!(await pageShows('Run in esmini:', '.notifications-toasts')), 'an error toast is shown');
      // The run and the picture: one road file, the one beside the scenario, drawn with the run's trajectories.
      assert.equal(result.roadFile?.loaded, road, `esmini loaded ${result.roadFile?.loaded}`);
      const view = api().birdsEye;
      await waitFor("the run in the bird's-eye view", () =>
        view.stats?.trajectories === 2 && view.scene?.uri === main.document.uri.toString() ? true : undefined,
      );
      assert.equal(view.scene?.roadFile?.resolved, road);
      assert.deepEqual(view.scene?.problems, [], 'every entity is on the road drawn');
      await waitForPage(`road ${road}`);
      assert.ok(!(await pageShows('the run loaded the road file')), 'the view says the run loaded another road');
      // The run named by what ran, not by its file (trajectories.csv).
      await waitForPage('run: esmini run of main.xosc, ');
      // The run ends at its limit, as the message says (esmini logs the step after it too).
      await waitForPage(`/ ${result.duration.toFixed(2)} s`);
      assert.ok(!(await pageShows(`/ ${(result.duration + result.timeStep).toFixed(2)} s`)), 'the view runs past the limit');
      await screenshot("the picture's road is the run's road");
    } finally {
      for (const key of ['path', 'roadPath', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      fs.rmSync(folder, { recursive: true, force: true });
    }
  },
  runEsminiCutIn: async function () {
    this.timeout(2 * TEST_MS);
    requireServerFeature(this, 'runEsmini', offersRequest(RunEsminiRequest));
    const { repository, esmini, roads } = esminiOrSkip(this);
    const folder = path.join(workspaceRoot(), 'esminiCutIn');
    esminiCutInFolder(repository, roads, folder);
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
    // No roadPath: the road and catalogs resolve from the scenario's folder, as esmini's corpus lays them out.
    await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
    await settings.update('duration', 5, vscode.ConfigurationTarget.Workspace);
    try {
      const scenario = await open('esminiCutIn/xosc/cut-in.xosc');
      const uri = scenario.document.uri;
      // esmini's text gluing in ${BrakeCondition_HWT + _ + $HeadwayTime_Brake}: a warning by the severity policy, never an error.
      const glued = await waitFor('the warning on the glued expression', () =>
        ownDiagnostics(uri).find((diagnostic) => /glues it/.test(diagnostic.message)),
      );
      assert.equal(glued.severity, vscode.DiagnosticSeverity.Warning, glued.message);
      assert.deepEqual(
        ownDiagnostics(uri)
          .filter((diagnostic) => diagnostic.severity === vscode.DiagnosticSeverity.Error)
          .map((diagnostic) => diagnostic.message),
        [],
      );
      const [lens] = await runLenses(uri, 1);
      assert.equal(lens.command?.title, '▶ Run in esmini', 'no Run Anyway on a scenario without errors');
      const result = await vscode.commands.executeCommand<RunEsminiResult>(lens.command?.command ?? '', ...(lens.command?.arguments ?? []));
      assert.equal(result?.outcome, 'ok', result?.message);
      assert.match(result.message, /^esmini: 0 errors, 0 warnings; 5\.00 s simulated/);
      assert.deepEqual(result.problems, []);
      assert.equal(result.forcible, undefined);
      assert.deepEqual(
        result.flattenProblems.filter((problem) => problem.severity === 'error'),
        [],
      );
      assert.ok(
        result.flattenProblems.some((problem) => problem.severity === 'warning' && /glues it/.test(problem.message)),
        JSON.stringify(result.flattenProblems),
      );
      assert.equal(result.roadFile?.loaded, path.join(folder, 'xodr', 'e6mini.xodr'), `esmini loaded ${result.roadFile?.loaded}`);
      assert.ok(result.csvFile && fs.existsSync(result.csvFile));
      await waitForPage('esmini: 0 errors, 0 warnings', '.notifications-toasts');
      assert.ok(!(await pageShows('Run in esmini:', '.notifications-toasts')), 'an error toast is shown');
      assert.ok(!(await pageShows('nothing was run', '.notifications-toasts')), 'a refusal is shown');
      await screenshot("esmini's cut-in.xosc run in esmini");
    } finally {
      for (const key of ['path', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      // Later tests look for roads in the workspace (New Modular Scenario offers each e6mini.xodr it finds).
      fs.rmSync(folder, { recursive: true, force: true });
    }
  },

  runEsminiAnyway: async function () {
    this.timeout(2 * TEST_MS);
    requireServerFeature(this, 'runEsmini', offersRequest(RunEsminiRequest));
    const { repository, esmini, roads } = esminiOrSkip(this);
    const folder = path.join(workspaceRoot(), 'esminiAnyway');
    const cutIn = esminiCutInFolder(repository, roads, folder);
    // A double parameter whose value is no number: an error by any policy, which esmini never reads.
    const text = fs.readFileSync(cutIn, 'utf8');
    const broken = text.replace(
      '<ParameterDeclarations>',
      '<ParameterDeclarations>\n      <ParameterDeclaration name="Pace" parameterType="double" value="fast"/>',
    );
    assert.notEqual(broken, text, 'cut-in.xosc has root ParameterDeclarations');
    const file = path.join(folder, 'xosc', 'anyway.xosc');
    fs.writeFileSync(file, broken);
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
    await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
    await settings.update('duration', 3, vscode.ConfigurationTarget.Workspace);
    try {
      const scenario = await open('esminiAnyway/xosc/anyway.xosc');
      const uri = scenario.document.uri;
      const error = await waitFor('the error on the parameter', () =>
        ownDiagnostics(uri).find((diagnostic) => diagnostic.severity === vscode.DiagnosticSeverity.Error),
      );
      assert.match(error.message, /'fast' is not a double/);
      const lenses = await runLenses(uri, 2);
      assert.deepEqual(
        lenses.map((lens) => lens.command?.title),
        ['▶ Run in esmini', '▶ Run Anyway (1 error)'],
      );
      assert.equal(lenses[1].command?.command, 'modular2simple.runEsminiAnyway');
      // The plain run is refused, and says Run Anyway would run it.
      const refused = await vscode.commands.executeCommand<RunEsminiResult>(
        lenses[0].command?.command ?? '',
        ...(lenses[0].command?.arguments ?? []),
      );
      assert.equal(refused?.outcome, 'not-flattened', refused?.message);
      assert.equal(refused.forcible, true);
      await waitForPage('Run Anyway', '.notifications-toasts');
      await screenshot('Run in esmini refused, offering Run Anyway');
      await vscode.commands.executeCommand('notifications.clearAll');

      const forced = await vscode.commands.executeCommand<RunEsminiResult>(
        lenses[1].command?.command ?? '',
        ...(lenses[1].command?.arguments ?? []),
      );
      assert.equal(forced?.outcome, 'ok', forced?.message);
      assert.match(
        forced.message,
        /3\.00 s simulated: stopped at the 3 s limit set by the modular2simple\.esmini\.duration setting, before the scenario ended by itself.*\(run anyway despite 1 error in the scenario\)$/,
      );
      assert.ok(
        forced.flattenProblems.some((problem) => problem.severity === 'error' && /'fast' is not a double/.test(problem.message)),
        JSON.stringify(forced.flattenProblems),
      );
      assert.ok(forced.csvFile && fs.existsSync(forced.csvFile));
      // What the client reported to the user (the message its information toast shows, kept in the screenshot below).
      assert.match(api().lastEsminiRun()?.result.message ?? '', /\(run anyway despite 1 error in the scenario\)$/);
      // The toasts as the result first shows among them, read at once: the run's progress (with its Cancel) has gone.
      const toasts = await waitFor('the result among the toasts', async () => {
        const shown = (await pageBoxes('.notifications-toasts')).map((box) => box.text).join('\n');
        return shown.includes('(run anyway despite 1 error in the scenario)') ? shown : undefined;
      });
      assert.ok(!toasts.includes('Running anyway.xosc in esmini'), `the run's progress is still shown beside its result:\n${toasts}`);
      // The notification centre keeps what the toast showed: an information toast hides itself after a while, and on a
      // busy machine it had gone before the page was read.
      await vscode.commands.executeCommand('notifications.showList');
      try {
        await waitForPage('(run anyway despite 1 error in the scenario)', '.notifications-center');
        assert.ok(!(await pageShows('Running anyway.xosc in esmini', '.notifications-center')), "the run's progress is still listed");
        assert.ok(!(await pageShows('Run in esmini:', '.notifications-center')), 'an error notification is shown');
        await screenshot('Run Anyway ran the scenario despite its error');
      } finally {
        await vscode.commands.executeCommand('notifications.hideList');
      }
    } finally {
      for (const key of ['path', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      // Later tests look for roads in the workspace (New Modular Scenario offers each e6mini.xodr it finds).
      fs.rmSync(folder, { recursive: true, force: true });
    }
  },
};
