import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { SESSION_ARGUMENT } from '../../../server/src/debug/supervisor';
import { esminiCutInFolder, esminiOrSkip } from './esmini.inside';
import { clickElement, pageShows, pressKeys, screenshot } from './harnessClient';
import { api, cli, EXTENSION_ID, type InsideTests, open, positionOf, waitFor, workspaceRoot } from './helpers';

/**
 * The debug adapter processes of the extension under test (their command line names its dist/debugAdapter.js): the
 * one VS Code starts, and the session it runs esmini in, whose command line also has SESSION_ARGUMENT.
 */
function adapterProcesses(): number[] {
  const adapter = path.join(vscode.extensions.getExtension(EXTENSION_ID)?.extensionPath ?? '-', 'dist', 'debugAdapter.js');
  return fs
    .readdirSync('/proc')
    .filter((name) => /^\d+$/.test(name))
    .map(Number)
    .filter((pid) => {
      try {
        return fs.readFileSync(`/proc/${pid}/cmdline`, 'utf8').split('\0').includes(adapter);
      } catch {
        return false;
      }
    });
}

interface StackFrameBody {
  stackFrames: { id: number; name: string; line: number; source?: { path?: string } }[];
}

/** F5 on a scenario as a person does it: the stop on a breakpoint's line, the Variables view, then esmini crashing. */
export const debuggingTests: InsideTests = {
  debugScenario: async function () {
    this.timeout(240_000);
    const { repository, esmini, roads } = esminiOrSkip(this);
    const scenario = esminiCutInFolder(repository, roads, path.join(workspaceRoot(), 'debugging'));
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
    await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
    await settings.update('roadPath', [roads], vscode.ConfigurationTarget.Workspace);
    const events: string[] = [];
    const tracker = vscode.debug.registerDebugAdapterTrackerFactory('modular2simple', {
      createDebugAdapterTracker: () => ({
        onDidSendMessage: (message: { type?: string; event?: string }) => {
          if (message.type === 'event' && message.event) events.push(message.event);
        },
      }),
    });
    const editor = await open(path.relative(workspaceRoot(), scenario));
    const line = positionOf(editor.document, '<Event name="CutInEvent"').line;
    const breakpoint = new vscode.SourceBreakpoint(new vscode.Location(editor.document.uri, new vscode.Position(line, 0)));
    vscode.debug.addBreakpoints([breakpoint]);
    // The bird's-eye view open beside it follows the session.
    await vscode.commands.executeCommand('modular2simple.showBirdsEye', editor.document.uri);
    const view = api().birdsEye;
    await waitFor("the bird's-eye view", () => view.isOpen && view.stats !== undefined, 60_000);
    await vscode.window.showTextDocument(editor.document, vscode.ViewColumn.One);
    try {
      // F5 with no launch.json: the active file, debugged with the folder's settings.
      const stopOnTheEvent = async (): Promise<vscode.DebugSession> => {
        events.length = 0;
        await pressKeys(['F5']);
        await waitFor('the stop on the breakpoint', () => events.includes('stopped') || events.includes('terminated'), 120_000);
        assert.ok(!events.includes('terminated'), `the session ended without stopping: ${events.join(', ')}`);
        // VS Code makes the session active once it has shown the stop, after the tracker saw it.
        const session = await waitFor('the debug session', () => vscode.debug.activeDebugSession, 20_000);
        const trace = (await session.customRequest('stackTrace', { threadId: 1 })) as StackFrameBody;
        assert.equal(trace.stackFrames[0].name, 'Event CutInEvent (running)');
        assert.equal(trace.stackFrames[0].line, line + 1);
        // The path as the remote window names it (vscode-remote://host/path).
        assert.ok(trace.stackFrames[0].source?.path?.endsWith(scenario), trace.stackFrames[0].source?.path);
        return session;
      };
      const session = await stopOnTheEvent();
      const stopTime = Number(
        ((await session.customRequest('evaluate', { expression: 'time', context: 'watch' })) as { result: string }).result,
      );
      // The bird's-eye view at the stop's time, the running event highlighted in its list.
      await waitFor(
        "the bird's-eye view at the stop",
        () => Math.abs((view.stats?.time ?? -1) - stopTime) < 1e-6 && view.stats?.trajectories === 2,
        20_000,
      );
      await waitFor('the running event highlighted', () => pageShows('CutInEvent', '.running'), 20_000);
      // What a person sees: the editor on the breakpoint's line, the call stack, the entities in the Variables view.
      await waitFor('the editor on the stop line', () => vscode.window.activeTextEditor?.selection.active.line === line, 20_000);
      await waitFor('the call stack', () => pageShows('Event CutInEvent (running)'), 20_000);
      await waitFor('the entities in the Variables view', async () => (await pageShows('Ego')) && pageShows('OverTaker'), 20_000);
      // The adapter lists the scope; whether its row is drawn depends on the panel's height, which earlier tests' views change.
      const frames = (await session.customRequest('stackTrace', { threadId: 1 })) as StackFrameBody;
      const scopes = (await session.customRequest('scopes', { frameId: frames.stackFrames[0].id })) as { scopes: { name: string }[] };
      assert.ok(
        scopes.scopes.some((scope) => scope.name === 'Why it fired'),
        `the Why it fired scope is listed: ${scopes.scopes.map((scope) => scope.name).join(', ')}`,
      );
      await screenshot("debug: stopped on the CutInEvent breakpoint, Variables view with the entities, the bird's-eye view at the stop");

      // esmini crashing in the session's process (a segmentation fault, as a bad pointer in esmini gives): the adapter's
      // outer process says so (server/src/debug/supervisor.ts).
      const adapters = adapterProcesses();
      const sessions = adapters.filter((pid) => fs.readFileSync(`/proc/${pid}/cmdline`, 'utf8').split('\0').includes(SESSION_ARGUMENT));
      assert.equal(adapters.length, 2, `the adapter and its session: ${adapters.join(', ')}`);
      assert.equal(sessions.length, 1, `one session process: ${sessions.join(', ')}`);
      process.kill(sessions[0], 'SIGSEGV');
      await waitFor('the session to end', () => vscode.debug.activeDebugSession === undefined, 30_000);
      await waitFor('the message naming the crash', () => pageShows('The debug session of cut-in.xosc ended'), 30_000);
      assert.ok(await pageShows("esmini's process was killed by"), 'the message says how the adapter ended');
      await screenshot('debug: esmini crashed, the session ended with a message, the editor lives');

      // The editor lives: the same F5 starts a new session, which stops on the same line.
      await vscode.commands.executeCommand('notifications.clearAll');
      await vscode.window.showTextDocument(editor.document);
      const again = await stopOnTheEvent();
      await vscode.debug.stopDebugging(again);
      await waitFor('the second session to end', () => vscode.debug.activeDebugSession === undefined, 30_000);
      assert.ok(!(await pageShows('The debug session of cut-in.xosc ended')), 'Stop is no crash');
    } finally {
      vscode.debug.removeBreakpoints([breakpoint]);
      tracker.dispose();
      if (vscode.debug.activeDebugSession) await vscode.debug.stopDebugging();
      await settings.update('path', undefined, vscode.ConfigurationTarget.Workspace);
      await settings.update('roadPath', undefined, vscode.ConfigurationTarget.Workspace);
    }
  },

  debugTimeline: async function () {
    this.timeout(240_000);
    const { repository, esmini, roads } = esminiOrSkip(this);
    // A folder of its own: nothing here depends on what earlier tests left.
    const folder = path.join(workspaceRoot(), 'timeline');
    const scenario = esminiCutInFolder(repository, roads, folder);
    // esmini's own run: the times its log starts each Event at.
    const log = path.join(folder, 'esmini-log.txt');
    execFileSync(
      esmini,
      ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--seed', '1', '--logfile_path', log, '--path', roads],
      {
        cwd: path.dirname(scenario),
      },
    );
    const esminiStarts = [
      ...fs.readFileSync(log, 'utf8').matchAll(/^\[([\d.]+)\] \[info\] (\w+Event) standbyState -> startTransition -> runningState/gm),
    ].map((match) => ({ event: match[2], time: Number(match[1]) }));
    assert.ok(
      esminiStarts.some((start) => start.event === 'CutInEvent'),
      `esmini's log starts CutInEvent: ${JSON.stringify(esminiStarts)}`,
    );
    // The trace as CI writes it, opened in the timeline as a person does from the palette's command with the file.
    const trace = path.join(folder, 'cut-in.jsonl');
    cli([
      'run',
      path.relative(workspaceRoot(), scenario),
      '--trace',
      path.relative(workspaceRoot(), trace),
      '--road-path',
      roads,
      '--esmini',
      esmini,
    ]);
    const view = api().timeline;
    const rendered = view.nextRender();
    assert.equal(await vscode.commands.executeCommand('modular2simple.showTimeline', trace), true);
    await rendered;
    const stats = await waitFor(
      'the timeline drawn',
      () => (view.isOpen && (view.stats?.rows.length ?? 0) > 0 ? view.stats : undefined),
      30_000,
    );
    // A row per Event esmini started, its bar starting at the time esmini's log gives.
    for (const start of esminiStarts) {
      const row = stats.rows.find((candidate) => candidate.element.endsWith(`::${start.event}`));
      assert.ok(row, `a row for ${start.event}: ${stats.rows.map((candidate) => candidate.element).join(', ')}`);
      assert.ok(row.started && row.bars >= 1, `${start.event} drawn with a bar: ${row.text}`);
      assert.ok(row.text.includes(`: ${start.time.toFixed(2)}–`), `${start.event} starts at esmini's ${start.time}: ${row.text}`);
    }
    await waitFor('the rows on the page', async () => (await pageShows('CutInEvent', '.row .label')) && pageShows('HWT', '.cause'), 20_000);
    await screenshot("timeline: cut-in.xosc's run --trace, a row per storyboard element with its bars at esmini's times");
    // A click on a row's name opens the element where it is written.
    const eventLine = positionOf(await vscode.workspace.openTextDocument(scenario), '<Event name="CutInEvent"').line;
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    await vscode.commands.executeCommand('modular2simple.showTimeline', trace);
    await waitFor('the timeline open again', () => view.isOpen && pageShows('CutInEvent', '.row .label'), 30_000);
    assert.ok(await clickElement('.row .label', 'CutInEvent'), "the CutInEvent row's name clicked");
    const editor = await waitFor(
      'cut-in.xosc opened on the Event line',
      () => {
        const active = vscode.window.activeTextEditor;
        return active?.document.uri.fsPath === scenario && active.selection.active.line === eventLine ? active : undefined;
      },
      30_000,
    );
    assert.equal(view.opened?.fsPath, scenario);
    assert.ok(
      editor.visibleRanges.some((range) => range.contains(new vscode.Position(eventLine, 0))),
      'the Event line in view',
    );
    await screenshot('timeline: a click on the CutInEvent row opened cut-in.xosc on its Event line');
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
  },
};
