import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as net from 'node:net';
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
  TEST_MS,
  waitFor,
  workspaceRoot,
} from './helpers';

const SOURCE = 'Export for CARLA';
const CHECK_IN_SCENARIO_RUNNER = 'modular2simple.checkInScenarioRunner';

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

/**
 * A ScenarioRunner folder of the test's own: its scenario_runner.py appends its argv and working folder to
 * runs.jsonl beside it and exits with the code written in exit-code (0 without one), so the test sees what
 * *Run in CARLA* started and how it takes each end. No CARLA, no ScenarioRunner needed.
 */
function fakeScenarioRunner(folder: string): { runs: () => { argv: string[]; cwd: string }[]; exitWith: (code: number) => void } {
  fs.mkdirSync(folder, { recursive: true });
  fs.writeFileSync(
    path.join(folder, 'scenario_runner.py'),
    [
      'import json, os, sys',
      'here = os.path.dirname(os.path.abspath(__file__))',
      "with open(os.path.join(here, 'runs.jsonl'), 'a') as runs:",
      "    runs.write(json.dumps({'argv': sys.argv, 'cwd': os.getcwd()}) + '\\n')",
      "code = os.path.join(here, 'exit-code')",
      'sys.exit(int(open(code).read()) if os.path.exists(code) else 0)',
      '',
    ].join('\n'),
  );
  const log = path.join(folder, 'runs.jsonl');
  return {
    runs: () =>
      fs.existsSync(log)
        ? fs
            .readFileSync(log, 'utf8')
            .split('\n')
            .filter((line) => line.trim())
            .map((line) => JSON.parse(line) as { argv: string[]; cwd: string })
        : [],
    exitWith: (code) => fs.writeFileSync(path.join(folder, 'exit-code'), String(code)),
  };
}

/** Runs *Run in CARLA* on a file and answers how it ended, within a time that fails the test instead of hanging it. */
async function runInCarla(uri: vscode.Uri): Promise<{ ran: boolean; message: string } | undefined> {
  return Promise.race([
    vscode.commands.executeCommand<{ ran: boolean; message: string } | undefined>('modular2simple.runInCarla', uri),
    new Promise<never>((_resolve, reject) => setTimeout(() => reject(new Error('Run in CARLA did not answer within 60 s')), 60_000)),
  ]);
}

