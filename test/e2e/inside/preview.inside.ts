import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import * as vscode from 'vscode';
import {
  api,
  type InsideTests,
  open,
  positionOf,
  replaceText,
  requireServerFeature,
  revertAndClose,
  TEST_MS,
  waitFor,
  workspaceRoot,
} from './helpers';
import { pageShows, post, runFromPalette, screenshot } from './harnessClient';

/** The flattened preview: opened from a CodeLens and from the palette, following edits. */
export const previewTests: InsideTests = {
  preview: async function () {
    this.timeout(TEST_MS);
    requireServerFeature(this, 'codeLens', !!api().serverCapabilities()?.codeLensProvider);
    const editor = await open('main.xosc');
    const previewOpen = () =>
      vscode.workspace.textDocuments.find((document) => document.uri.scheme === 'modular2simple-preview' && !document.isClosed);
    const previewEditor = () =>
      vscode.window.visibleTextEditors.find((visible) => visible.document.uri.scheme === 'modular2simple-preview');
    const shows = (preview: vscode.TextEditor, line: number) =>
      preview.visibleRanges.some((range) => range.start.line <= line && line <= range.end.line);
    // The "flatten preview" CodeLens of the third reference opens the preview at the group that reference imports, not at line 1.
    const referenceLine = positionOf(editor.document, 'scenarioFileName="pedestrian.mosc"').line;
    const lenses = await waitFor('the CodeLenses', async () => {
      const found = await vscode.commands.executeCommand<vscode.CodeLens[]>('vscode.executeCodeLensProvider', editor.document.uri, 100);
      return found.some((candidate) => candidate.command?.command === 'modular2simple.openPreview') ? found : undefined;
    });
    const lens = lenses.find(
      (candidate) => candidate.command?.command === 'modular2simple.openPreview' && candidate.range.start.line === referenceLine,
    )?.command;
    assert.ok(lens, `no flatten preview lens on line ${referenceLine + 1}`);
    await vscode.commands.executeCommand(lens.command, ...(lens.arguments ?? []));
    const preview = await waitFor('the preview', previewOpen);
    assert.match(preview.uri.path, /\/examples\.flattened\.xosc$/, 'the preview is not named as Flatten names its output');
    await waitFor('the flattened text', () => preview.getText().includes('name="Pedestrian.Walker.Crossing"') || undefined);
    assert.ok(!preview.getText().includes('ScenarioReference'), 'the preview still holds a ScenarioReference');
    const pedestrian = positionOf(preview, 'name="Pedestrian.Walker.Crossing"').line;
    const atLens = await waitFor('the preview editor', previewEditor);
    await waitFor('the preview to open at the pedestrian group', () => (shows(atLens, pedestrian) && !shows(atLens, 0)) || undefined);
    await screenshot('preview opens at the group of the CodeLens');
    await vscode.commands.executeCommand('workbench.action.closeEditorsInOtherGroups');

    // From the command palette: at the group around the cursor.
    await vscode.window.showTextDocument(editor.document, vscode.ViewColumn.One);
    const cursorAt = positionOf(editor.document, 'maneuverGroupName="CutIn"');
    editor.selection = new vscode.Selection(cursorAt, cursorAt);
    editor.revealRange(new vscode.Range(cursorAt, cursorAt), vscode.TextEditorRevealType.InCenter);
    await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
    await runFromPalette('Modular2Simple: Open Flattened Preview');
    const atCursor = await waitFor('the preview editor', previewEditor);
    const cutIn = positionOf(atCursor.document, 'name="CutInVehicle.CutIn"').line;
    await waitFor('the preview to open at the group of the cursor', () => (shows(atCursor, cutIn) && !shows(atCursor, 0)) || undefined);
    await screenshot('preview opens at the group of the cursor');

    // Each edit reaches the preview; the time from the edit to the new text is printed (a figure, not a limit).
    const latencies: number[] = [];
    let previous = '27.5';
    for (const value of ['31.25', '32.5', '33.75', '35', '36.25']) {
      let arrived = 0;
      const listener = vscode.workspace.onDidChangeTextDocument((event) => {
        if (event.document === atCursor.document && !arrived && event.document.getText().includes(`value="${value}"`))
          arrived = performance.now();
      });
      const started = performance.now();
      await replaceText(
        editor.document,
        `key="AbsoluteTargetSpeed.value" value="${previous}"`,
        `key="AbsoluteTargetSpeed.value" value="${value}"`,
      );
      await waitFor('the preview to follow the edit', () => arrived > 0 || undefined);
      listener.dispose();
      latencies.push(Math.round(arrived - started));
      previous = value;
    }
    latencies.sort((a, b) => a - b);
    console.log(`edit -> preview in VS Code, examples/main.xosc: median ${latencies[2]} ms, max ${latencies[4]} ms over 5 edits`);
    await post('/figure', { name: 'edit -> preview in VS Code, examples/main.xosc (ms)', values: latencies }).catch(() => undefined);
    assert.ok(!atCursor.document.getText().includes('value="27.5"'));
    // What a person sees: the preview follows the cursor, and its own editor (the group without focus) shows the new value.
    const cursor = positionOf(editor.document, `value="${previous}"`);
    editor.selection = new vscode.Selection(cursor, cursor);
    editor.revealRange(new vscode.Range(cursor, cursor), vscode.TextEditorRevealType.InCenter);
    await waitFor('the preview to scroll to the imported group', () => shows(atCursor, cutIn) || undefined);
    await waitFor('the preview to show the change', () => pageShows(previous, '.editor-group-container:not(.active) .view-lines'));
    await screenshot('preview after an edit');

    // A simple scenario that breaks turns the preview into the few lines saying why: shown from its first line, not scrolled below them.
    const simple = await vscode.workspace.openTextDocument(vscode.Uri.file(path.join(workspaceRoot(), 'lane_change.xosc')));
    await replaceText(simple, 'ManeuverGroup name="CutIn"', 'ManeuverGroup name="CutInRenamed"');
    await waitFor(
      'the preview to say why it cannot flatten',
      () => atCursor.document.getText().includes('cannot be flattened') || undefined,
    );
    await waitFor('the preview to show its first line', () => shows(atCursor, 0) || undefined);
    await waitFor('the explanation to be on screen', () => pageShows('error:', '.editor-group-container:not(.active) .view-lines'));
    await screenshot('preview of a main whose simple scenario broke');
    await vscode.window.showTextDocument(simple, { viewColumn: vscode.ViewColumn.One, preview: false });
    await vscode.commands.executeCommand('workbench.action.files.revert');
    await vscode.window.showTextDocument(editor.document, vscode.ViewColumn.One);
    await revertAndClose();
  },
};
