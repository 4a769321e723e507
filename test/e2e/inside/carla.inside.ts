import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { CheckInScenarioRunnerRequest, ExportForCarlaRequest } from '../../../common/src/protocol';
import { HARNESS_ENV } from '../titles';
import { pageShows, runFromPalette, screenshot, typeText } from './harnessClient';
import {
  acceptSaveDialog,
  type InsideTests,
  offersRequest,
  open,
  positionOf,
  requireServerFeature,
  revertAndClose,
  waitFor,
  workspaceRoot,
} from './helpers';

const SOURCE = 'Export for CARLA';

function exportLosses(uri: vscode.Uri): vscode.Diagnostic[] {
  return vscode.languages.getDiagnostics(uri).filter((diagnostic) => diagnostic.source === SOURCE);
}

/**
 * test/fixtures/modularRun laid out as esmini's corpus is (xosc/ beside xodr/, esmini's catalog names such as
 * car_white), in the workspace's `carlaExport/`; undefined when esmini's e6mini road is not beside the repository.
 */
function carlaExportFolder(): string | undefined {
  const repository = path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
  const road = path.resolve(repository, '..', 'shared', 'esmini', 'xodr', 'e6mini.xodr');
  if (!fs.existsSync(road)) return undefined;
  const folder = path.join(workspaceRoot(), 'carlaExport');
  fs.mkdirSync(path.join(folder, 'xosc'), { recursive: true });
  fs.mkdirSync(path.join(folder, 'xodr'), { recursive: true });
  for (const file of ['main.xosc', 'cut_in_group.xosc'])
    fs.copyFileSync(path.join(repository, 'test', 'fixtures', 'modularRun', 'xosc', file), path.join(folder, 'xosc', file));
  fs.copyFileSync(road, path.join(folder, 'xodr', 'e6mini.xodr'));
  return folder;
}

/** The repository the harness runs from (its dist/cli.js is the CLI the harness names). */
function repositoryRoot(): string {
  return path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
}

/**
 * ScenarioRunner 0.9.16 as ../shared/carla's harness unpacks it into the repository's .cache/carla, and a Python
 * with its requirements (py_trees 0.8.3 and the XSD libraries it pins on the path, as test/support/carla.ts does):
 * what a user names in the settings. Undefined when the harness was not set up.
 */
function scenarioRunnerSetup(folder: string): { scenarioRunner: string; python: string } | undefined {
  const cache = path.join(repositoryRoot(), '.cache', 'carla');
  const scenarioRunner = path.join(cache, 'scenario_runner');
  const libraries = ['py_trees-0.8.3', 'xmlschema-1.0.18', 'elementpath-1.3.3'].map((name) => path.join(cache, name));
  if (![scenarioRunner, ...libraries].every((each) => fs.existsSync(each))) return undefined;
  const python = path.join(folder, 'python-scenario-runner');
  fs.writeFileSync(python, `#!/bin/sh\nPYTHONPATH='${libraries.join(':')}' exec /usr/bin/python3 "$@"\n`, { mode: 0o755 });
  return { scenarioRunner, python };
}

