import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { EXTRACT_GROUP_COMMAND, ExtractGroupRequest } from '../../../common/src/protocol';
import { firstDifference } from '../../../server/src/core/equivalence';
import { fileStem } from '../../../server/src/core/refactor/extractGroup';
import { api, cli, type InsideTests, offersRequest, open, positionOf, requireServerFeature, waitFor, workspaceRoot } from './helpers';
import { pressKeys, quickInput, screenshot } from './harnessClient';

/** The refactorings of issue 19 as a person uses them in VS Code. */
export const refactoringTests: InsideTests = {
  extractToSimple: async function () {
    requireServerFeature(
      this,
      'Extract to a simple scenario',
      offersRequest(ExtractGroupRequest) && !!api().serverCapabilities()?.codeActionProvider,
    );
    // A plain scenario: the example main flattened, whose groups are plain OpenSCENARIO.
    cli(['flatten', 'main.xosc', '-o', 'extract_e2e.xosc']);
    const plainFile = path.join(workspaceRoot(), 'extract_e2e.xosc');
    const before = fs.readFileSync(plainFile, 'utf8');
    const editor = await open('extract_e2e.xosc');
    // Earlier tests rename groups of the example: the first group of the flattened main, whatever its name now.
    const tag = /<ManeuverGroup [^>]*>/.exec(before)?.[0];
    const groupName = tag && /\bname="([^"]+)"/.exec(tag)?.[1];
    assert.ok(tag && groupName, 'the flattened main has a named group');
    const at = positionOf(editor.document, tag, 3);
    editor.selection = new vscode.Selection(at, at);
    editor.revealRange(new vscode.Range(at, at), vscode.TextEditorRevealType.AtTop);
    const actions = await waitFor('the Extract to a simple scenario action', async () => {
      const found = await vscode.commands.executeCommand<vscode.CodeAction[]>(
        'vscode.executeCodeActionProvider',
        editor.document.uri,
        new vscode.Range(at, at),
        'refactor.extract',
      );
      return found.find((action) => action.title.startsWith(`Extract '${groupName}' to a simple scenario`));
    });
    assert.equal(actions.command?.command, EXTRACT_GROUP_COMMAND);
    // As a person: the refactoring from the light bulb's menu, then the pick list of attributes, accepted as proposed.
    const applied = vscode.commands.executeCommand('editor.action.codeAction', { kind: 'refactor.extract.simpleScenario', apply: 'first' });
    await waitFor('the pick list of attributes', async () => {
      const shown = await quickInput();
      return (shown.visible && /Extract to a simple scenario/.test(shown.title)) || undefined;
    });
    await screenshot('Extract to a simple scenario: the pick list of attributes');
    await pressKeys(['Enter']);
    await applied;
    const simpleName = `${fileStem(groupName)}.xosc`;
    const simpleFile = path.join(workspaceRoot(), simpleName);
    await waitFor(
      'the group replaced by a ScenarioReference',
      () => editor.document.getText().includes(`<ScenarioReference scenarioFileName="${simpleName}">`) || undefined,
    );
    const simple = await waitFor('the simple scenario open beside', () =>
      vscode.workspace.textDocuments.find((document) => document.uri.fsPath === simpleFile),
    );
    assert.match(simple.getText(), /parameterAttributes="/);
    await screenshot('Extract to a simple scenario: the main and its new simple scenario');
    assert.ok(await vscode.workspace.saveAll(false));
    // The scenario flattens as it was.
    cli(['flatten', 'extract_e2e.xosc', '-o', 'extract_e2e.flat.xosc']);
    assert.equal(firstDifference(fs.readFileSync(path.join(workspaceRoot(), 'extract_e2e.flat.xosc'), 'utf8'), before), undefined);
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    for (const file of [plainFile, simpleFile, path.join(workspaceRoot(), 'extract_e2e.flat.xosc')]) fs.rmSync(file, { force: true });
  },
};
