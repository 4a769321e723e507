import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { firstDifference } from '../../../server/src/core/equivalence';
import { FlattenToFileRequest, PackRequest } from '../../../common/src/protocol';
import {
  acceptSaveDialog,
  cli,
  type InsideTests,
  offersRequest,
  open,
  replaceText,
  requireServerFeature,
  TEST_MS,
  waitFor,
  waitForPage,
  workspaceRoot,
  zipEntries,
} from './helpers';
import { clickText, pageShows, pressKeys, quickInput, runFromPalette, screenshot } from './harnessClient';

/** Answers the Pack command's first question (where roads and catalogs go) with its first choice: they stay where they are, as the CLI's pack without --self-contained. */
async function keepFilesOutsidePackage(): Promise<void> {
  await waitFor('the question where roads and catalogs go', async () => {
    const shown = await quickInput();
    return (shown.visible && shown.title === 'Pack into .mosc' && shown.value === '') || undefined;
  });
  await pressKeys(['Enter']);
}

/** Pack and Flatten from the palette and the explorer, compared with the CLI's output. */
export const packAndFlattenTests: InsideTests = {
  pack: async function () {
    requireServerFeature(this, 'pack', offersRequest(PackRequest));
    const root = workspaceRoot();
    await open('pedestrian/main.xosc');
    await runFromPalette('Modular2Simple: Pack into .mosc');
    await keepFilesOutsidePackage();
    await acceptSaveDialog('pedestrian.mosc');
    const written = path.join(root, 'pedestrian.mosc');
    await waitFor('pedestrian.mosc', () => fs.existsSync(written) || undefined);
    const expected = path.join(os.tmpdir(), `m2s-cli-pack-${process.pid}.mosc`);
    cli(['pack', path.join(root, 'pedestrian'), '-o', expected]);
    const [ours, theirs] = [await zipEntries(written), await zipEntries(expected)];
    assert.deepEqual([...ours.keys()].sort(), [...theirs.keys()].sort());
    for (const [name, text] of theirs) assert.equal(firstDifference(ours.get(name) ?? '', text), undefined, `${name} differs`);

    // From files selected in the explorer: each stored at the root of the package.
    const selected = ['pedestrian/main.xosc', 'crossing.xosc'].map((file) => vscode.Uri.file(path.join(root, file)));
    const output = path.join(root, 'selected.mosc');
    assert.equal(await vscode.commands.executeCommand('modular2simple.pack', selected[0], selected, { output }), output);
    const expectedFiles = path.join(os.tmpdir(), `m2s-cli-pack-files-${process.pid}.mosc`);
    cli(['pack', ...selected.map((uri) => uri.fsPath), '-o', expectedFiles]);
    assert.deepEqual(await zipEntries(output), await zipEntries(expectedFiles));
  },

  flatten: async function () {
    this.timeout(TEST_MS);
    requireServerFeature(this, 'flattenToFile', offersRequest(FlattenToFileRequest));
    const root = workspaceRoot();
    await open('main.xosc');
    await runFromPalette('Modular2Simple: Flatten to .xosc');
    // One naming convention (client/src/naming.ts): the package's name, .flattened.xosc, proposed in a save dialog.
    const written = path.join(root, `${path.basename(root)}.flattened.xosc`);
    await acceptSaveDialog(path.basename(written));
    await waitFor(path.basename(written), () => fs.existsSync(written) || undefined);
    const expected = path.join(os.tmpdir(), `m2s-cli-flatten-${process.pid}.xosc`);
    cli(['flatten', path.join(root, 'main.xosc'), '-o', expected]);
    const difference = firstDifference(fs.readFileSync(written, 'utf8'), fs.readFileSync(expected, 'utf8'));
    assert.equal(difference, undefined, difference);
    assert.ok(fs.readFileSync(written, 'utf8').includes('Pedestrian.Walker.Crossing'));

    // Flattening again: the save dialog asks before replacing the file; Escape keeps it, Enter replaces it.
    fs.writeFileSync(written, '<!-- kept -->');
    const overwriteQuestion = async () => /already exists/.test((await quickInput()).title) || undefined;
    await runFromPalette('Modular2Simple: Flatten to .xosc');
    await acceptSaveDialog(path.basename(written));
    await waitFor('the overwrite question', overwriteQuestion);
    await screenshot('flatten asks before overwriting');
    await pressKeys(['Escape']);
    await waitFor('the save dialog again', async () => ((await quickInput()).visible && !(await overwriteQuestion())) || undefined);
    await pressKeys(['Escape']);
    await waitFor('the dialog to close', async () => !(await quickInput()).visible || undefined);
    await new Promise((resolve) => setTimeout(resolve, 500));
    assert.equal(fs.readFileSync(written, 'utf8'), '<!-- kept -->');
    await runFromPalette('Modular2Simple: Flatten to .xosc');
    await acceptSaveDialog(path.basename(written));
    await waitFor('the overwrite question', overwriteQuestion);
    await pressKeys(['Enter']);
    await waitFor('the file to be replaced', () => fs.readFileSync(written, 'utf8') !== '<!-- kept -->' || undefined);
    assert.equal(firstDifference(fs.readFileSync(written, 'utf8'), fs.readFileSync(expected, 'utf8')), undefined);

    // From the explorer's context menu on a .mosc: the package flattened beside it, under the same convention.
    const braking = vscode.Uri.file(path.join(root, 'braking.mosc'));
    const flattening = vscode.commands.executeCommand<string | undefined>('modular2simple.flatten', braking, [braking]);
    await acceptSaveDialog('braking.flattened.xosc');
    const fromPackage = await flattening;
    assert.equal(fromPackage, path.join(root, 'braking.flattened.xosc'));
    const expectedPackage = path.join(os.tmpdir(), `m2s-cli-flatten-braking-${process.pid}.xosc`);
    cli(['flatten', braking.fsPath, '-o', expectedPackage]);
    assert.equal(firstDifference(fs.readFileSync(fromPackage, 'utf8'), fs.readFileSync(expectedPackage, 'utf8')), undefined);
  },

  packUnsaved: async function () {
    this.timeout(TEST_MS);
    requireServerFeature(this, 'pack', offersRequest(PackRequest));
    const root = workspaceRoot();
    const editor = await open('main.xosc');
    await replaceText(
      editor.document,
      'key="RelativeDistanceCondition.value" value="12"',
      'key="RelativeDistanceCondition.value" value="17.5"',
    );
    assert.ok(editor.document.isDirty);
    await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
    await runFromPalette('Modular2Simple: Pack into .mosc');
    await keepFilesOutsidePackage();
    const written = path.join(root, `${path.basename(root)}.mosc`);
    await acceptSaveDialog(path.basename(written));
    await waitFor(path.basename(written), () => fs.existsSync(written) || undefined);
    // The package holds what the editor shows, the file was saved to match, and the message says so.
    const packed = await zipEntries(written);
    assert.ok(
      packed.get('main.xosc')?.includes('key="RelativeDistanceCondition.value" value="17.5"'),
      'the package holds the saved text, not the edited one',
    );
    assert.equal(packed.get('main.xosc'), editor.document.getText());
    assert.ok(!editor.document.isDirty, 'main.xosc was not saved');
    await waitFor('the message naming the saved file', () => pageShows('saved main.xosc first'));
    await screenshot('pack saves unsaved files first');
    fs.rmSync(written);
  },

  flattenAnyway: async function () {
    this.timeout(TEST_MS);
    requireServerFeature(this, 'flattenToFile', offersRequest(FlattenToFileRequest));
    const root = workspaceRoot();
    const editor = await open('main.xosc');
    await replaceText(editor.document, 'key="LaneChangeActionDynamics.value"', 'key="LaneChangeActionDynamic.value"');
    assert.ok(await editor.document.save());
    const written = path.join(root, `${path.basename(root)}.flattened.xosc`);
    fs.rmSync(written, { force: true });
    try {
      await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
      await runFromPalette('Modular2Simple: Flatten to .xosc');
      await acceptSaveDialog(path.basename(written));
      // Refused, with the offer that names what writing anyway skips.
      await waitForPage('Write Anyway');
      // The offer names the skipped key.
      await waitForPage('LaneChangeActionDynamic.value');
      assert.ok(!fs.existsSync(written), 'a refused flatten wrote its output');
      await screenshot('flatten refused offers to write anyway');
      assert.ok(await clickText('Write Anyway'), 'no Write Anyway button');
      await waitFor(path.basename(written), () => fs.existsSync(written) || undefined);
      const expected = path.join(os.tmpdir(), `m2s-cli-flatten-force-${process.pid}.xosc`);
      cli(['flatten', path.join(root, 'main.xosc'), '-o', expected, '--force']);
      assert.equal(firstDifference(fs.readFileSync(written, 'utf8'), fs.readFileSync(expected, 'utf8')), undefined);
    } finally {
      await replaceText(editor.document, 'key="LaneChangeActionDynamic.value"', 'key="LaneChangeActionDynamics.value"');
      await editor.document.save();
    }
  },
};