/** *Export for CARLA…* from the palette: the file written, its losses as diagnostics on the simple scenario's lines. */
export const carlaTests: InsideTests = {
  carlaCheck: async function () {
    this.timeout(120_000);
    requireServerFeature(this, 'checkInScenarioRunner', offersRequest(CheckInScenarioRunnerRequest));
    const folder = path.join(workspaceRoot(), '.carla-check');
    fs.mkdirSync(folder, { recursive: true });
    const setup = scenarioRunnerSetup(folder);
    if (!setup) {
      fs.rmSync(folder, { recursive: true, force: true });
      assert.ok(!process.env.M2S_REQUIRE_CARLA, 'M2S_REQUIRE_CARLA is set, but .cache/carla holds no ScenarioRunner');
      console.log('skipped: ScenarioRunner is not unpacked in .cache/carla (python3 ../shared/carla/check.py setup)');
      this.skip();
    }
    const settings = vscode.workspace.getConfiguration('modular2simple.carla');
    const global = vscode.ConfigurationTarget.Global;
    try {
      await settings.update('scenarioRunnerPath', setup.scenarioRunner, global);
      await settings.update('python', setup.python, global);
      await settings.update('timeLimit', 100, global);
      // Under 0.9.15's facts the export keeps crossing.xosc's AcquirePositionAction, on which ScenarioRunner 0.9.16 crashes.
      await settings.update('release', '0.9.15', global);
      await open('main.xosc');
      await runFromPalette('Modular2Simple: Check in CARLA ScenarioRunner');
      // crossing.xosc is the file itself, or the copy inside pedestrian.mosc (a mosc: URI) once the suite's Pack test made main.xosc import the package.
      const [crossing, problem] = await waitFor(
        "ScenarioRunner's error on crossing.xosc",
        () =>
          vscode.languages
            .getDiagnostics()
            .filter(([uri]) => uri.path.endsWith('/crossing.xosc'))
            .flatMap(([uri, diagnostics]) =>
              diagnostics.filter((diagnostic) => diagnostic.source === 'ScenarioRunner').map((diagnostic) => [uri, diagnostic] as const),
            )[0],
        100_000,
      );
      const document = await vscode.workspace.openTextDocument(crossing);
      // The position inside the AcquirePositionAction, the line after it, in the simple scenario main.xosc imports.
      assert.equal(problem.range.start.line, positionOf(document, '<AcquirePositionAction').line + 1);
      assert.equal(problem.severity, vscode.DiagnosticSeverity.Error);
      assert.match(problem.message, /TypeError: object of type 'NoneType' has no len\(\)/);
      await waitFor('the message of the check', async () => (await pageShows('ScenarioRunner')) || undefined);
      const editor = await vscode.window.showTextDocument(document, { viewColumn: vscode.ViewColumn.One, preview: false });
      editor.revealRange(problem.range, vscode.TextEditorRevealType.InCenter);
      editor.selection = new vscode.Selection(problem.range.start, problem.range.start);
      await vscode.commands.executeCommand('editor.action.marker.next');
      await screenshot("Check in CARLA ScenarioRunner: ScenarioRunner's error on the source line");
    } finally {
      for (const key of ['scenarioRunnerPath', 'python', 'timeLimit', 'release']) await settings.update(key, undefined, global);
      fs.rmSync(folder, { recursive: true, force: true });
      await revertAndClose();
    }
  },

  carlaExport: async function () {
    this.timeout(120_000);
    requireServerFeature(this, 'exportForCarla', offersRequest(ExportForCarlaRequest));
    const folder = carlaExportFolder();
    if (!folder) {
      assert.ok(!process.env.M2S_REQUIRE_ESMINI, "M2S_REQUIRE_ESMINI is set, but esmini's e6mini.xodr is absent");
      console.log("skipped: esmini's e6mini.xodr is not beside the repository");
      this.skip();
    }
    try {
      const main = await open('carlaExport/xosc/main.xosc');
      await runFromPalette('Modular2Simple: Export for CARLA…');
      // Proposed as Flatten proposes, with .carla.xosc: beside the folder that stands for the package.
      const written = path.join(folder, 'xosc.carla.xosc');
      await acceptSaveDialog(path.basename(written));
      await waitFor(path.basename(written), () => fs.existsSync(written) || undefined, 60_000);
      const text = fs.readFileSync(written, 'utf8');
      assert.match(text, /<FileHeader [^>]*revMajor="1" revMinor="0"/);
      assert.match(text, /<Property name="type" value="ego_vehicle"\/>/);
      assert.doesNotMatch(text, /parameterAttributes|ScenarioReference/);

      // The imported group's loss lands in the simple scenario, on the Event that has the priority; the main's own in the main.
      const simple = vscode.Uri.file(path.join(folder, 'xosc', 'cut_in_group.xosc'));
      const simpleDocument = await vscode.workspace.openTextDocument(simple);
      const priority = await waitFor('the priority loss in cut_in_group.xosc', () =>
        exportLosses(simple).find((diagnostic) => diagnostic.message.startsWith('Event/@priority')),
      );
      assert.equal(priority.range.start.line, positionOf(simpleDocument, 'priority=').line);
      assert.equal(priority.severity, vscode.DiagnosticSeverity.Warning);
      assert.match(priority.message, /ScenarioRunner runs every event in parallel/);
      assert.ok(
        exportLosses(main.document.uri).some((diagnostic) => /'car_white' is no CARLA blueprint/.test(diagnostic.message)),
        'the blueprint loss is on the main',
      );
      const editor = await vscode.window.showTextDocument(simpleDocument, { viewColumn: vscode.ViewColumn.One, preview: false });
      editor.revealRange(priority.range, vscode.TextEditorRevealType.InCenter);
      editor.selection = new vscode.Selection(priority.range.start, priority.range.start);
      await vscode.commands.executeCommand('workbench.actions.view.problems');
      // The panel lists only the rows in view, and the earlier tests leave dozens of problems above ours: filter to it.
      await vscode.commands.executeCommand('problems.action.focusFilter');
      await typeText('ScenarioRunner runs every event');
      try {
        await waitFor(
          'the loss in the Problems panel',
          async () => (await pageShows('ScenarioRunner runs every event in parallel', '.markers-panel')) || undefined,
          15_000,
        );
        await screenshot('Export for CARLA: the losses on the simple scenario');
      } finally {
        await vscode.commands.executeCommand('problems.action.clearFilterText');
      }

      // A refused export writes nothing, and its refusal replaces the previous export's losses.
      const crossing = vscode.Uri.file(path.join(workspaceRoot(), 'crossing.xosc'));
      const refusedOutput = path.join(folder, 'crossing.carla.xosc');
      // The command answers at once, while its error message (with Go to Problem) waits for the user.
      const answer = await Promise.race([
        vscode.commands.executeCommand('modular2simple.exportForCarla', crossing, undefined, { output: refusedOutput }),
        new Promise((_resolve, reject) => setTimeout(() => reject(new Error('the refused export waits for its message')), 60_000)),
      ]);
      assert.equal(answer, undefined);
      const refusal = await waitFor('the refusal on crossing.xosc', () =>
        exportLosses(crossing).find((diagnostic) => diagnostic.severity === vscode.DiagnosticSeverity.Error),
      );
      assert.match(refusal.message, /AcquirePositionAction: crashes ScenarioRunner 0\.9\.16/);
      await waitFor('the refusal message', async () => (await pageShows('Export for CARLA failed: AcquirePositionAction')) || undefined);
      await vscode.commands.executeCommand('notifications.clearAll');
      assert.equal(fs.existsSync(refusedOutput), false, 'a refused export writes nothing');
      assert.deepEqual(exportLosses(simple), [], 'the next export replaces the previous losses');
    } finally {
      await revertAndClose();
    }
  },
};
