import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import * as vscode from 'vscode';
import { StructureRequest } from '../../../common/src/protocol';
import {
  api,
  type InsideTests,
  offersRequest,
  packageUri,
  positionOf,
  replaceText,
  requireServerFeature,
  revertAndClose,
  waitFor,
  workspaceRoot,
  zipEntries,
} from './helpers';
import { clickText, pageShows, post } from './harnessClient';

/** .mosc packages: the package view, editing and saving inside them, language features and rename inside them. */
export const packageTests: InsideTests = {
  packageView: async function () {
    await vscode.commands.executeCommand('vscode.open', vscode.Uri.file(path.join(workspaceRoot(), 'braking.mosc')));
    const shown = await waitFor('the package view to list the entries', async () => {
      const found = await post<{ found: boolean }>('/findText', { text: 'hard_brake.xosc' });
      return found.found || undefined;
    });
    assert.ok(shown);
    // A click on an entry opens it in place, through the mosc: file system.
    assert.ok(await clickText('hard_brake.xosc'), 'no link to hard_brake.xosc');
    await waitFor(
      'hard_brake.xosc to open',
      () =>
        vscode.window.activeTextEditor?.document.uri.toString() === packageUri('braking.mosc', 'hard_brake.xosc').toString() || undefined,
    );
    if (offersRequest(StructureRequest)) {
      await vscode.commands.executeCommand('vscode.open', vscode.Uri.file(path.join(workspaceRoot(), 'braking.mosc')));
      await waitFor('the package view', () => pageShows('Show Structure'));
      assert.ok(await clickText('Show Structure'));
      await waitFor('the structure of the package', () => pageShows('hard_brake.xosc', '.customview-tree'));
    }
    const entries = await vscode.workspace.fs.readDirectory(packageUri('braking.mosc'));
    assert.deepEqual(entries.map(([name]) => name).sort(), ['hard_brake.xosc', 'main.xosc']);
    const nested = await vscode.workspace.fs.readDirectory(packageUri('nested.mosc'));
    assert.deepEqual(nested, [
      ['braking.mosc', vscode.FileType.Directory],
      ['main.xosc', vscode.FileType.File],
    ]);
  },

  packageEdit: async function () {
    const archive = path.join(workspaceRoot(), 'nested.mosc');
    const before = await zipEntries(archive);
    // A file two packages deep: nested.mosc holds braking.mosc, which holds hard_brake.xosc.
    // Two files of one archive edited at once: saving the second must keep what saving the first wrote.
    const mainDocument = await vscode.workspace.openTextDocument(packageUri('nested.mosc', 'main.xosc'));
    await vscode.window.showTextDocument(mainDocument);
    await replaceText(mainDocument, '<OpenSCENARIO>', '<OpenSCENARIO>\n  <!-- edited main -->');
    const uri = packageUri('nested.mosc', 'braking.mosc', 'hard_brake.xosc');
    const document = await vscode.workspace.openTextDocument(uri);
    assert.equal(document.languageId, 'xosc');
    await vscode.window.showTextDocument(document);
    await replaceText(document, '<OpenSCENARIO>', '<OpenSCENARIO>\n  <!-- edited inside two packages -->');
    assert.ok(await document.save(), 'save failed');
    assert.equal((await zipEntries(archive)).get('main.xosc'), before.get('main.xosc'), 'an unsaved file was written');
    await vscode.window.showTextDocument(mainDocument);
    assert.ok(await mainDocument.save(), 'saving the second file of the archive failed');
    const after = await zipEntries(archive);
    assert.deepEqual([...after.keys()].sort(), [...before.keys()].sort());
    assert.equal(after.get('main.xosc'), mainDocument.getText());
    const innerAfter = await JSZip.loadAsync(
      await (await JSZip.loadAsync(fs.readFileSync(archive))).file('braking.mosc')!.async('uint8array'),
    );
    assert.equal(
      await innerAfter.file('hard_brake.xosc')!.async('string'),
      document.getText(),
      'saving the second file lost the first change',
    );
    const inner = await JSZip.loadAsync(await (await JSZip.loadAsync(fs.readFileSync(archive))).file('braking.mosc')!.async('uint8array'));
    const saved = await inner.file('hard_brake.xosc')!.async('string');
    assert.ok(saved.includes('<!-- edited inside two packages -->'), 'the change is not in the archive');
    assert.equal(saved, document.getText());
    assert.ok(
      fs.readdirSync(workspaceRoot()).every((name) => !name.endsWith('.tmp')),
      'a temporary file was left behind',
    );
  },

  brokenPackage: async function () {
    const archive = path.join(workspaceRoot(), 'broken.mosc');
    const bytes = fs.readFileSync(archive);
    await assert.rejects(() => Promise.resolve(vscode.workspace.openTextDocument(packageUri('broken.mosc', 'main.xosc'))), /ZIP|zip/);
    await assert.rejects(
      () => Promise.resolve(vscode.workspace.fs.writeFile(packageUri('broken.mosc', 'main.xosc'), Buffer.from('<OpenSCENARIO/>'))),
      /ZIP|zip/,
    );
    assert.deepEqual(fs.readFileSync(archive), bytes, 'the broken archive was changed');
    await vscode.commands.executeCommand('vscode.open', vscode.Uri.file(archive));
    await waitFor(
      'the package view to report the broken archive',
      async () => (await post<{ found: boolean }>('/findText', { text: 'not a readable ZIP' })).found || undefined,
    );
  },

  insidePackage: async function () {
    requireServerFeature(this, 'go to definition', !!api().serverCapabilities()?.definitionProvider);
    const main = packageUri('braking.mosc', 'main.xosc');
    const editor = await vscode.window.showTextDocument(await vscode.workspace.openTextDocument(main));
    const cursor = positionOf(editor.document, 'scenarioFileName="hard_brake.xosc"', 'scenarioFileName="hard'.length);
    const locations = await waitFor('a definition inside the package', async () => {
      const found = await vscode.commands.executeCommand<(vscode.Location | vscode.LocationLink)[]>(
        'vscode.executeDefinitionProvider',
        main,
        cursor,
      );
      return found.length > 0 ? found : undefined;
    });
    const target = 'targetUri' in locations[0] ? locations[0].targetUri : locations[0].uri;
    assert.equal(target.toString(), packageUri('braking.mosc', 'hard_brake.xosc').toString());
    const opened = await vscode.window.showTextDocument(await vscode.workspace.openTextDocument(target));
    assert.ok(opened.document.getText().includes('name="HardBrake"'));
    // Diagnostics reach files inside packages too: a bad key shows up where it is.
    await vscode.window.showTextDocument(editor.document);
    await replaceText(editor.document, 'key="SimulationTimeCondition.value"', 'key="SimulationTimeCondition.valeu"');
    const keyLine = positionOf(editor.document, 'SimulationTimeCondition.valeu').line;
    await waitFor('a diagnostic inside the package', () =>
      vscode.languages.getDiagnostics(main).find((d) => d.range.start.line === keyLine),
    );
    await revertAndClose();
  },

  renameInPackage: async function () {
    requireServerFeature(this, 'rename', !!api().serverCapabilities()?.renameProvider);
    const uri = packageUri('braking.mosc', 'hard_brake.xosc');
    const document = await vscode.workspace.openTextDocument(uri);
    await vscode.window.showTextDocument(document);
    const position = positionOf(document, 'name="HardBrake"', 'name="Hard'.length);
    const edit = await waitFor('a rename edit', async () => {
      const found = await vscode.commands.executeCommand<vscode.WorkspaceEdit | undefined>(
        'vscode.executeDocumentRenameProvider',
        uri,
        position,
        'SuddenBrake',
      );
      return found && found.size > 0 ? found : undefined;
    });
    const touched = edit.entries().map(([target]) => target.toString());
    assert.ok(touched.includes(uri.toString()), `the group itself is not renamed: ${touched.join(', ')}`);
    assert.ok(touched.includes(packageUri('braking.mosc', 'main.xosc').toString()), 'the package main is not updated');
    assert.ok(await vscode.workspace.applyEdit(edit));
    // Saved at once, as F2 with refactoring auto-save does: two of the files share one archive.
    const saved = await Promise.all(edit.entries().map(async ([target]) => (await vscode.workspace.openTextDocument(target)).save()));
    assert.ok(saved.every(Boolean), 'saving the renamed files failed');
    const entries = await zipEntries(path.join(workspaceRoot(), 'braking.mosc'));
    assert.match(entries.get('hard_brake.xosc') ?? '', /<ManeuverGroup name="SuddenBrake"/);
    assert.match(entries.get('main.xosc') ?? '', /maneuverGroupName="SuddenBrake"/);
    assert.match(fs.readFileSync(path.join(workspaceRoot(), 'main.xosc'), 'utf8'), /maneuverGroupName="Brake\.SuddenBrake"/);
  },
};
