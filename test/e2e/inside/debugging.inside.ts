import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { DEBUG_CODE_CACHE_ENV } from '../../../common/src/debugState';
import { SESSION_ARGUMENT } from '../../../server/src/debug/supervisor';
import { writeTwoCutIns } from '../../support/debugScenarios';
import { esminiCutInFolder, esminiOrSkip } from './esmini.inside';
import { clickElement, type PageBox, pageBoxes, pageShows, pressKeys, runFromPalette, screenshot } from './harnessClient';
import { api, cli, EXTENSION_ID, type InsideTests, open, positionOf, TEST_MS, waitFor, waitForPage, workspaceRoot } from './helpers';

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

/** esmini's own run of `scenario` at the debugger's default step: the times its log starts each Event at, and its last time. */
function esminiRunOf(
  esmini: string,
  scenario: string,
  roads: string,
  folder: string,
): { starts: { event: string; time: number }[]; end: number } {
  const log = path.join(folder, 'esmini-log.txt');
  execFileSync(
    esmini,
    ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--seed', '1', '--logfile_path', log, '--path', roads],
    { cwd: path.dirname(scenario) },
  );
  const text = fs.readFileSync(log, 'utf8');
  const starts = [...text.matchAll(/^\[([\d.]+)\] \[info\] (\w+Event) standbyState -> startTransition -> runningState/gm)].map((match) => ({
    event: match[2],
    time: Number(match[1]),
  }));
  assert.ok(
    starts.some((start) => start.event === 'CutInEvent'),
    `esmini's log starts CutInEvent: ${JSON.stringify(starts)}`,
  );
  return { starts, end: Math.max(...[...text.matchAll(/^\[([\d.]+)\]/gm)].map((match) => Number(match[1]))) };
}

/** What the timeline's page shows now: its title, the time and where its axis ends (the run's end, once it finished) in its header. */
async function timelineHeader(): Promise<{ title: string; time: number; end: number } | undefined> {
  const [title] = await pageBoxes('#title');
  const [time] = await pageBoxes('#time');
  const times = /t = ([\d.]+) s (?:of|so far, axis to) ([\d.]+) s/.exec(time?.text ?? '');
  return title && times ? { title: title.text, time: Number(times[1]), end: Number(times[2]) } : undefined;
}

/** The time axis's labels that wrap (taller than one line) or leave the axis (none should). */
async function badAxisLabels(): Promise<string[]> {
  const [axis] = await pageBoxes('#axisLabels');
  const labels = await pageBoxes('#axisLabels .axisLabel');
  if (!axis || labels.length === 0) return ['no axis labels drawn'];
  const line = Math.min(...labels.map((label) => label.bottom - label.top));
  return labels.flatMap((label) => [
    ...(label.bottom - label.top > line * 1.5 ? [`'${label.text}' wraps`] : []),
    ...(label.left < axis.left - 0.5 || label.right > axis.right + 0.5 ? [`'${label.text}' leaves the axis`] : []),
  ]);
}

/**
 * The times at which the page draws the bars of the element whose path ends with `::name`: read from where they are
 * drawn against the time axis (its labels span 0 to the run's end), as a person reads them; with the width of a pixel in s.
 */
async function drawnBars(name: string, end: number): Promise<{ starts: number[]; open: number; pixel: number }> {
  const [axis] = await pageBoxes('#axisLabels');
  assert.ok(axis && axis.right > axis.left, 'the time axis is drawn');
  const pixel = end / (axis.right - axis.left);
  // A Story's path is its name; any other element's ends with it.
  const rows = [`.row[data-element="${name}"]`, `.row[data-element$="::${name}"]`];
  const bars = await pageBoxes(rows.map((row) => `${row} .bar`).join(', '));
  return {
    starts: bars.map((bar) => (bar.left - axis.left) * pixel),
    open: (await pageBoxes(rows.map((row) => `${row} .bar.open`).join(', '))).length,
    pixel,
  };
}

