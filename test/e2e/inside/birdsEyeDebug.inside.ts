import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { cutInToDebug, pressF5UntilStop } from './debugging.inside';
import { pageShows, screenshot } from './harnessClient';
import { api, type InsideTests, open, positionOf, TEST_MS, waitFor, workspaceRoot } from './helpers';

/** The bird's-eye view and F5 on another scenario than the one it shows (issue 27, a new user's walk). */
export const birdsEyeDebugTests: InsideTests = {
  debugBirdsEyeTurns: async function () {
    this.timeout(2 * TEST_MS);
    const { scenario, events, undo } = await cutInToDebug(this, 'debugTurn');
    // The view open on the workspace's main.xosc (four entities on Town05).
    const main = await open('main.xosc');
    await vscode.commands.executeCommand('modular2simple.showBirdsEye', main.document.uri);
    const view = api().birdsEye;
    await waitFor("the bird's-eye view of main.xosc", () => view.isOpen && /Town05/.test(view.scene?.roadFile?.resolved ?? ''));
    const editor = await open(path.relative(workspaceRoot(), scenario));
    const line = positionOf(editor.document, '<Event name="CutInEvent"').line;
    const breakpoint = new vscode.SourceBreakpoint(new vscode.Location(editor.document.uri, new vscode.Position(line, 0)));
    vscode.debug.addBreakpoints([breakpoint]);
    try {
      const session = await pressF5UntilStop(events);
      const stopTime = Number(
        ((await session.customRequest('evaluate', { expression: 'time', context: 'watch' })) as { result: string }).result,
      );
      // The view turned to cut-in.xosc: its road and its two cars at the stop, not main.xosc's Town05.
      await waitFor(
        "the bird's-eye view of cut-in.xosc at the stop",
        () =>
          /e6mini\.xodr$/.test(view.scene?.roadFile?.resolved ?? '') &&
          Math.abs((view.stats?.time ?? -1) - stopTime) < 1e-6 &&
          view.stats?.trajectories === 2,
      );
      assert.deepEqual(
        view.scene?.entities.map((entity) => entity.name),
        ['Ego', 'OverTaker'],
        "the scene's entities are cut-in.xosc's",
      );
      // An event that started at 0.05 s and ended at the stop's step, between two of the session's states, is listed as started.
      await waitFor('OverTakerStartSpeedEvent listed as started at 0.05 s', () => pageShows('started 0.05 s'));
      await screenshot("debug: F5 on cut-in.xosc turned the bird's-eye view from main.xosc to cut-in.xosc, at the stop");
    } finally {
      vscode.debug.removeBreakpoints([breakpoint]);
      await undo();
    }
  },
};
