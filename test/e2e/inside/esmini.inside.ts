import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { RunEsminiRequest, type RunEsminiResult } from '../../../common/src/protocol';
import { HARNESS_ENV } from '../titles';
import { api, type InsideTests, offersRequest, open, positionOf, replaceText, requireServerFeature, revertAndClose, waitFor } from './helpers';
import { screenshot } from './harnessClient';

/** Run in esmini from the CodeLens: esmini's errors on the scenario's lines, the run in the bird's-eye view. */
export const esminiTests: InsideTests = {
  runEsmini: async function () {
    this.timeout(120_000);
    requireServerFeature(this, 'runEsmini', offersRequest(RunEsminiRequest));
    // esmini as the test setup builds it beside the CLI under test, and the shared road files.
    const repository = path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
    const esmini = path.join(repository, '.cache', 'esmini', 'bin', 'esmini');
    const roads = path.resolve(repository, '..', 'shared', 'esmini', 'xodr');
    if (!fs.existsSync(esmini) || !fs.existsSync(roads)) {
      assert.ok(!process.env.M2S_REQUIRE_ESMINI, `M2S_REQUIRE_ESMINI is set, but ${esmini} or ${roads} is absent`);
      console.log(`skipped: ${esmini} or ${roads} is absent`);
      this.skip();
    }
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
};
