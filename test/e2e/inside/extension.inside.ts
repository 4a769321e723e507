import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import JSZip from 'jszip';
import * as vscode from 'vscode';
import type { Modular2SimpleApi } from '../../../client/src/extension';
import { firstDifference } from '../../../server/src/core/equivalence';
import { FlattenToFileRequest, PackRequest, RunEsminiRequest, StructureRequest, type RunEsminiResult, type StructureNode } from '../../../common/src/protocol';
import { HARNESS_ENV, INSIDE_TESTS } from '../titles';
import { clickText, pageShows, post, pressKeys, quickInput, runFromPalette, screenshot, typeText } from './harnessClient';

const EXTENSION_ID = 'modular2simple.modular2simple';

export function workspaceRoot(): string {
  const root = process.env[HARNESS_ENV.workspace];
  assert.ok(root, `${HARNESS_ENV.workspace} is not set`);
  return root;
}

export async function waitFor<T>(what: string, probe: () => T | undefined | false | Promise<T | undefined | false>, timeoutMs = 20_000): Promise<T> {
  const deadline = Date.now() + timeoutMs;
  let last: unknown;
  while (Date.now() < deadline) {
    try {
      const value = await probe();
      if (value !== undefined && value !== false) return value;
    } catch (error) {
      last = error;
    }
    await new Promise((resolve) => setTimeout(resolve, 100));
  }
  throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}${last ? ` (last error: ${(last as Error).message})` : ''}`);
}

export function api(): Modular2SimpleApi {
  const extension = vscode.extensions.getExtension<Modular2SimpleApi>(EXTENSION_ID);
  assert.ok(extension?.isActive, 'the extension is not active');
  return extension.exports;
}

/** Skips a test whose feature the language server does not offer yet (the server is built in parallel). */
function requireServerFeature(context: Mocha.Context, feature: string, offered: boolean): void {
  if (!offered) {
    console.log(`skipped: the language server does not offer ${feature}`);
    context.skip();
  }
}

function offersRequest(request: { method: string }): boolean {
  const experimental = api().serverCapabilities()?.experimental as { requests?: string[] } | undefined;
  return experimental?.requests?.includes(request.method) ?? false;
}

export async function open(relative: string): Promise<vscode.TextEditor> {
  const document = await vscode.workspace.openTextDocument(vscode.Uri.file(path.join(workspaceRoot(), relative)));
  return vscode.window.showTextDocument(document, { viewColumn: vscode.ViewColumn.One, preview: false });
}

export function positionOf(document: vscode.TextDocument, text: string, offsetInText = 0): vscode.Position {
  const index = document.getText().indexOf(text);
  assert.ok(index >= 0, `${path.basename(document.uri.path)} does not contain ${text}`);
  return document.positionAt(index + offsetInText);
}

export async function replaceText(document: vscode.TextDocument, from: string, to: string): Promise<void> {
  const start = positionOf(document, from);
  const edit = new vscode.WorkspaceEdit();
  edit.replace(document.uri, new vscode.Range(start, start.translate(0, from.length)), to);
  assert.ok(await vscode.workspace.applyEdit(edit), `could not replace ${from}`);
}

export async function revertAndClose(): Promise<void> {
  await vscode.commands.executeCommand('workbench.action.files.revert');
  await vscode.commands.executeCommand('workbench.action.closeAllEditors');
}

export function packageUri(...parts: string[]): vscode.Uri {
  return vscode.Uri.from({ scheme: 'mosc', path: path.posix.join(workspaceRoot(), ...parts) });
}

async function zipEntries(file: string): Promise<Map<string, string>> {
  const zip = await JSZip.loadAsync(fs.readFileSync(file));
  const entries = new Map<string, string>();
  for (const entry of Object.values(zip.files)) if (!entry.dir) entries.set(entry.name, await entry.async('string'));
  return entries;
}

function cli(args: string[]): void {
  const cliPath = process.env[HARNESS_ENV.cli];
  assert.ok(cliPath, `${HARNESS_ENV.cli} is not set`);
  execFileSync(process.execPath, [cliPath, ...args], { cwd: workspaceRoot(), env: { ...process.env, ELECTRON_RUN_AS_NODE: '1' } });
}

/** Waits for the save dialog to propose `name`, then accepts it with Enter, as a person does. */
async function acceptSaveDialog(name: string): Promise<void> {
  await waitFor(`the save dialog proposing ${name}`, async () => {
    const shown = await quickInput();
    return (shown.visible && shown.value.endsWith(`/${name}`)) || undefined;
  });
  await pressKeys(['Enter']);
}

function flattenTree(node: StructureNode): StructureNode[] {
  return [node, ...node.children.flatMap(flattenTree)];
}

/** A scenario whose stop condition is a ${...} over two root parameters (it evaluates to 3). */
const EXPRESSIONS = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" description="expressions" author="tests"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="a" parameterType="double" value="6"/>
    <ParameterDeclaration name="b" parameterType="double" value="4"/>
  </ParameterDeclarations>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="Ego"/>
  </Entities>
  <Storyboard>
    <Init>
      <Actions/>
    </Init>
    <StopTrigger>
      <ConditionGroup>
        <Condition name="End" delay="0" conditionEdge="rising">
          <ByValueCondition>
            <SimulationTimeCondition value="\${2*$a/$b}" rule="greaterThan"/>
          </ByValueCondition>
        </Condition>
      </ConditionGroup>
    </StopTrigger>
  </Storyboard>
</OpenSCENARIO>
`;