/** The firing conditions' words the timeline's page writes that cover a bar or one another (none should). */
async function coveringLabels(): Promise<string[]> {
  const labels = await pageBoxes('.row .cause');
  const bars = await pageBoxes('.row .bar');
  const overlap = (a: PageBox, b: PageBox) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
  return labels.flatMap((label, index) => [
    ...bars.filter((bar) => overlap(label, bar)).map(() => `'${label.text}' covers a bar`),
    ...labels
      .slice(index + 1)
      .filter((other) => overlap(label, other))
      .map((other) => `'${label.text}' covers '${other.text}'`),
  ]);
}

/** Waits until the timeline's page draws a bar for each of esmini's Event starts at esmini's time (within a pixel). */
async function barsAtEsminiTimes(starts: { event: string; time: number }[], what: string): Promise<string> {
  let seen = '';
  try {
    return await waitFor(what, async () => {
      const header = await timelineHeader();
      if (!header) return false;
      const drawn: string[] = [];
      for (const start of starts) {
        const bars = await drawnBars(start.event, header.end);
        drawn.push(`${start.event} at ${bars.starts.map((time) => time.toFixed(3)).join(', ') || 'nothing'} (esmini ${start.time})`);
        if (!bars.starts.some((time) => Math.abs(time - start.time) <= bars.pixel + 1e-3)) {
          seen = `${header.title}, ${header.time} of ${header.end} s: ${drawn.join('; ')}`;
          return false;
        }
      }
      return drawn.join('; ');
    });
  } catch (error) {
    throw new Error(`${(error as Error).message}; the page last drew ${seen}`);
  }
}

/** F5 as the folder's settings make it: esmini's program and roads set, the adapter's events recorded; `undo` resets both and ends a session left. */
async function debugSetup(esmini: string, roads: string, moreFolders: string[] = []): Promise<{ events: string[]; undo(): Promise<void> }> {
  const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
  await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
  await settings.update('roadPath', [roads, ...moreFolders], vscode.ConfigurationTarget.Workspace);
  const events: string[] = [];
  const tracker = vscode.debug.registerDebugAdapterTrackerFactory('modular2simple', {
    createDebugAdapterTracker: () => ({
      onDidSendMessage: (message: { type?: string; event?: string }) => {
        if (message.type === 'event' && message.event) events.push(message.event);
      },
    }),
  });
  return {
    events,
    undo: async () => {
      tracker.dispose();
      if (vscode.debug.activeDebugSession) await vscode.debug.stopDebugging();
      await settings.update('path', undefined, vscode.ConfigurationTarget.Workspace);
      await settings.update('roadPath', undefined, vscode.ConfigurationTarget.Workspace);
    },
  };
}

/** esmini's cut-in.xosc in the workspace's `folder`, with esmini and its roads set for debugging (`undo` resets them). */
export async function cutInToDebug(
  context: Mocha.Context,
  folder: string,
): Promise<{ scenario: string; esmini: string; roads: string; events: string[]; undo(): Promise<void> }> {
  const { repository, esmini, roads } = esminiOrSkip(context);
  const scenario = esminiCutInFolder(repository, roads, path.join(workspaceRoot(), folder));
  return { scenario, esmini, roads, ...(await debugSetup(esmini, roads)) };
}

/** F5 as a person presses it, on the active editor, until the session stops (one that ends without stopping fails). */
export async function pressF5UntilStop(events: string[]): Promise<vscode.DebugSession> {
  events.length = 0;
  await pressKeys(['F5']);
  await waitFor('the stop on the breakpoint', () => events.includes('stopped') || events.includes('terminated'), 120_000);
  assert.ok(!events.includes('terminated'), `the session ended without stopping: ${events.join(', ')}`);
  // VS Code makes the session active once it has shown the stop, after the tracker saw it.
  return waitFor('the debug session', () => vscode.debug.activeDebugSession);
}

interface StackFrameBody {
  stackFrames: { id: number; name: string; line: number; source?: { path?: string } }[];
}

