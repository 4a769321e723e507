import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { NewScenarioRequest } from '../../../common/src/protocol';
import { BIRDS_EYE_FILES } from '../birdsEyeSetup';
import { pressKeys, quickInput, screenshot, typeText } from './harnessClient';
import { type InsideTests, offersRequest, requireServerFeature, TEST_MS, waitFor, workspaceRoot } from './helpers';

async function waitForQuickInput(what: string, matches: (shown: { title: string; value: string }) => boolean): Promise<void> {
  await waitFor(what, async () => {
    const shown = await quickInput();
    return (shown.visible && matches(shown)) || undefined;
  });
}

/** New Modular Scenario… from a folder's context menu, answered as a person answers its questions. */
export const newScenarioTests: InsideTests = {
  newScenario: async function () {
    this.timeout(TEST_MS);
    requireServerFeature(this, 'newScenario', offersRequest(NewScenarioRequest));
    const root = workspaceRoot();
    const road = path.join(root, BIRDS_EYE_FILES.roadFolder, 'e6mini.xodr');
    if (!fs.existsSync(road)) {
      console.log(`skipped: ${road} is absent (no shared esmini roads)`);
      this.skip();
    }
    // A folder two levels below the workspace, the road one level below it: the path written must climb.
    const folder = path.join(root, 'scenarios', 'highway');
    fs.mkdirSync(folder, { recursive: true });
    const running = vscode.commands.executeCommand<vscode.Uri | undefined>('modular2simple.newScenario', vscode.Uri.file(folder));
    await waitForQuickInput('the road network question', (shown) => /road network/.test(shown.title));
    await typeText('e6mini');
    await screenshot('New Modular Scenario asks for the road network');
    await pressKeys(['Enter']);
    await waitForQuickInput(
      'the file name question, proposing main.xosc',
      (shown) => /file name/.test(shown.title) && shown.value === 'main.xosc',
    );
    await pressKeys(['Enter']);
    const created = await running;
    const written = path.join(folder, 'main.xosc');
    assert.equal(created?.fsPath, written);
    const text = fs.readFileSync(written, 'utf8');
    assert.ok(text.includes('<LogicFile filepath="../../roads/e6mini.xodr"/>'), text);
    assert.match(text, /<LanePosition roadId="[^"]+" laneId="-\d+" s="[\d.]+"/);
    const editor = await waitFor('the new scenario in the editor', () =>
      vscode.window.activeTextEditor?.document.uri.fsPath === written ? vscode.window.activeTextEditor : undefined,
    );
    // The server has read it once it answers for it; then no problem may show.
    await waitFor(
      'the outline of the new scenario',
      async () =>
        ((await vscode.commands.executeCommand<unknown[]>('vscode.executeDocumentSymbolProvider', editor.document.uri))?.length ?? 0) > 0 ||
        undefined,
    );
    await new Promise((resolve) => setTimeout(resolve, 2_000));
    assert.deepEqual(
      vscode.languages.getDiagnostics(editor.document.uri).map((diagnostic) => diagnostic.message),
      [],
    );
    const importHere = text.indexOf('<!-- Import behaviours');
    editor.revealRange(
      new vscode.Range(editor.document.positionAt(importHere), editor.document.positionAt(importHere)),
      vscode.TextEditorRevealType.InCenter,
    );
    await screenshot('New Modular Scenario wrote a main with an ego on e6mini');

    // Again in the same folder: main.xosc is taken, so main-2.xosc is proposed; Escape writes nothing.
    const again = vscode.commands.executeCommand<vscode.Uri | undefined>('modular2simple.newScenario', vscode.Uri.file(folder));
    await waitForQuickInput('the road network question', (shown) => /road network/.test(shown.title));
    await typeText('e6mini');
    await pressKeys(['Enter']);
    await waitForQuickInput(
      'the file name question, proposing main-2.xosc',
      (shown) => /file name/.test(shown.title) && shown.value === 'main-2.xosc',
    );
    await pressKeys(['Escape']);
    assert.equal(await again, undefined);
    assert.deepEqual(fs.readdirSync(folder), ['main.xosc']);
    assert.equal(fs.readFileSync(written, 'utf8'), text, 'never overwritten');
  },
};