export function defineExtensionTests(): void {
  describe('Modular2Simple in a real VS Code', function () {
    this.timeout(45_000);

    before(async function () {
      this.timeout(60_000);
      const extension = vscode.extensions.getExtension<Modular2SimpleApi>(EXTENSION_ID);
      assert.ok(extension, `${EXTENSION_ID} is not installed`);
      await waitFor('the extension to activate', () => extension.isActive, 30_000);
      await extension.exports.serverReady;
    });

    beforeEach(async () => {
      await vscode.commands.executeCommand('notifications.clearAll');
    });

    afterEach(async function () {
      await screenshot(`${this.currentTest?.state === 'failed' ? 'FAILED ' : ''}${this.currentTest?.title ?? 'unnamed'}`).catch(() => undefined);
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    });

    it(INSIDE_TESTS.activates, async () => {
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
    });

    it(INSIDE_TESTS.grammar, async () => {
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
        const found = await post<Record<string, string | null>>('/tokenColors', { words: ['ScenarioReference', 'ManeuverGroupReference', 'ParameterReference', 'Actors'] });
        return Object.values(found).every((color) => color !== null) ? found : undefined;
      });
      assert.notEqual(tags.ScenarioReference, tags.Actors, 'ScenarioReference is drawn like any other element');
      assert.equal(tags.ManeuverGroupReference, tags.ScenarioReference);
      assert.equal(tags.ParameterReference, tags.ScenarioReference);
    });

    it(INSIDE_TESTS.typing, async () => {
      const file = path.join(workspaceRoot(), 'typed.xosc');
      fs.writeFileSync(file, '<OpenSCENARIO>\n  \n</OpenSCENARIO>\n');
      const editor = await open('typed.xosc');
      editor.selection = new vscode.Selection(1, 2, 1, 2);
      await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
      await typeText('<Actors selectTriggeringEntities="false">');
      await waitFor('the closing tag', () => editor.document.lineAt(1).text === '  <Actors selectTriggeringEntities="false"></Actors>' || undefined, 5_000);
      assert.equal(editor.selection.active.character, '  <Actors selectTriggeringEntities="false">'.length, 'the cursor is not between the tags');
      await pressKeys(['Control+Slash']);
      await waitFor('the line to be commented out', () => editor.document.lineAt(1).text === '  <!-- <Actors selectTriggeringEntities="false"></Actors> -->' || undefined, 5_000);
      await screenshot('typing closes tags and comments lines');
      await revertAndClose();
      fs.rmSync(file);
    });

    it(INSIDE_TESTS.packageView, async () => {
      await vscode.commands.executeCommand('vscode.open', vscode.Uri.file(path.join(workspaceRoot(), 'braking.mosc')));
      const shown = await waitFor('the package view to list the entries', async () => {
        const found = await post<{ found: boolean }>('/findText', { text: 'hard_brake.xosc' });
        return found.found || undefined;
      });
      assert.ok(shown);
      // A click on an entry opens it in place, through the mosc: file system.
      assert.ok(await clickText('hard_brake.xosc'), 'no link to hard_brake.xosc');
      await waitFor('hard_brake.xosc to open', () => vscode.window.activeTextEditor?.document.uri.toString() === packageUri('braking.mosc', 'hard_brake.xosc').toString() || undefined);
      if (offersRequest(StructureRequest)) {
        await vscode.commands.executeCommand('vscode.open', vscode.Uri.file(path.join(workspaceRoot(), 'braking.mosc')));
        await waitFor('the package view', () => pageShows('Show Structure'));
        assert.ok(await clickText('Show Structure'));
        await waitFor('the structure of the package', () => pageShows('hard_brake.xosc', '.customview-tree'));
      }
      const entries = await vscode.workspace.fs.readDirectory(packageUri('braking.mosc'));
      assert.deepEqual(entries.map(([name]) => name).sort(), ['hard_brake.xosc', 'main.xosc']);
      const nested = await vscode.workspace.fs.readDirectory(packageUri('nested.mosc'));
      assert.deepEqual(nested, [['braking.mosc', vscode.FileType.Directory], ['main.xosc', vscode.FileType.File]]);
    });

    it(INSIDE_TESTS.packageEdit, async () => {
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
      const innerAfter = await JSZip.loadAsync(await (await JSZip.loadAsync(fs.readFileSync(archive))).file('braking.mosc')!.async('uint8array'));
      assert.equal(await innerAfter.file('hard_brake.xosc')!.async('string'), document.getText(), 'saving the second file lost the first change');
      const inner = await JSZip.loadAsync(await (await JSZip.loadAsync(fs.readFileSync(archive))).file('braking.mosc')!.async('uint8array'));
      const saved = await inner.file('hard_brake.xosc')!.async('string');
      assert.ok(saved.includes('<!-- edited inside two packages -->'), 'the change is not in the archive');
      assert.equal(saved, document.getText());
      assert.ok(fs.readdirSync(workspaceRoot()).every((name) => !name.endsWith('.tmp')), 'a temporary file was left behind');
    });

    it(INSIDE_TESTS.brokenPackage, async () => {
      const archive = path.join(workspaceRoot(), 'broken.mosc');
      const bytes = fs.readFileSync(archive);
      await assert.rejects(() => Promise.resolve(vscode.workspace.openTextDocument(packageUri('broken.mosc', 'main.xosc'))), /ZIP|zip/);
      await assert.rejects(() => Promise.resolve(vscode.workspace.fs.writeFile(packageUri('broken.mosc', 'main.xosc'), Buffer.from('<OpenSCENARIO/>'))), /ZIP|zip/);
      assert.deepEqual(fs.readFileSync(archive), bytes, 'the broken archive was changed');
      await vscode.commands.executeCommand('vscode.open', vscode.Uri.file(archive));
      await waitFor('the package view to report the broken archive', async () => (await post<{ found: boolean }>('/findText', { text: 'not a readable ZIP' })).found || undefined);
    });

    it(INSIDE_TESTS.diagnostic, async function () {
      requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
      const editor = await open('main.xosc');
      const uri = editor.document.uri;
      await waitFor('the example to check clean', () => vscode.languages.getDiagnostics(uri).every((d) => d.severity !== vscode.DiagnosticSeverity.Error) || undefined);
      await replaceText(editor.document, 'key="AbsoluteTargetSpeed.value"', 'key="AbsoluteTargetSped.value"');
      const keyLine = positionOf(editor.document, 'AbsoluteTargetSped.value').line;
      const diagnostic = await waitFor('a diagnostic on the bad key', () => vscode.languages.getDiagnostics(uri).find((d) => d.range.start.line === keyLine));
      assert.match(diagnostic.message, /AbsoluteTargetSped\.value|AbsoluteTargetSpeed/);
      editor.revealRange(diagnostic.range, vscode.TextEditorRevealType.InCenter);
      editor.selection = new vscode.Selection(diagnostic.range.start, diagnostic.range.start);
      await vscode.commands.executeCommand('editor.action.marker.next');
      await screenshot('diagnostic on a bad key (marker)');
      await revertAndClose();
    });

    it(INSIDE_TESTS.completion, async function () {
      requireServerFeature(this, 'completion', !!api().serverCapabilities()?.completionProvider);
      const editor = await open('main.xosc');
      const anchor = '<ParameterReference key="RelativeDistanceCondition.value" value="12"/>';
      const at = positionOf(editor.document, anchor);
      const edit = new vscode.WorkspaceEdit();
      edit.insert(editor.document.uri, at.translate(0, anchor.length), `\n${' '.repeat(at.character)}<ParameterReference key="" value="1"/>`);
      await vscode.workspace.applyEdit(edit);
      const cursor = new vscode.Position(at.line + 1, at.character + '<ParameterReference key="'.length);
      editor.selection = new vscode.Selection(cursor, cursor);
      const list = await waitFor('completion items', async () => {
        const result = await vscode.commands.executeCommand<vscode.CompletionList>('vscode.executeCompletionItemProvider', editor.document.uri, cursor);
        return result.items.length > 0 ? result : undefined;
      });
      const labels = list.items.map((item) => (typeof item.label === 'string' ? item.label : item.label.label));
      for (const expected of ['dynamicsShape', 'delay', 'SimulationTimeCondition.value']) {
        assert.ok(labels.some((label) => label === expected || label.endsWith(`.${expected}`)), `completion lacks ${expected}: ${labels.join(', ')}`);
      }
      assert.ok(!labels.includes('AbsoluteTargetSpeed.value'), `a key already given is offered again: ${labels.join(', ')}`);
      await vscode.commands.executeCommand('editor.action.triggerSuggest');
      await waitFor('the suggest widget', async () => (await post<{ found: boolean }>('/findText', { text: 'dynamicsShape' })).found || undefined, 10_000);
      await screenshot('completion offers the overridable keys (widget)');
      await revertAndClose();
    });

    it(INSIDE_TESTS.definition, async function () {
      requireServerFeature(this, 'go to definition', !!api().serverCapabilities()?.definitionProvider);
      const editor = await open('main.xosc');
      const cursor = positionOf(editor.document, 'scenarioFileName="lane_change.xosc"', 'scenarioFileName="lane'.length);
      editor.selection = new vscode.Selection(cursor, cursor);
      const locations = await vscode.commands.executeCommand<(vscode.Location | vscode.LocationLink)[]>('vscode.executeDefinitionProvider', editor.document.uri, cursor);
      const targets = locations.map((location) => ('targetUri' in location ? location.targetUri : location.uri).fsPath);
      assert.deepEqual(targets, [path.join(workspaceRoot(), 'lane_change.xosc')]);
      // Then the key press, as a person does it, in the page, with the keyboard focus in the editor.
      await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
      await pressKeys(['F12']);
      const target = await waitFor('the referenced file to open', () => {
        const active = vscode.window.activeTextEditor?.document.uri;
        return active && path.basename(active.path) === 'lane_change.xosc' ? active : undefined;
      });
      assert.equal(target.fsPath, path.join(workspaceRoot(), 'lane_change.xosc'));
    });

    it(INSIDE_TESTS.preview, async function () {
      this.timeout(90_000);
      requireServerFeature(this, 'codeLens', !!api().serverCapabilities()?.codeLensProvider);
      const editor = await open('main.xosc');
      const previewOpen = () => vscode.workspace.textDocuments.find((document) => document.uri.scheme === 'modular2simple-preview' && !document.isClosed);
      const previewEditor = () => vscode.window.visibleTextEditors.find((visible) => visible.document.uri.scheme === 'modular2simple-preview');
      const shows = (preview: vscode.TextEditor, line: number) => preview.visibleRanges.some((range) => range.start.line <= line && line <= range.end.line);
      // The "flatten preview" CodeLens of the third reference opens the preview at the group that reference imports, not at line 1.
      const referenceLine = positionOf(editor.document, 'scenarioFileName="pedestrian.mosc"').line;
      const lenses = await waitFor('the CodeLenses', async () => {
        const found = await vscode.commands.executeCommand<vscode.CodeLens[]>('vscode.executeCodeLensProvider', editor.document.uri, 100);
        return found.some((candidate) => candidate.command?.command === 'modular2simple.openPreview') ? found : undefined;
      });
      const lens = lenses.find((candidate) => candidate.command?.command === 'modular2simple.openPreview' && candidate.range.start.line === referenceLine)?.command;
      assert.ok(lens, `no flatten preview lens on line ${referenceLine + 1}`);
      await vscode.commands.executeCommand(lens.command, ...(lens.arguments ?? []));
      const preview = await waitFor('the preview', previewOpen);
      assert.match(preview.uri.path, /\/examples\.flattened\.xosc$/, 'the preview is not named as Flatten names its output');
      await waitFor('the flattened text', () => preview.getText().includes('name="Pedestrian.Walker.Crossing"') || undefined);
      assert.ok(!preview.getText().includes('ScenarioReference'), 'the preview still holds a ScenarioReference');
      const pedestrian = positionOf(preview, 'name="Pedestrian.Walker.Crossing"').line;
      const atLens = await waitFor('the preview editor', previewEditor);
      await waitFor('the preview to open at the pedestrian group', () => (shows(atLens, pedestrian) && !shows(atLens, 0)) || undefined, 10_000);
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
      await waitFor('the preview to open at the group of the cursor', () => (shows(atCursor, cutIn) && !shows(atCursor, 0)) || undefined, 10_000);
      await screenshot('preview opens at the group of the cursor');

      // Each edit reaches the preview; the time from the edit to the new text is printed (a figure, not a limit).
      const latencies: number[] = [];
      let previous = '27.5';
      for (const value of ['31.25', '32.5', '33.75', '35', '36.25']) {
        let arrived = 0;
        const listener = vscode.workspace.onDidChangeTextDocument((event) => {
          if (event.document === atCursor.document && !arrived && event.document.getText().includes(`value="${value}"`)) arrived = performance.now();
        });
        const started = performance.now();
        await replaceText(editor.document, `key="AbsoluteTargetSpeed.value" value="${previous}"`, `key="AbsoluteTargetSpeed.value" value="${value}"`);
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
      await waitFor('the preview to scroll to the imported group', () => shows(atCursor, cutIn) || undefined, 10_000);
      await waitFor('the preview to show the change', () => pageShows(previous, '.editor-group-container:not(.active) .view-lines'), 10_000);
      await screenshot('preview after an edit');
      await revertAndClose();
    });

    it(INSIDE_TESTS.scenarioPath, async function () {
      requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
      // A library folder outside the workspace, found only through the setting.
      const library = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-library-'));
      fs.copyFileSync(path.join(workspaceRoot(), 'lane_change.xosc'), path.join(library, 'shared_lane_change.xosc'));
      const editor = await open('main.xosc');
      const uri = editor.document.uri;
      await replaceText(editor.document, 'scenarioFileName="lane_change.xosc"', 'scenarioFileName="shared_lane_change.xosc"');
      const line = positionOf(editor.document, 'shared_lane_change.xosc').line;
      const onReference = (): vscode.Diagnostic | undefined => vscode.languages.getDiagnostics(uri).find((d) => d.range.start.line === line && d.severity === vscode.DiagnosticSeverity.Error);
      await waitFor('the missing file to be reported', onReference);
      const settings = vscode.workspace.getConfiguration('modular2simple');
      await settings.update('scenarioPath', [library], vscode.ConfigurationTarget.Workspace);
      try {
        await waitFor('the reference to resolve through the setting', () => !onReference() || undefined);
        // The library lies outside the workspace, and still its files are watched: a file removed there is reported.
        // A new watcher starts in its own time: the file goes away and comes back until the removal is seen.
        const [present, away] = [path.join(library, 'shared_lane_change.xosc'), path.join(library, 'moved_away.xosc')];
        await waitFor('the removed library file to be reported', async () => {
          if (fs.existsSync(away)) fs.renameSync(away, present);
          await new Promise((resolve) => setTimeout(resolve, 500));
          fs.renameSync(present, away);
          return await waitFor('the removal to be reported', onReference, 3_000).catch(() => undefined);
        }, 20_000);
        fs.renameSync(path.join(library, 'moved_away.xosc'), path.join(library, 'shared_lane_change.xosc'));
        await waitFor('the restored library file to resolve', () => !onReference() || undefined, 15_000);
      } finally {
        await settings.update('scenarioPath', undefined, vscode.ConfigurationTarget.Workspace);
        await revertAndClose();
        fs.rmSync(library, { recursive: true, force: true });
      }
    });

    it(INSIDE_TESTS.pack, async function () {
      requireServerFeature(this, 'pack', offersRequest(PackRequest));
      const root = workspaceRoot();
      await open('pedestrian/main.xosc');
      await runFromPalette('Modular2Simple: Pack into .mosc');
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
    });

    it(INSIDE_TESTS.flatten, async function () {
      this.timeout(90_000);
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
    });

    it(INSIDE_TESTS.expression, async function () {
      requireServerFeature(this, 'inlay hints', !!api().serverCapabilities()?.inlayHintProvider);
      const file = path.join(workspaceRoot(), 'expressions.xosc');
      fs.writeFileSync(file, EXPRESSIONS);
      // The file is gone again after this test, so that the other tests see the example workspace as it is.
      try {
        await showExpression();
      } finally {
        await vscode.commands.executeCommand('workbench.action.closeAllEditors');
        fs.rmSync(file, { force: true });
      }
    });

    async function showExpression(): Promise<void> {
      const editor = await open('expressions.xosc');
      const hints = await waitFor('the inlay hints', async () => {
        const found = await vscode.commands.executeCommand<vscode.InlayHint[]>('vscode.executeInlayHintProvider', editor.document.uri, new vscode.Range(0, 0, editor.document.lineCount, 0));
        return found.length > 0 ? found : undefined;
      });
      assert.deepEqual(hints.map((hint) => hint.label), ['= 3']);
      // What a person sees: the value drawn after the attribute, then the hover over the expression.
      // The editor draws spaces as no-break spaces.
      await waitFor('the hint drawn in the editor', async () => (await pageShows('= 3', '.monaco-editor .view-lines')) || (await pageShows('=\u00a03', '.monaco-editor .view-lines')));
      const cursor = positionOf(editor.document, '${2*$a/$b}', 3);
      editor.selection = new vscode.Selection(cursor, cursor);
      await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
      await vscode.commands.executeCommand('editor.action.showHover');
      await waitFor('the hover with the value and the declarations', async () => (await pageShows('= 3 (double)', '.monaco-hover')) && (await pageShows('declared in <OpenSCENARIO> on line 6', '.monaco-hover')));
      await screenshot('expression value as inlay hint and hover');
    }

    it(INSIDE_TESTS.insidePackage, async function () {
      requireServerFeature(this, 'go to definition', !!api().serverCapabilities()?.definitionProvider);
      const main = packageUri('braking.mosc', 'main.xosc');
      const editor = await vscode.window.showTextDocument(await vscode.workspace.openTextDocument(main));
      const cursor = positionOf(editor.document, 'scenarioFileName="hard_brake.xosc"', 'scenarioFileName="hard'.length);
      const locations = await waitFor('a definition inside the package', async () => {
        const found = await vscode.commands.executeCommand<(vscode.Location | vscode.LocationLink)[]>('vscode.executeDefinitionProvider', main, cursor);
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
      await waitFor('a diagnostic inside the package', () => vscode.languages.getDiagnostics(main).find((d) => d.range.start.line === keyLine));
      await revertAndClose();
    });

    it(INSIDE_TESTS.structure, async function () {
      requireServerFeature(this, 'structure', offersRequest(StructureRequest));
      const editor = await open('main.xosc');
      const root = await vscode.commands.executeCommand<StructureNode | undefined>('modular2simple.showStructure', editor.document.uri);
      assert.ok(root, 'no structure');
      const nodes = flattenTree(root);
      assert.equal(root.kind, 'main');
      for (const kind of ['package', 'scenario', 'group'] as const) assert.ok(nodes.some((node) => node.kind === kind), `no ${kind} in the structure`);
      for (const name of ['lane_change.xosc', 'braking.mosc', 'pedestrian']) {
        assert.ok(nodes.some((node) => node.label.includes(name)), `${name} is not in the structure`);
      }
      // What a person sees: the tree view itself lists the packages and scenarios.
      for (const name of ['braking.mosc', 'lane_change.xosc']) {
        await waitFor(`${name} in the tree view`, () => pageShows(name, '.customview-tree'), 10_000);
      }
      // The tree follows a save.
      await replaceText(editor.document, 'name="CutInVehicle"', 'name="CutInCar"');
      assert.ok(await editor.document.save());
      await waitFor('the renamed group in the tree view', () => pageShows('CutInCar', '.customview-tree'), 10_000);
      assert.ok(flattenTree(api().structure() ?? root).some((node) => node.label.includes('CutInCar')));
    });

    it(INSIDE_TESTS.renameInPackage, async function () {
      requireServerFeature(this, 'rename', !!api().serverCapabilities()?.renameProvider);
      const uri = packageUri('braking.mosc', 'hard_brake.xosc');
      const document = await vscode.workspace.openTextDocument(uri);
      await vscode.window.showTextDocument(document);
      const position = positionOf(document, 'name="HardBrake"', 'name="Hard'.length);
      const edit = await waitFor('a rename edit', async () => {
        const found = await vscode.commands.executeCommand<vscode.WorkspaceEdit | undefined>('vscode.executeDocumentRenameProvider', uri, position, 'SuddenBrake');
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
    });

    it(INSIDE_TESTS.runEsmini, async function () {
      this.timeout(120_000);
      requireServerFeature(this, 'runEsmini', offersRequest(RunEsminiRequest));
      // esmini as the test setup builds it beside the CLI under test, and the shared road files.
      const repository = path.resolve(path.dirname(process.env[HARNESS_ENV.cli] ?? '.'), '..');
      const esmini = path.join(repository, '.cache', 'esmini', 'bin', 'esmini');
      const roads = path.resolve(repository, '..', 'shared', 'esmini', 'xodr');
      if (!fs.existsSync(esmini) || !fs.existsSync(roads)) {
        assert.ok(!process.env.M2S_REQUIRE_ESMINI, `M2S_REQUIRE_ESMINI is set, but ${esmini} or ${roads} is absent`);
        console.log(`skipped: ${esmini} or ${roads} is absent`);
        this.skip();
      }
      const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
      await settings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
      await settings.update('roadPath', [roads], vscode.ConfigurationTarget.Workspace);
      await settings.update('duration', 5, vscode.ConfigurationTarget.Workspace);
      try {
        const simple = await open('lane_change.xosc');
        await replaceText(simple.document, 'dynamicsShape="linear" value="3"', 'dynamicsShape="wobbly" value="3"');
        const line = positionOf(simple.document, 'dynamicsShape="wobbly"').line;
        const main = await open('main.xosc');
        const lenses = await waitFor('the Run in esmini lens', async () => {
          const found = await vscode.commands.executeCommand<vscode.CodeLens[]>('vscode.executeCodeLensProvider', main.document.uri, 100);
          return found.find((lens) => lens.command?.command === 'modular2simple.runEsmini');
        });
        assert.equal(lenses.command?.title, '▶ Run in esmini');
        const esminiDiagnostics = () => vscode.languages.getDiagnostics(simple.document.uri).filter((diagnostic) => diagnostic.source === 'esmini');
        const broken = await vscode.commands.executeCommand<RunEsminiResult>(lenses.command?.command ?? '', ...(lenses.command?.arguments ?? []));
        assert.equal(broken?.outcome, 'errors', broken?.message);
        const [error] = esminiDiagnostics();
        assert.ok(error, 'no esmini diagnostic on the simple scenario');
        assert.equal(error.range.start.line, line);
        assert.equal(error.severity, vscode.DiagnosticSeverity.Error);
        assert.match(error.message, /wobbly/);
        await screenshot('run-esmini-error');

        await vscode.window.showTextDocument(simple.document);
        await vscode.commands.executeCommand('workbench.action.files.revert');
        const clean = await vscode.commands.executeCommand<RunEsminiResult>('modular2simple.runEsmini', main.document.uri);
        assert.equal(clean?.outcome, 'ok', clean?.message);
        assert.deepEqual(esminiDiagnostics(), [], 'the next run replaces the esmini diagnostics');
        assert.ok(clean?.csvFile && fs.existsSync(clean.csvFile));
        assert.equal(api().lastEsminiRun()?.result.csvFile, clean.csvFile);
        // Run it and see it: the trajectories of the four entities in the bird's-eye view.
        await waitFor("the run in the bird's-eye view", () => (api().birdsEye.stats?.trajectories === 4 ? true : undefined));
        await screenshot("bird's-eye view after Run in esmini");
      } finally {
        for (const key of ['path', 'roadPath', 'duration']) await settings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
        await revertAndClose();
      }
    });

    it(INSIDE_TESTS.packUnsaved, async function () {
      this.timeout(60_000);
      requireServerFeature(this, 'pack', offersRequest(PackRequest));
      const root = workspaceRoot();
      const editor = await open('main.xosc');
      await replaceText(editor.document, 'key="RelativeDistanceCondition.value" value="12"', 'key="RelativeDistanceCondition.value" value="17.5"');
      assert.ok(editor.document.isDirty);
      await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
      await runFromPalette('Modular2Simple: Pack into .mosc');
      const written = path.join(root, `${path.basename(root)}.mosc`);
      await acceptSaveDialog(path.basename(written));
      await waitFor(path.basename(written), () => fs.existsSync(written) || undefined);
      // The package holds what the editor shows, the file was saved to match, and the message says so.
      const packed = await zipEntries(written);
      assert.ok(packed.get('main.xosc')?.includes('key="RelativeDistanceCondition.value" value="17.5"'), 'the package holds the saved text, not the edited one');
      assert.equal(packed.get('main.xosc'), editor.document.getText());
      assert.ok(!editor.document.isDirty, 'main.xosc was not saved');
      await waitFor('the message naming the saved file', () => pageShows('saved main.xosc first'), 10_000);
      await screenshot('pack saves unsaved files first');
      fs.rmSync(written);
    });

    it(INSIDE_TESTS.flattenAnyway, async function () {
      this.timeout(60_000);
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
        await waitFor('the offer to write anyway', () => pageShows('Write Anyway'), 20_000);
        assert.ok(await pageShows('LaneChangeActionDynamic.value'), 'the offer does not name the skipped key');
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
    });

    it(INSIDE_TESTS.structureFollows, async function () {
      this.timeout(60_000);
      requireServerFeature(this, 'rename', !!api().serverCapabilities()?.renameProvider);
      const editor = await open('main.xosc');
      const root = await vscode.commands.executeCommand<StructureNode | undefined>('modular2simple.showStructure', editor.document.uri);
      assert.ok(root);
      const groupLabels = () => flattenTree(api().structure() ?? root).filter((node) => node.kind === 'group' || node.kind === 'missing').map((node) => `${node.label}: ${node.detail ?? ''}`);
      const original = /^CutIn: \d+ attributes? overridden$/;
      assert.ok(groupLabels().some((label) => original.test(label)), groupLabels().join(', '));
      // A cross-file rename, not saved: the group and its reference change in two files.
      const laneChange = await vscode.workspace.openTextDocument(vscode.Uri.file(path.join(workspaceRoot(), 'lane_change.xosc')));
      await vscode.window.showTextDocument(laneChange);
      const edit = await waitFor('a rename edit', async () => {
        const found = await vscode.commands.executeCommand<vscode.WorkspaceEdit | undefined>('vscode.executeDocumentRenameProvider', laneChange.uri, positionOf(laneChange, 'name="CutIn"', 'name="Cut'.length), 'CutInLeft');
        return found && found.size > 1 ? found : undefined;
      });
      assert.ok(await vscode.workspace.applyEdit(edit));
      await waitFor('the renamed group in the tree view', () => pageShows('CutInLeft', '.customview-tree'), 10_000);
      assert.ok(!(await pageShows('no such group', '.customview-tree')), 'the tree shows "no such group" after the rename');
      assert.ok(groupLabels().some((label) => label.startsWith('CutInLeft:')), groupLabels().join(', '));
      await screenshot('structure follows a cross-file rename');
      // Undone without saving: the tree follows back.
      for (const document of [laneChange, editor.document]) {
        await vscode.window.showTextDocument(document);
        await vscode.commands.executeCommand('workbench.action.files.revert');
      }
      await waitFor('the original group in the tree view', () => groupLabels().some((label) => original.test(label)) || undefined, 10_000);
      // A file changed on disk, not open in the editor: the reference now names a group that does not exist.
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      const file = path.join(workspaceRoot(), 'lane_change.xosc');
      const saved = fs.readFileSync(file, 'utf8');
      try {
        fs.writeFileSync(file, saved.replace('name="CutIn"', 'name="CutInRight"'));
        await waitFor('the tree to show the missing group', () => pageShows('no such group', '.customview-tree'), 15_000);
        await screenshot('structure follows a file changed on disk');
      } finally {
        fs.writeFileSync(file, saved);
      }
      await waitFor('the tree to follow the restored file', async () => !(await pageShows('no such group', '.customview-tree')) || undefined, 15_000);
    });
    it(INSIDE_TESTS.schemaCompletion, async function () {
      requireServerFeature(this, 'completion', !!api().serverCapabilities()?.completionProvider);
      const editor = await open('crossing.xosc');
      await replaceText(editor.document, '<Actions>\n        <Private entityRef="ego">', '<Actions>\n        <\n        <Private entityRef="ego">');
      const line = positionOf(editor.document, '<Actions>').line + 1;
      editor.selection = new vscode.Selection(new vscode.Position(line, 9), new vscode.Position(line, 9));
      editor.revealRange(new vscode.Range(line, 0, line, 9), vscode.TextEditorRevealType.InCenter);
      const list = await waitFor('schema completion items', async () => {
        const result = await vscode.commands.executeCommand<vscode.CompletionList>('vscode.executeCompletionItemProvider', editor.document.uri, new vscode.Position(line, 9));
        return result.items.length > 0 ? result : undefined;
      });
      const labels = list.items.map((item) => (typeof item.label === 'string' ? item.label : item.label.label));
      assert.deepEqual(labels.filter((label) => ['GlobalAction', 'UserDefinedAction', 'Private'].includes(label)), ['GlobalAction', 'UserDefinedAction', 'Private']);
      await vscode.commands.executeCommand('editor.action.triggerSuggest');
      await waitFor('the suggest widget showing UserDefinedAction', async () => (await post<{ found: boolean }>('/findText', { text: 'UserDefinedAction', selector: '.suggest-widget' })).found || undefined, 10_000);
      await screenshot('schema completion of a child element (widget)');
      await vscode.commands.executeCommand('hideSuggestWidget');
      await revertAndClose();
    });

    it(INSIDE_TESTS.schemaDeprecated, async function () {
      requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
      const crossing = fs.readFileSync(path.join(workspaceRoot(), 'crossing.xosc'), 'utf8');
      // The example as an OpenSCENARIO 1.3 file whose Init activates a controller the way 1.0 did (deprecated since 1.1).
      const deprecated = crossing
        .replace('revMinor="0"', 'revMinor="3"')
        .replace('<Actions>\n', '<Actions>\n        <Private entityRef="walker">\n          <PrivateAction>\n            <ActivateControllerAction longitudinal="true"/>\n          </PrivateAction>\n        </Private>\n');
      const file = path.join(workspaceRoot(), 'deprecated_1_3.xosc');
      fs.writeFileSync(file, deprecated);
      const editor = await open('deprecated_1_3.xosc');
      const diagnostic = await waitFor('the deprecated diagnostic', () =>
        vscode.languages.getDiagnostics(editor.document.uri).find((candidate) => candidate.tags?.includes(vscode.DiagnosticTag.Deprecated) && /<ActivateControllerAction>/.test(candidate.message)),
      );
      assert.match(diagnostic.message, /<ActivateControllerAction> is deprecated since OpenSCENARIO 1\.1/);
      editor.revealRange(diagnostic.range, vscode.TextEditorRevealType.InCenter);
      await waitFor('the struck-through element name', async () => (await post<{ found: boolean }>('/findText', { text: 'ActivateControllerAction', selector: '.squiggly-inline-deprecated' })).found || undefined, 10_000);
      editor.selection = new vscode.Selection(diagnostic.range.start, diagnostic.range.start);
      await vscode.commands.executeCommand('editor.action.showHover');
      await screenshot('a deprecated element struck through (hover)');
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      fs.rmSync(file, { force: true });
    });
  });
}
