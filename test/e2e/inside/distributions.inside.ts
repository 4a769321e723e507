import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { HARNESS_ENV } from '../titles';
import { screenshot } from './harnessClient';
import { api, open, TEST_MS, waitFor, workspaceRoot } from './helpers';
import type { InsideTests } from './helpers';

/** esmini's cut-in_parameter_set.xosc and what it needs, copied into the workspace's distributions/ (variations/ holds the Variations view's batch); skips the test without the shared corpus. */
function copyCutInDistribution(context: Mocha.Context): { repository: string; folder: string } {
  const repository = path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
  const corpus = path.resolve(repository, '..', 'shared', 'corpus', 'openscenario', 'esmini');
  if (!fs.existsSync(path.join(corpus, 'cut-in_parameter_set.xosc'))) {
    console.log(`skipped: ${corpus} is absent`);
    context.skip();
  }
  const folder = path.join(workspaceRoot(), 'distributions', 'xosc');
  fs.mkdirSync(path.join(folder, 'Catalogs'), { recursive: true });
  for (const file of ['cut-in_parameter_set.xosc', 'cut-in.xosc']) fs.copyFileSync(path.join(corpus, file), path.join(folder, file));
  fs.cpSync(path.join(corpus, 'Catalogs', 'Vehicles'), path.join(folder, 'Catalogs', 'Vehicles'), { recursive: true });
  return { repository, folder };
}

/** A distribution file (issue 20): the number of concrete scenarios above it, as `vary --count` gives it. */
export const distributionTests: InsideTests = {
  distributionLens: async function () {
    this.timeout(2 * TEST_MS);
    const copied = copyCutInDistribution(this);
    const { folder } = copied;
    try {
      const distribution = await open('distributions/xosc/cut-in_parameter_set.xosc');
      const cliPath = process.env[HARNESS_ENV.cli] ?? '';
      const count = execFileSync(process.execPath, [cliPath, 'vary', path.join(folder, 'cut-in_parameter_set.xosc'), '--count'], {
        encoding: 'utf8',
        env: { ...process.env, ELECTRON_RUN_AS_NODE: '1' },
      }).trim();
      assert.equal(count, '12');
      const lenses = await waitFor('the count lens', async () => {
        const found = await vscode.commands.executeCommand<vscode.CodeLens[]>(
          'vscode.executeCodeLensProvider',
          distribution.document.uri,
          100,
        );
        return found.some((lens) => lens.command?.command === 'modular2simple.runVariations') ? found : undefined;
      });
      assert.deepEqual(
        lenses.map((lens) => lens.command?.title),
        ['▶ Run in esmini', `${count} concrete scenarios`, 'Run Variations'],
      );
      const errors = vscode.languages
        .getDiagnostics(distribution.document.uri)
        .filter((diagnostic) => diagnostic.severity === vscode.DiagnosticSeverity.Error);
      assert.deepEqual(
        errors.map((diagnostic) => diagnostic.message),
        [],
      );
      await screenshot('the count of concrete scenarios above a distribution');

      // Run Variations from its lens: a batch of the 12 beside the file, results.csv opened (no Variations view here).
      const { repository } = copied;
      const esmini = path.join(repository, '.cache', 'esmini', 'bin', 'esmini');
      const roads = path.resolve(repository, '..', 'shared', 'esmini', 'xodr');
      if (!fs.existsSync(esmini) || !fs.existsSync(roads)) return;
      const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
      await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
      await settings.update('roadPath', [roads], vscode.ConfigurationTarget.Workspace);
      await settings.update('duration', 2, vscode.ConfigurationTarget.Workspace);
      try {
        const run = lenses.find((lens) => lens.command?.command === 'modular2simple.runVariations');
        const outcome = await vscode.commands.executeCommand<{ exitCode: number | null; resultsFolder: string }>(
          run?.command?.command ?? '',
          ...(run?.command?.arguments ?? []),
        );
        assert.equal(outcome?.exitCode, 0);
        assert.equal(outcome.resultsFolder, path.join(folder, 'cut-in_parameter_set.results'));
        const rows = fs.readFileSync(path.join(outcome.resultsFolder, 'results.csv'), 'utf8').trim().split('\n');
        assert.equal(rows.length, 13, rows.join('\n'));
        // The Variations view shows the results (results.csv in an editor where the view is not registered).
        await waitFor('the results shown', () =>
          vscode.window.tabGroups.all.some((group) =>
            group.tabs.some((tab) => tab.label.startsWith('Variations') || tab.label === 'results.csv'),
          ),
        );
        await screenshot('Run Variations showed its results');

        // ▶ Run in esmini on the distribution runs its concrete scenario 0, drawn in the bird's-eye view on the ScenarioFile's road.
        const runLens = lenses.find((lens) => lens.command?.title === '▶ Run in esmini');
        await vscode.commands.executeCommand(runLens?.command?.command ?? '', ...(runLens?.command?.arguments ?? []));
        const view = api().birdsEye;
        await waitFor("the run of concrete scenario 0 on cut-in.xosc's road", () =>
          /e6mini\.xodr$/.test(view.scene?.roadFile?.resolved ?? '') && (view.stats?.trajectories ?? 0) === 2 ? true : undefined,
        );
        await screenshot("Run in esmini on a distribution: its concrete scenario 0 on the ScenarioFile's road");
      } finally {
        for (const key of ['path', 'roadPath', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
      }
    } finally {
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      fs.rmSync(path.dirname(folder), { recursive: true, force: true });
    }
  },
};
