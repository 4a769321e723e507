import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { RunEsminiRequest, type RunEsminiResult } from '../../../common/src/protocol';
import { HARNESS_ENV } from '../titles';
import { api, type InsideTests, offersRequest, open, positionOf, replaceText, requireServerFeature, revertAndClose, waitFor, workspaceRoot } from './helpers';
import { pageShows, screenshot } from './harnessClient';

/** esmini as the test setup builds it beside the CLI under test, and the shared road files; skips the test without them. */
function esminiOrSkip(context: Mocha.Context): { repository: string; esmini: string; roads: string } {
  const repository = path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
  const esmini = path.join(repository, '.cache', 'esmini', 'bin', 'esmini');
  const roads = path.resolve(repository, '..', 'shared', 'esmini', 'xodr');
  if (!fs.existsSync(esmini) || !fs.existsSync(roads)) {
    assert.ok(!process.env.M2S_REQUIRE_ESMINI, `M2S_REQUIRE_ESMINI is set, but ${esmini} or ${roads} is absent`);
    console.log(`skipped: ${esmini} or ${roads} is absent`);
    context.skip();
  }
  return { repository, esmini, roads };
}

/** Run in esmini from the CodeLens: esmini's errors on the scenario's lines, the run in the bird's-eye view. */
export const esminiTests: InsideTests = {
  runEsmini: async function () {
    this.timeout(120_000);
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
      const esminiDiagnostics = () => vscode.languages.getDiagnostics(simple.document.uri).filter((diagnostic) => diagnostic.source === 'esmini');
      const broken = await vscode.commands.executeCommand<RunEsminiResult>(lenses.command?.command ?? '', ...(lenses.command?.arguments ?? []));
      assert.equal(broken?.outcome, 'errors', broken?.message);
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
    this.timeout(120_000);
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
      assert.ok(result.remarks?.some((remark) => remark.message.startsWith('Unsupported object type: rail-pole')), JSON.stringify(result.remarks));
      const esminiDiagnostics = vscode.languages.getDiagnostics().flatMap(([, diagnostics]) => diagnostics.filter((diagnostic) => diagnostic.source === 'esmini'));
      assert.deepEqual(esminiDiagnostics, [], 'no esmini diagnostic anywhere');
      // What a person sees: the information toast, and no error toast.
      await waitFor('the information toast', () => pageShows('esmini: 0 errors, 0 warnings', '.notifications-toasts'), 10_000);
      assert.ok(!(await pageShows('Run in esmini:', '.notifications-toasts')), 'an error toast is shown');
      // The run and the picture: one road file, the one beside the scenario, drawn with the run's trajectories.
      assert.equal(result.roadFile?.loaded, road, `esmini loaded ${result.roadFile?.loaded}`);
      const view = api().birdsEye;
      await waitFor("the run in the bird's-eye view", () => (view.stats?.trajectories === 2 && view.scene?.uri === main.document.uri.toString() ? true : undefined), 30_000);
      assert.equal(view.scene?.roadFile?.resolved, road);
      assert.deepEqual(view.scene?.problems, [], 'every entity is on the road drawn');
      await waitFor('the road file named in the view', () => pageShows(`road ${road}`));
      assert.ok(!(await pageShows('the run loaded the road file')), 'the view says the run loaded another road');
      await screenshot("the picture's road is the run's road");
    } finally {
      for (const key of ['path', 'roadPath', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      fs.rmSync(folder, { recursive: true, force: true });
    }
  },
};