/** F5 on a scenario as a person does it: the stop on a breakpoint's line, the Variables view, then esmini crashing. */
export const debuggingTests: InsideTests = {
  debugScenario: async function () {
    this.timeout(2 * TEST_MS);
    const { scenario, events, undo } = await cutInToDebug(this, 'debugging');
    const editor = await open(path.relative(workspaceRoot(), scenario));
    const line = positionOf(editor.document, '<Event name="CutInEvent"').line;
    const breakpoint = new vscode.SourceBreakpoint(new vscode.Location(editor.document.uri, new vscode.Position(line, 0)));
    vscode.debug.addBreakpoints([breakpoint]);
    // The bird's-eye view open beside it follows the session.
    await vscode.commands.executeCommand('modular2simple.showBirdsEye', editor.document.uri);
    const view = api().birdsEye;
    await waitFor("the bird's-eye view", () => view.isOpen && view.stats !== undefined);
    await vscode.window.showTextDocument(editor.document, vscode.ViewColumn.One);
    try {
      // F5 with no launch.json: the active file, debugged with the folder's settings.
      const stopOnTheEvent = async (): Promise<vscode.DebugSession> => {
        const session = await pressF5UntilStop(events);
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
      );
      await waitFor('the running event highlighted', () => pageShows('CutInEvent', '.running'));
      // What a person sees: the editor on the breakpoint's line, the call stack, the entities in the Variables view.
      await waitFor('the editor on the stop line', () => vscode.window.activeTextEditor?.selection.active.line === line);
      await waitFor('the call stack', () => pageShows('Event CutInEvent (running)'));
      await waitFor('the entities in the Variables view', async () => (await pageShows('Ego')) && pageShows('OverTaker'));
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
      await waitFor('the session to end', () => vscode.debug.activeDebugSession === undefined);
      await waitForPage('The debug session of cut-in.xosc ended');
      // The message says how the adapter ended.
      await waitForPage("esmini's process was killed by");
      await screenshot('debug: esmini crashed, the session ended with a message, the editor lives');

      // The editor lives: the same F5 starts a new session, which stops on the same line.
      await vscode.commands.executeCommand('notifications.clearAll');
      await vscode.window.showTextDocument(editor.document);
      const again = await stopOnTheEvent();
      await vscode.debug.stopDebugging(again);
      await waitFor('the second session to end', () => vscode.debug.activeDebugSession === undefined);
      // What would report a crash has happened: the adapter's processes ended (the client's crash report follows their
      // exit), and the page followed the session's end (its call stack is gone; the adapter's own report comes before).
      await waitFor('the adapter processes to end', () => adapterProcesses().length === 0);
      await waitFor('the call stack to clear', async () => !(await pageShows('Event CutInEvent (running)')));
      assert.ok(!(await pageShows('The debug session of cut-in.xosc ended')), 'Stop is no crash');
    } finally {
      vscode.debug.removeBreakpoints([breakpoint]);
      await undo();
    }
  },

  debugImportLine: async function () {
    this.timeout(2 * TEST_MS);
    const { repository, esmini, roads } = esminiOrSkip(this);
    const folder = path.join(workspaceRoot(), 'importLine');
    fs.mkdirSync(folder, { recursive: true });
    writeTwoCutIns(folder, 30, path.join(repository, 'examples'));
    const { events, undo } = await debugSetup(esmini, roads, [path.join(roads, '..', 'Catalogs', 'Vehicles')]);
    const main = await open(path.relative(workspaceRoot(), path.join(folder, 'main.xosc')));
    const line = positionOf(main.document, '<ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">').line;
    const breakpoint = new vscode.SourceBreakpoint(new vscode.Location(main.document.uri, new vscode.Position(line, 0)));
    vscode.debug.addBreakpoints([breakpoint]);
    try {
      const session = await pressF5UntilStop(events);
      const trace = (await session.customRequest('stackTrace', { threadId: 1 })) as StackFrameBody;
      assert.equal(trace.stackFrames[0].name, 'ManeuverGroup CutInVehicle.CutIn (running)');
      assert.equal(trace.stackFrames[0].line, line + 1);
      // What a person sees: the editor on the main's line where the breakpoint is, the copy further down the stack.
      await waitFor(
        "the editor on the breakpoint's line of the main",
        () =>
          vscode.window.activeTextEditor?.document.uri.toString() === main.document.uri.toString() &&
          vscode.window.activeTextEditor.selection.active.line === line,
      );
      await waitFor('the call stack', () => pageShows('ManeuverGroup CutInVehicle.CutIn (running)'));
      // The stack path as the remote window names it (vscode-remote://host/path).
      const copy = trace.stackFrames.find((frame) => frame.name.startsWith('ManeuverGroup CutInVehicle.CutIn (running since'));
      assert.ok(copy?.source?.path?.endsWith(path.join(folder, 'lane_change.xosc')), JSON.stringify(trace.stackFrames));
      await screenshot("debug: stopped on the main's ManeuverGroup that imports CutIn, the editor on that line");
      // The session's process was given a folder of the extension's storage for V8's code cache of its bundle.
      const [sessionPid] = adapterProcesses().filter((pid) =>
        fs.readFileSync(`/proc/${pid}/cmdline`, 'utf8').split('\0').includes(SESSION_ARGUMENT),
      );
      const cacheFolder = fs
        .readFileSync(`/proc/${sessionPid}/environ`, 'utf8')
        .split('\0')
        .find((entry) => entry.startsWith(`${DEBUG_CODE_CACHE_ENV}=`))
        ?.slice(DEBUG_CODE_CACHE_ENV.length + 1);
      assert.ok(
        cacheFolder !== undefined && cacheFolder.includes('globalStorage'),
        `the cache folder ${cacheFolder} is the extension's storage`,
      );
      await vscode.debug.stopDebugging(session);
      await waitFor('the session to end', () => vscode.debug.activeDebugSession === undefined);
      // It writes the cache as it exits, for the next F5 on this runtime.
      await waitFor('the adapter processes to end', () => adapterProcesses().length === 0);
      const written = fs.readdirSync(cacheFolder).filter((name) => name.startsWith('debugSession.js-') && name.endsWith('.cache'));
      assert.equal(written.length, 1, `the session's code cache in ${cacheFolder}: ${written.join(', ')}`);
    } finally {
      vscode.debug.removeBreakpoints([breakpoint]);
      await undo();
    }
  },

  debugTimeline: async function () {
    this.timeout(2 * TEST_MS);
    const { repository, esmini, roads } = esminiOrSkip(this);
    // A folder of its own: nothing here depends on what earlier tests left.
    const folder = path.join(workspaceRoot(), 'timeline');
    const scenario = esminiCutInFolder(repository, roads, folder);
    const { starts: esminiStarts } = esminiRunOf(esmini, scenario, roads, folder);
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
    const stats = await waitFor('the timeline drawn', () => (view.isOpen && (view.stats?.rows.length ?? 0) > 0 ? view.stats : undefined));
    // A row per Event esmini started, its bar starting at the time esmini's log gives.
    for (const start of esminiStarts) {
      const row = stats.rows.find((candidate) => candidate.element.endsWith(`::${start.event}`));
      assert.ok(row, `a row for ${start.event}: ${stats.rows.map((candidate) => candidate.element).join(', ')}`);
      assert.ok(row.started && row.bars >= 1, `${start.event} drawn with a bar: ${row.text}`);
      assert.ok(row.text.includes(`: ${start.time.toFixed(2)}–`), `${start.event} starts at esmini's ${start.time}: ${row.text}`);
    }
    await waitFor('the rows on the page', async () => (await pageShows('CutInEvent', '.row .label')) && pageShows('HWT', '.cause'));
    assert.deepEqual(await coveringLabels(), [], 'no firing condition written over a bar or another');
    await screenshot("timeline: cut-in.xosc's run --trace, a row per storyboard element with its bars at esmini's times");
    // A click on a row's name opens the element where it is written.
    const eventLine = positionOf(await vscode.workspace.openTextDocument(scenario), '<Event name="CutInEvent"').line;
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    await vscode.commands.executeCommand('modular2simple.showTimeline', trace);
    await waitFor('the timeline open again', () => view.isOpen && pageShows('CutInEvent', '.row .label'));
    assert.ok(await clickElement('.row .label', 'CutInEvent'), "the CutInEvent row's name clicked");
    const editor = await waitFor('cut-in.xosc opened on the Event line', () => {
      const active = vscode.window.activeTextEditor;
      return active?.document.uri.fsPath === scenario && active.selection.active.line === eventLine ? active : undefined;
    });
    assert.equal(view.opened?.fsPath, scenario);
    assert.ok(
      editor.visibleRanges.some((range) => range.contains(new vscode.Position(eventLine, 0))),
      'the Event line in view',
    );
    await screenshot('timeline: a click on the CutInEvent row opened cut-in.xosc on its Event line');
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
  },

  debugTimelineSession: async function () {
    this.timeout(300_000);
    const { repository, esmini, roads } = esminiOrSkip(this);
    // A folder of its own: nothing here depends on what earlier tests left.
    const folder = path.join(workspaceRoot(), 'session-timeline');
    const scenario = esminiCutInFolder(repository, roads, folder);
    const esminiRun = esminiRunOf(esmini, scenario, roads, folder);
    const { events, undo } = await debugSetup(esmini, roads);
    const editor = await open(path.relative(workspaceRoot(), scenario));
    const line = positionOf(editor.document, '<Event name="OvertakerBrakeEvent"').line;
    const brake = esminiRun.starts.find((start) => start.event === 'OvertakerBrakeEvent');
    assert.ok(brake, `esmini's log starts OvertakerBrakeEvent: ${JSON.stringify(esminiRun.starts)}`);
    const breakpoint = new vscode.SourceBreakpoint(new vscode.Location(editor.document.uri, new vscode.Position(line, 0)));
    vscode.debug.addBreakpoints([breakpoint]);
    try {
      await pressKeys(['F5']);
      await waitFor('the stop on the breakpoint', () => events.includes('stopped') || events.includes('terminated'), 120_000);
      assert.ok(!events.includes('terminated'), `the session ended without stopping: ${events.join(', ')}`);
      // VS Code shows the stop (and moves the focus to the editor) after the adapter sent it: the palette only once it has.
      await waitFor('the editor on the stop line', () => vscode.window.activeTextEditor?.selection.active.line === line);
      await waitFor('the call stack', () => pageShows('Event OvertakerBrakeEvent (running)'));
      // While the session is stopped, the timeline opened from the palette as a person does: the run so far, to the stop.
      await runFromPalette('Modular2Simple: Show Storyboard Timeline');
      await waitFor('the running session on the timeline page, at the stop', async () => {
        const header = await timelineHeader();
        // The axis reaches past the stop: the bar just stopped on has room, not squeezed against the track's right end.
        return (
          header?.title === 'debugging cut-in.xosc (running)' &&
          Math.abs(header.time - brake.time) < 1e-6 &&
          header.time <= header.end * 0.8 + 1e-6 &&
          header.time >= header.end * 0.4
        );
      });
      const stopBar = await pageBoxes(`.row[data-element$="::OvertakerBrakeEvent"] .bar`);
      const [axisBox] = await pageBoxes('#axisLabels');
      assert.ok(
        stopBar.length === 1 && axisBox && stopBar[0].left < axisBox.right - (axisBox.right - axisBox.left) * 0.15,
        `the bar stopped on stands clear of the track's right end: ${JSON.stringify(stopBar)}, axis ${JSON.stringify(axisBox)}`,
      );
      assert.deepEqual(await badAxisLabels(), [], 'every axis label whole on one line, on the axis');
      // The Story starts at 0 s, as the session launches: its bar too.
      const story = { event: 'CutInAndBrakeStory', time: 0 };
      const soFar = [story, ...esminiRun.starts.filter((start) => start.time <= brake.time)];
      await barsAtEsminiTimes(soFar, "the bars of the session so far at esmini's times");
      assert.equal((await drawnBars('OvertakerBrakeEvent', brake.time)).open, 1, 'the event stopped on runs on: its bar is open');
      assert.ok(!(await pageShows('never started', '.row')), 'every row so far started');
      assert.deepEqual(await coveringLabels(), [], 'no firing condition written over a bar or another');
      await screenshot(
        "timeline: the debug session of cut-in.xosc stopped on OvertakerBrakeEvent, its bars to the stop at esmini's times, the axis reaching past it",
      );

      // VS Code's restart button: the same session (its id kept, the protocol's restart), a new run, which the
      // timeline shows alone: each start once, not the first run's bars with the second's.
      const sessionId = vscode.debug.activeDebugSession?.id;
      const stopsBefore = events.filter((event) => event === 'stopped').length;
      await vscode.commands.executeCommand('workbench.action.debug.restart');
      await waitFor(
        'the restarted run to stop on the breakpoint again',
        () => events.filter((event) => event === 'stopped').length > stopsBefore,
        120_000,
      );
      assert.equal(vscode.debug.activeDebugSession?.id, sessionId, 'a restart keeps the session');
      const restarted = await waitFor('the restarted run on the timeline page, at the stop', async () => {
        const header = await timelineHeader();
        return header?.title === 'debugging cut-in.xosc, run 2 (restarted) (running)' && Math.abs(header.time - brake.time) < 1e-6
          ? header
          : undefined;
      });
      await barsAtEsminiTimes(soFar, "the restarted run's bars at esmini's times");
      for (const start of soFar)
        assert.equal(
          (await drawnBars(start.event, restarted.end)).starts.length,
          1,
          `${start.event}: one bar, the first run's not mixed in`,
        );
      await screenshot(
        "timeline: the same session restarted with VS Code's restart button, the new run alone, stopped on OvertakerBrakeEvent",
      );

      // On to the end: the timeline of the finished session ends where the run did, not at the run's limit (an hour).
      await vscode.commands.executeCommand('workbench.action.debug.continue');
      await waitFor('the session to end', () => vscode.debug.activeDebugSession === undefined, 120_000);
      const finished = async (what: string): Promise<void> => {
        await waitFor(what, async () => {
          const header = await timelineHeader();
          return header?.title === 'debugging cut-in.xosc, run 2 (restarted)' && Math.abs(header.end - esminiRun.end) <= 0.05 + 1e-6;
        });
        await barsAtEsminiTimes([story, ...esminiRun.starts], "the finished session's bars at esmini's times");
        for (const start of esminiRun.starts)
          assert.equal((await drawnBars(start.event, esminiRun.end)).open, 0, `${start.event} ended before the run did: no open bar`);
        assert.ok(!(await pageShows('never started', '.row')), 'every row started');
        assert.deepEqual(await coveringLabels(), [], 'no firing condition written over a bar or another');
        assert.deepEqual(await badAxisLabels(), [], 'every axis label whole on one line, on the axis');
        assert.ok(await pageShows('TimeHeadwayCondition: HWT 0.7 > 0.7', '.row .cause'), "OvertakerBrakeEvent's firing condition written");
      };
      await finished("the finished session on the timeline page, to esmini's end");
      await screenshot("timeline: the finished debug session of cut-in.xosc, its bars at esmini's times to the run's end");

      // Closed, then opened again from the palette: the finished session's timeline, as it was.
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      await waitFor('the timeline closed', () => !api().timeline.isOpen);
      await runFromPalette('Modular2Simple: Show Storyboard Timeline');
      await finished('the finished session on the timeline page opened again');
    } finally {
      // Keys meant for the palette that reached the editor change nothing on disk.
      if (editor.document.isDirty) {
        await vscode.window.showTextDocument(editor.document);
        await vscode.commands.executeCommand('workbench.action.files.revert');
      }
      vscode.debug.removeBreakpoints([breakpoint]);
      await undo();
    }
  },
};