/** *Export for CARLA…* from the palette: the file written, its losses as diagnostics on the simple scenario's lines. */
export const carlaTests: InsideTests = {
  carlaCheck: async function () {
    this.timeout(2 * TEST_MS);
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

  carlaSettingsAtOnce: async function () {
    this.timeout(2 * TEST_MS);
    const check = async (): Promise<string> =>
      (await vscode.commands.executeCommand<{ message: string } | undefined>(CHECK_IN_SCENARIO_RUNNER, vscode.Uri.file(main)))?.message ??
      'no answer';
    /** Whether the check's answer names the folder; what it said instead, as the error waitFor gives when it times out. */
    const checkNames = async (folder: string): Promise<true> => {
      const said = await check();
      if (!said.includes(folder)) throw new Error(`the check said: ${said}`);
      return true;
    };
    const main = path.join(workspaceRoot(), 'main.xosc');
    const folder = path.join(workspaceRoot(), '.carla-settings');
    fs.mkdirSync(folder, { recursive: true });
    // Where a user writes the settings: the user settings.json, opened and saved in the editor.
    await vscode.commands.executeCommand('workbench.action.openSettingsJson');
    const settingsFile = await waitFor('the user settings.json in the editor', () => {
      const document = vscode.window.activeTextEditor?.document;
      return document && /settings\.json$/.test(document.uri.path) ? document : undefined;
    });
    const settingsUri = settingsFile.uri;
    const original = settingsFile.getText();
    /**
     * settings.json replaced by `text` and saved as the user does it, in the editor's own model (typed over all, then
     * File: Save): an edit of its file: URI from here is a change on disk, which VS Code in a browser does not watch.
     */
    const replaceSettings = async (text: string): Promise<void> => {
      await vscode.commands.executeCommand('workbench.action.openSettingsJson');
      await vscode.commands.executeCommand('editor.action.selectAll');
      // A snippet, not typing: no bracket or quote is closed twice ('$' and '\\' escaped, which a snippet reads otherwise).
      await vscode.commands.executeCommand('editor.action.insertSnippet', { snippet: text.replace(/[$\\]/g, '\\$&') });
      await vscode.commands.executeCommand('workbench.action.files.save');
      await waitFor('settings.json saved as written', () => fs.readFileSync(settingsUri.fsPath, 'utf8') === text || undefined);
    };
    const write = (values: Record<string, string>): Promise<void> =>
      replaceSettings(JSON.stringify({ ...(JSON.parse(original.trim() || '{}') as Record<string, unknown>), ...values }, null, 2) + '\n');
    try {
      const first = path.join(folder, 'scenario_runner-first');
      await write({ 'modular2simple.carla.scenarioRunnerPath': first, 'modular2simple.carla.python': '/usr/bin/python3' });
      await waitFor(`the check to name the folder just set in ${settingsUri.toString()}`, () => checkNames(first));
      const second = path.join(folder, 'scenario_runner-second');
      await write({ 'modular2simple.carla.scenarioRunnerPath': second, 'modular2simple.carla.python': '/usr/bin/python3' });
      await waitFor('the check to name the folder set second', () => checkNames(second));
      await screenshot('Check in CARLA ScenarioRunner names the ScenarioRunner folder just saved in settings.json');
    } finally {
      await replaceSettings(original);
      fs.rmSync(folder, { recursive: true, force: true });
      await revertAndClose();
    }
  },

  carlaRun: async function () {
    this.timeout(240_000);
    const folder = carlaExportFolder();
    if (!folder || !fs.existsSync('/usr/bin/python3')) {
      assert.ok(!process.env.M2S_REQUIRE_ESMINI, "M2S_REQUIRE_ESMINI is set, but esmini's e6mini.xodr is absent");
      console.log("skipped: esmini's e6mini.xodr is not beside the repository, or there is no /usr/bin/python3");
      this.skip();
    }
    const scenarioRunner = path.join(folder, 'fake-scenario-runner');
    const fake = fakeScenarioRunner(scenarioRunner);
    const main = vscode.Uri.file(path.join(folder, 'xosc', 'main.xosc'));
    const settings = vscode.workspace.getConfiguration('modular2simple.carla');
    const global = vscode.ConfigurationTarget.Global;
    // What listens where the CARLA server would: Run in CARLA checks that something answers before it starts ScenarioRunner.
    const server = net.createServer((socket) => socket.destroy());
    await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
    const port = (server.address() as net.AddressInfo).port;
    try {
      await settings.update('scenarioRunnerPath', scenarioRunner, global);
      await settings.update('python', '/usr/bin/python3', global);

      // No host: said, naming the setting, and nothing started.
      await settings.update('host', undefined, global);
      const noHost = await runInCarla(main);
      assert.equal(noHost?.ran, false);
      assert.match(noHost?.message ?? '', /set modular2simple\.carla\.host .*nothing was run/);
      assert.deepEqual(fake.runs(), [], 'nothing started without a host');

      // A host where nothing listens: said, nothing started.
      const closed = net.createServer();
      await new Promise<void>((resolve) => closed.listen(0, '127.0.0.1', resolve));
      const closedPort = (closed.address() as net.AddressInfo).port;
      await new Promise<void>((resolve) => closed.close(() => resolve()));
      await settings.update('host', '127.0.0.1', global);
      await settings.update('port', closedPort, global);
      const unreachable = await runInCarla(main);
      assert.equal(unreachable?.ran, false);
      assert.match(unreachable?.message ?? '', new RegExp(`no CARLA server at 127\\.0\\.0\\.1:${closedPort} .*nothing was run`));
      assert.deepEqual(fake.runs(), [], 'nothing started without a server');

      // A server: scenario_runner.py started on the export, with its host and port, in ScenarioRunner's folder.
      await settings.update('port', port, global);
      const ran = await runInCarla(main);
      assert.deepEqual(ran, {
        ran: true,
        message: 'Run in CARLA: ScenarioRunner ran main to its end (exit code 0); its verdict is in the terminal.',
      });
      const [run] = fake.runs();
      assert.ok(run, 'scenario_runner.py was started');
      assert.equal(fs.realpathSync(run.cwd), fs.realpathSync(scenarioRunner));
      assert.equal(run.argv.length, 7, run.argv.join(' '));
      const [script, openscenario, exported, host, hostValue, portFlag, portValue] = run.argv;
      assert.equal(fs.realpathSync(script), fs.realpathSync(path.join(scenarioRunner, 'scenario_runner.py')));
      assert.deepEqual(
        [openscenario, host, hostValue, portFlag, portValue],
        ['--openscenario', '--host', '127.0.0.1', '--port', String(port)],
      );
      assert.match(path.basename(exported), /^main\.carla\.xosc$/);
      const text = fs.readFileSync(exported, 'utf8');
      assert.match(text, /<FileHeader [^>]*revMajor="1" revMinor="0"/, 'ScenarioRunner is given the 1.0 export');
      assert.match(text, /<Property name="type" value="ego_vehicle"\/>/);

      // ScenarioRunner ending with an error: not done.
      fake.exitWith(3);
      const failed = await runInCarla(main);
      assert.equal(failed?.ran, false);
      assert.match(failed?.message ?? '', /ScenarioRunner exited with code 3: main did not run to its end/);
      assert.equal(fake.runs().length, 2);

      // A Python that does not exist: said before anything starts, never called done.
      await settings.update('python', path.join(folder, 'no-such-python'), global);
      const noPython = await runInCarla(main);
      assert.equal(noPython?.ran, false);
      assert.match(
        noPython?.message ?? '',
        /the Python .*no-such-python \(modular2simple\.carla\.python\) is not an executable file.*Nothing was run/,
      );
      // One that cannot start (its interpreter is missing): the task ends without a process, which is not done either.
      const broken = path.join(scenarioRunner, 'broken-python');
      fs.writeFileSync(broken, '#!/no/such/interpreter\n', { mode: 0o755 });
      await settings.update('python', broken, global);
      const notStarted = await runInCarla(main);
      assert.equal(notStarted?.ran, false, notStarted?.message);
      assert.equal(fake.runs().length, 2, 'nothing ran');
    } finally {
      await new Promise<void>((resolve) => server.close(() => resolve()));
      for (const key of ['scenarioRunnerPath', 'python', 'host', 'port']) await settings.update(key, undefined, global);
      // The runs' task terminals (workbench.action.terminal.killAll never answers in code-server).
      for (const terminal of vscode.window.terminals) terminal.dispose();
      fs.rmSync(scenarioRunner, { recursive: true, force: true });
      await revertAndClose();
    }
  },

  carlaExport: async function () {
    this.timeout(2 * TEST_MS);
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
      await waitFor(path.basename(written), () => fs.existsSync(written) || undefined);
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
