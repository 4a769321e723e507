import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { Modular2SimpleApi } from '../../../client/src/extension';
import { EXTENSION_ID, type InsideTests, open, positionOf, revertAndClose, TEST_MS, waitFor, workspaceRoot } from './helpers';
import { post, pressKeys, screenshot, typeText } from './harnessClient';

/** Activation, the grammar's colours and typing in the editor. */
export const editingTests: InsideTests = {
  activates: async function () {
    // The workspace holds .xosc files, so VS Code activated the extension without being asked.
    const extension = vscode.extensions.getExtension<Modular2SimpleApi>(EXTENSION_ID);
    assert.ok(extension?.isActive);
    assert.equal(extension.extensionKind, vscode.ExtensionKind.Workspace);
    const editor = await open('main.xosc');
    assert.equal(editor.document.languageId, 'xosc');
    const commands = await vscode.commands.getCommands(true);
    for (const command of ['modular2simple.pack', 'modular2simple.flatten', 'modular2simple.openPreview', 'modular2simple.showStructure']) {
      assert.ok(commands.includes(command), `${command} is not registered`);
    }
  },

  // A healthy server: switching windows, tabs and the preview asks for code actions, lenses and hints, and none fails.
  windowSwitch: async function () {
    this.timeout(TEST_MS);
    // The language client's log, which VS Code keeps in the profile beside the workspace.
    const logs = path.join(workspaceRoot(), '..', 'user-data', 'logs');
    const clientLogs = (): string[] => {
      const found: string[] = [];
      const walk = (folder: string) => {
        for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
          const full = path.join(folder, entry.name);
          if (entry.isDirectory()) walk(full);
          else if (entry.name === 'Modular2Simple Language Server.log') found.push(full);
        }
      };
      if (fs.existsSync(logs)) walk(logs);
      return found;
    };
    const logged = () =>
      clientLogs()
        .map((file) => fs.readFileSync(file, 'utf8'))
        .join('\n');
    const before = logged().length;
    const main = await open('main.xosc');
    const cursorAt = positionOf(main.document, 'key="AbsoluteTargetSpeed.value"');
    main.selection = new vscode.Selection(cursorAt, cursorAt);
    await open('lane_change.xosc');
    for (let round = 0; round < 3; round++) {
      await post('/switchWindow', {});
      await open(round % 2 === 0 ? 'main.xosc' : 'lane_change.xosc');
      await vscode.commands.executeCommand('modular2simple.openPreview');
      await new Promise((resolve) => setTimeout(resolve, 700));
      await post('/switchWindow', {});
    }
    await new Promise((resolve) => setTimeout(resolve, 1500));
    assert.ok(clientLogs().length > 0, `no language client log under ${logs}`);
    const added = logged().slice(before);
    assert.doesNotMatch(added, /failed/i, added);
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
  },

  grammar: async function () {
    const editor = await open('lane_change.xosc');
    const line = positionOf(editor.document, '<Condition parameterAttributes="delay"').line;
    editor.revealRange(new vscode.Range(line, 0, line, 0), vscode.TextEditorRevealType.AtTop);
    // What a person sees: the colour each token is drawn in.
    const colors = await waitFor('the tokens to be drawn', async () => {
      const found = await post<Record<string, string | null>>('/tokenColors', { words: ['parameterAttributes', 'conditionEdge'] });
      return Object.values(found).every((color) => color !== null) ? found : undefined;
    });
    assert.notEqual(colors.parameterAttributes, colors.conditionEdge, 'parameterAttributes is drawn like any other attribute');
    const main = await open('main.xosc');
    const referenceLine = positionOf(main.document, '<ScenarioReference').line;
    main.revealRange(new vscode.Range(referenceLine - 4, 0, referenceLine - 4, 0), vscode.TextEditorRevealType.AtTop);
    const tags = await waitFor('the tags to be drawn', async () => {
      const found = await post<Record<string, string | null>>('/tokenColors', {
        words: ['ScenarioReference', 'ManeuverGroupReference', 'ParameterReference', 'Actors'],
      });
      return Object.values(found).every((color) => color !== null) ? found : undefined;
    });
    assert.notEqual(tags.ScenarioReference, tags.Actors, 'ScenarioReference is drawn like any other element');
    assert.equal(tags.ManeuverGroupReference, tags.ScenarioReference);
    assert.equal(tags.ParameterReference, tags.ScenarioReference);
  },

  typing: async function () {
    const file = path.join(workspaceRoot(), 'typed.xosc');
    fs.writeFileSync(file, '<OpenSCENARIO>\n  \n</OpenSCENARIO>\n');
    const editor = await open('typed.xosc');
    editor.selection = new vscode.Selection(1, 2, 1, 2);
    await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
    await typeText('<Actors selectTriggeringEntities="false">');
    await waitFor(
      'the closing tag',
      () => editor.document.lineAt(1).text === '  <Actors selectTriggeringEntities="false"></Actors>' || undefined,
    );
    assert.equal(
      editor.selection.active.character,
      '  <Actors selectTriggeringEntities="false">'.length,
      'the cursor is not between the tags',
    );
    await pressKeys(['Control+Slash']);
    await waitFor(
      'the line to be commented out',
      () => editor.document.lineAt(1).text === '  <!-- <Actors selectTriggeringEntities="false"></Actors> -->' || undefined,
    );
    await screenshot('typing closes tags and comments lines');
    await revertAndClose();
    fs.rmSync(file);
  },
};
