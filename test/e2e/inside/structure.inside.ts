import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { StructureRequest, type StructureNode } from '../../../common/src/protocol';
import {
  api,
  flattenTree,
  type InsideTests,
  offersRequest,
  open,
  positionOf,
  replaceText,
  requireServerFeature,
  TEST_MS,
  waitFor,
  workspaceRoot,
} from './helpers';
import { pageShows, screenshot } from './harnessClient';

/** The structure view: what it lists and how it follows edits, renames and files changed on disk. */
export const structureTests: InsideTests = {
  structure: async function () {
    requireServerFeature(this, 'structure', offersRequest(StructureRequest));
    const editor = await open('main.xosc');
    const root = await vscode.commands.executeCommand<StructureNode | undefined>('modular2simple.showStructure', editor.document.uri);
    assert.ok(root, 'no structure');
    const nodes = flattenTree(root);
    assert.equal(root.kind, 'main');
    for (const kind of ['package', 'scenario', 'group'] as const)
      assert.ok(
        nodes.some((node) => node.kind === kind),
        `no ${kind} in the structure`,
      );
    for (const name of ['lane_change.xosc', 'braking.mosc', 'pedestrian']) {
      assert.ok(
        nodes.some((node) => node.label.includes(name)),
        `${name} is not in the structure`,
      );
    }
    // What a person sees: the tree view itself lists the packages and scenarios.
    for (const name of ['braking.mosc', 'lane_change.xosc']) {
      await waitFor(`${name} in the tree view`, () => pageShows(name, '.customview-tree'));
    }
    // The tree follows a save.
    await replaceText(editor.document, 'name="CutInVehicle"', 'name="CutInCar"');
    assert.ok(await editor.document.save());
    await waitFor('the renamed group in the tree view', () => pageShows('CutInCar', '.customview-tree'));
    assert.ok(flattenTree(api().structure() ?? root).some((node) => node.label.includes('CutInCar')));
  },

  structureFollows: async function () {
    this.timeout(TEST_MS);
    requireServerFeature(this, 'rename', !!api().serverCapabilities()?.renameProvider);
    const editor = await open('main.xosc');
    const root = await vscode.commands.executeCommand<StructureNode | undefined>('modular2simple.showStructure', editor.document.uri);
    assert.ok(root);
    const groupLabels = () =>
      flattenTree(api().structure() ?? root)
        .filter((node) => node.kind === 'group' || node.kind === 'missing')
        .map((node) => `${node.label}: ${node.detail ?? ''}`);
    const original = /^CutIn: \d+ attributes? overridden$/;
    assert.ok(
      groupLabels().some((label) => original.test(label)),
      groupLabels().join(', '),
    );
    // A cross-file rename, not saved: the group and its reference change in two files.
    const laneChange = await vscode.workspace.openTextDocument(vscode.Uri.file(path.join(workspaceRoot(), 'lane_change.xosc')));
    await vscode.window.showTextDocument(laneChange);
    const edit = await waitFor('a rename edit', async () => {
      const found = await vscode.commands.executeCommand<vscode.WorkspaceEdit | undefined>(
        'vscode.executeDocumentRenameProvider',
        laneChange.uri,
        positionOf(laneChange, 'name="CutIn"', 'name="Cut'.length),
        'CutInLeft',
      );
      return found && found.size > 1 ? found : undefined;
    });
    assert.ok(await vscode.workspace.applyEdit(edit));
    // The rename reaches the server as two files' changes: the tree may be drawn in between, the group missing for a moment.
    await waitFor(
      'the renamed group in the tree view, and no "no such group"',
      async () => (await pageShows('CutInLeft', '.customview-tree')) && !(await pageShows('no such group', '.customview-tree')),
    );
    assert.ok(
      groupLabels().some((label) => label.startsWith('CutInLeft:')),
      groupLabels().join(', '),
    );
    await screenshot('structure follows a cross-file rename');
    // Undone without saving: the tree follows back.
    for (const document of [laneChange, editor.document]) {
      await vscode.window.showTextDocument(document);
      await vscode.commands.executeCommand('workbench.action.files.revert');
    }
    await waitFor('the original group in the tree view', () => groupLabels().some((label) => original.test(label)) || undefined);
    // A file changed on disk, not open in the editor: the reference now names a group that does not exist.
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    const file = path.join(workspaceRoot(), 'lane_change.xosc');
    const saved = fs.readFileSync(file, 'utf8');
    try {
      fs.writeFileSync(file, saved.replace('name="CutIn"', 'name="CutInRight"'));
      await waitFor('the tree to show the missing group', () => pageShows('no such group', '.customview-tree'));
      await screenshot('structure follows a file changed on disk');
    } finally {
      fs.writeFileSync(file, saved);
    }
    await waitFor('the tree to follow the restored file', async () => !(await pageShows('no such group', '.customview-tree')) || undefined);
  },
};
