import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { LibraryNode } from '../../../client/src/library/view';
import { dragOnto, pageShows, post, pressKeys, quickInput, screenshot, typeText } from './harnessClient';
import { projectEsmini } from './esmini.inside';
import { api, cli, type InsideTests, positionOf, revertAndClose, TEST_MS, waitFor, workspaceRoot } from './helpers';

/** The module node the Scenario Library view shows for `name`, as its inline Insert button passes it. */
function moduleNode(name: string): LibraryNode {
  const tree = api().library.tree;
  for (const group of tree.getChildren())
    for (const node of tree.getChildren(group)) if (node.kind === 'module' && node.module.name === name) return node;
  assert.fail(`the Scenario Library view shows no module '${name}'`);
}

/** *New Scenario from Template…* composition-bench into a new folder of the workspace; the main's path. */
async function newBench(folderName: string, fileName: string): Promise<string> {
  const folder = path.join(workspaceRoot(), folderName);
  fs.mkdirSync(folder, { recursive: true });
  const created = await vscode.commands.executeCommand<vscode.Uri | undefined>('modular2simple.newFromTemplate', vscode.Uri.file(folder), {
    template: 'composition-bench',
    fileName,
  });
  const main = path.join(folder, fileName);
  assert.equal(created?.fsPath, main);
  return main;
}

/** A new composition bench main in the editor, the line of its one ManeuverGroup. */
async function benchWithGroup(folderName: string, fileName: string): Promise<{ editor: vscode.TextEditor; onGroup: vscode.Position }> {
  const main = await newBench(folderName, fileName);
  const editor = await waitFor('the new main in the editor', () =>
    vscode.window.activeTextEditor?.document.uri.fsPath === main ? vscode.window.activeTextEditor : undefined,
  );
  return { editor, onGroup: positionOf(editor.document, '<ManeuverGroup name="EgoBehaviour"', 3) };
}

/** No error and no warning on the saved main, in the editor (after the server's answer settles) and under the CLI's check. */
async function assertClean(document: vscode.TextDocument): Promise<void> {
  await new Promise((resolve) => setTimeout(resolve, 2_000));
  const problems = vscode.languages
    .getDiagnostics(document.uri)
    .filter((diagnostic) => diagnostic.severity <= vscode.DiagnosticSeverity.Warning)
    .map((diagnostic) => `${diagnostic.range.start.line + 1}: ${diagnostic.message}`);
  assert.deepEqual(problems, []);
  cli(['check', document.uri.fsPath]);
}

/** A main composed from the Scenario Library: a template, then three modules inserted from the view, then checked clean. */
export const libraryTests: InsideTests = {
  libraryCompose: async function () {
    this.timeout(2 * TEST_MS);
    // A new user's walk: no main open, the Scenario Library view, Insert on three modules, Save (the user's decision).
    await revertAndClose();
    // Counted from the open view, as the issue counts: each click, key press and question answered.
    const steps: string[] = [];
    await vscode.commands.executeCommand('modular2simple.library.focus');
    const tree = api().library.tree;
    await waitFor('the Scenario Library listing', () => (tree.current?.modules.length ?? 0) > 0);
    assert.deepEqual(tree.current?.problems, [], 'the built-in library lists problems');
    // Every module in sight: the last group's last module is drawn without scrolling or filtering the view.
    await waitFor('the view drawing its modules', () => pageShows('library:pedestrian-crossing'));
    await screenshot('The Scenario Library view lists the modules by group');

    const main = path.join(workspaceRoot(), 'composition-bench.xosc');
    const road = path.join(workspaceRoot(), 'straight_1000m.xodr');
    assert.ok(!fs.existsSync(main) && !fs.existsSync(road), 'the workspace holds a composition bench already');
    // After each insert the main runs in esmini (for the notice of scripted actors that touch): this project's esmini.
    const esmini = vscode.workspace.getConfiguration('modular2simple.esmini');
    const program = projectEsmini().esmini;
    const esminiBuilt = fs.existsSync(program);
    assert.ok(esminiBuilt || !process.env.M2S_REQUIRE_ESMINI, `M2S_REQUIRE_ESMINI is set, but ${program} is absent`);
    await esmini.update('path', program, vscode.ConfigurationTarget.Workspace);
    const runsBefore = api().library.afterInsertRuns.length;
    try {
      steps.push('Insert into Main: cut-in');
      const first = vscode.commands.executeCommand<string | undefined>('modular2simple.library.insert', moduleNode('cut-in'));
      await waitFor('the quick pick of mains', async () => {
        const shown = await quickInput();
        return (shown.visible && /Insert into Main/.test(shown.title)) || undefined;
      });
      await waitFor('the new main offered first', () => pageShows('New main composition-bench.xosc', '.quick-input-list'));
      await screenshot('No main open: Insert into Main offers a new main from the composition bench first');
      steps.push('New main composition-bench.xosc');
      await pressKeys(['Enter']);
      const groups = [await first];
      for (const name of ['lead-brake', 'pedestrian-crossing']) {
        steps.push(`Insert into Main: ${name}`);
        groups.push(await vscode.commands.executeCommand<string | undefined>('modular2simple.library.insert', moduleNode(name)));
      }
      assert.deepEqual(groups, ['CutIn', 'LeadBrake', 'PedestrianCrossing']);
      const document = await waitFor('the main in the editor', () =>
        vscode.window.activeTextEditor?.document.uri.fsPath === main ? vscode.window.activeTextEditor.document : undefined,
      );
      for (const name of ['cut-in', 'lead-brake', 'pedestrian-crossing'])
        assert.ok(document.getText().includes(`scenarioFileName="library:${name}"`), `no reference to library:${name}`);
      // Each insert's run of the main in esmini: it ran, and no scripted actors touch, so no notice (before 30 November
      // 2026 the last named the cut-in's car touching the pedestrian at 7.75 s and the lead at 10.05 s).
      const runs = await waitFor('the run after each insert', () => {
        const done = api().library.afterInsertRuns.slice(runsBefore);
        return done.length >= 3 ? done : undefined;
      });
      assert.deepEqual(
        runs.map((run) => [run.module, path.basename(vscode.Uri.parse(run.main).fsPath), run.ran, run.notice]).sort(),
        ['cut-in', 'lead-brake', 'pedestrian-crossing'].map((name) => [name, 'composition-bench.xosc', esminiBuilt, undefined]),
      );
      // Each insert is an edit, as VS Code's own are: the main is left modified, the file on disk as the bench wrote it.
      assert.equal(document.isDirty, true, 'an insert saved the main');
      assert.ok(!fs.readFileSync(main, 'utf8').includes('library:'), 'an insert wrote the main on disk');
      // Ctrl+Z undoes the last insert, and only it; Ctrl+Shift+Z brings it back.
      const composed = document.getText();
      await vscode.commands.executeCommand('undo');
      assert.ok(!document.getText().includes('library:pedestrian-crossing'), 'Ctrl+Z did not undo the last insert');
      assert.ok(document.getText().includes('library:lead-brake'), 'Ctrl+Z undid more than the last insert');
      await vscode.commands.executeCommand('redo');
      assert.equal(document.getText(), composed, 'redo did not bring the insert back');
      steps.push('Save');
      assert.ok(await document.save(), 'the main was not saved');
      assert.equal(fs.readFileSync(main, 'utf8'), composed, 'the main on disk is not the composition');

      // The server's view of the saved main: no error and no warning, as the CLI's check says too.
      await waitFor(
        'the server to analyse the composed main',
        async () =>
          ((await vscode.commands.executeCommand<unknown[]>('vscode.executeDocumentSymbolProvider', document.uri))?.length ?? 0) > 0 ||
          undefined,
      );
      await assertClean(document);
      await screenshot('A main composed from three library modules, clean');
      assert.ok(steps.length <= 5, `composing took ${steps.length} steps: ${steps.join('; ')}`);
      console.log(`composed in ${steps.length} steps: ${steps.join('; ')}`);
    } finally {
      await esmini.update('path', undefined, vscode.ConfigurationTarget.Workspace);
      await revertAndClose();
      fs.rmSync(main, { force: true });
      fs.rmSync(road, { force: true });
    }
  },

  libraryComposeFromNew: async function () {
    this.timeout(2 * TEST_MS);
    // A new user's walk from an empty folder: New Modular Scenario… (an ego alone), then three modules from the view,
    // each adding its actor as the module's example main has it. Counted as the issue counts: each command, pick and key.
    await revertAndClose();
    const folder = path.join(workspaceRoot(), 'compose-new');
    fs.rmSync(folder, { recursive: true, force: true });
    fs.mkdirSync(folder);
    const steps: string[] = [];
    const started = Date.now();
    try {
      await vscode.commands.executeCommand('modular2simple.library.focus');
      const tree = api().library.tree;
      await waitFor('the Scenario Library listing', () => (tree.current?.modules.length ?? 0) > 0);
      steps.push('New Modular Scenario… on the empty folder');
      const created = vscode.commands.executeCommand<vscode.Uri | undefined>('modular2simple.newScenario', vscode.Uri.file(folder));
      await waitFor('the road network question', async () => {
        const shown = await quickInput();
        return (shown.visible && /road network/.test(shown.title)) || undefined;
      });
      await waitFor("the library's roads offered", () =>
        pageShows('Scenario Library road, copied beside the new main', '.quick-input-list'),
      );
      await screenshot("New Modular Scenario offers the Scenario Library's roads");
      steps.push("the library's straight_1000m.xodr");
      await typeText('straight_1000m');
      // The workspace may hold a road of that name too (listed first): the library's is the one picked.
      for (let down = 0; down < 5 && !(await pageShows('Scenario Library road', '.quick-input-list .monaco-list-row.focused')); down++)
        await pressKeys(['Down']);
      assert.ok(
        await pageShows('Scenario Library road', '.quick-input-list .monaco-list-row.focused'),
        "the library's road is not in the list",
      );
      await pressKeys(['Enter']);
      await waitFor('the file name question', async () => {
        const shown = await quickInput();
        return (shown.visible && /file name/.test(shown.title) && shown.value === 'main.xosc') || undefined;
      });
      steps.push('Enter (main.xosc)');
      await pressKeys(['Enter']);
      const main = path.join(folder, 'main.xosc');
      assert.equal((await created)?.fsPath, main);
      assert.deepEqual(fs.readdirSync(folder).sort(), ['main.xosc', 'straight_1000m.xodr'], 'the road is copied beside the main');
      const document = await waitFor('the new main in the editor', () =>
        vscode.window.activeTextEditor?.document.uri.fsPath === main ? vscode.window.activeTextEditor.document : undefined,
      );
      assert.match(document.getText(), /<LogicFile filepath="straight_1000m.xodr"\/>/);
      const groups: (string | undefined)[] = [];
      for (const name of ['cut-in', 'lead-brake', 'pedestrian-crossing']) {
        steps.push(`Insert into Main: ${name}`);
        groups.push(await vscode.commands.executeCommand<string | undefined>('modular2simple.library.insert', moduleNode(name)));
        // Asked nothing, the user is told what was added, in the status bar.
        if (name === 'cut-in')
          await waitFor('the status bar naming the new adversary', () =>
            pageShows('added adversary (Vehicle, 35 m ahead of Ego, lane -2, 7 m/s)', '.statusbar'),
          );
      }
      assert.deepEqual(groups, ['CutIn', 'LeadBrake', 'PedestrianCrossing']);
      assert.equal(document.isDirty, true, 'an insert saved the main');
      steps.push('Save');
      assert.ok(await document.save(), 'the main was not saved');
      const elapsed = (Date.now() - started) / 1000;
      const text = document.getText();
      assert.equal(fs.readFileSync(main, 'utf8'), text, 'the main on disk is not the composition');
      assert.deepEqual(
        [...text.matchAll(/<ScenarioObject name="([^"]+)">\s*<(\w+)/g)].map((match) => `${match[1]}: ${match[2]}`),
        ['Ego: Vehicle', 'adversary: Vehicle', 'lead: Vehicle', 'pedestrian: Pedestrian'],
      );
      assert.deepEqual(
        [...text.matchAll(/<Private entityRef="([^"]+)">[\s\S]*?<LanePosition roadId="0" laneId="(-?\d+)" s="([\d.]+)"/g)].map((match) =>
          match.slice(1).join(' '),
        ),
        ['Ego -1 10', 'adversary -2 45', 'lead -1 44.5', 'pedestrian -4 90'],
      );
      assert.deepEqual(
        [...text.matchAll(/<EntityRef entityRef="([^"]+)"\/>\s*<\/Actors>\s*<ScenarioReference scenarioFileName="([^"]+)"/g)].map(
          (match) => `${match[2]} by ${match[1]}`,
        ),
        ['library:cut-in by adversary', 'library:lead-brake by lead', 'library:pedestrian-crossing by pedestrian'],
      );
      await waitFor(
        'the server to analyse the composed main',
        async () =>
          ((await vscode.commands.executeCommand<unknown[]>('vscode.executeDocumentSymbolProvider', document.uri))?.length ?? 0) > 0 ||
          undefined,
      );
      await assertClean(document);
      const editor = vscode.window.activeTextEditor;
      const entities = positionOf(document, '<ScenarioObject name="adversary"');
      editor?.revealRange(new vscode.Range(entities, entities), vscode.TextEditorRevealType.AtTop);
      await screenshot('From an empty folder: a new main with a cut-in, a lead brake and a pedestrian, each actor added, clean');
      assert.ok(steps.length <= 7, `composing took ${steps.length} steps: ${steps.join('; ')}`);
      // A figure, not a limit: the harness's time, with no human reading or clicking.
      await post('/figure', {
        name: `composed from an empty folder (${steps.join('; ')}): steps, seconds in the harness`,
        values: [steps.length, Math.round(elapsed * 10) / 10],
      });
    } finally {
      await revertAndClose();
      fs.rmSync(folder, { recursive: true, force: true });
    }
  },

  libraryInsertHere: async function () {
    this.timeout(2 * TEST_MS);
    const { editor, onGroup } = await benchWithGroup('insert-here', 'here.xosc');
    const document = editor.document;
    editor.selection = new vscode.Selection(onGroup, onGroup);
    // The light bulb's actions at the cursor, as VS Code asks for them.
    const action = await waitFor('Insert library module here… among the code actions', async () =>
      (
        await vscode.commands.executeCommand<vscode.CodeAction[]>(
          'vscode.executeCodeActionProvider',
          document.uri,
          new vscode.Range(onGroup, onGroup),
        )
      )?.find((candidate) => candidate.title === 'Insert library module here…'),
    );
    assert.ok(action.command, 'the action runs a command');
    const running = vscode.commands.executeCommand<string | undefined>(action.command.command, ...(action.command.arguments ?? []));
    await waitFor('the quick pick of library modules', async () => {
      const shown = await quickInput();
      return (shown.visible && /Insert Library Module/.test(shown.title)) || undefined;
    });
    await typeText('library:lead-brake');
    await screenshot('Insert library module here… picks a module');
    await pressKeys(['Enter']);
    assert.equal(await running, 'LeadBrake');
    const text = document.getText();
    const [ego, lead, trigger] = ['<ManeuverGroup name="EgoBehaviour"', '<ManeuverGroup name="LeadBrake"', '<StartTrigger>'].map((tag) =>
      text.indexOf(tag),
    );
    assert.ok(
      ego > 0 && lead > ego && trigger > lead,
      `LeadBrake after EgoBehaviour, before the Act's StartTrigger (${ego}, ${lead}, ${trigger})`,
    );
    assert.ok(text.includes('scenarioFileName="library:lead-brake"'));
    assert.ok(await document.save(), 'the main was not saved');
    await assertClean(document);
    await screenshot('A library module inserted at the cursor, clean');
  },

  libraryDrop: async function () {
    this.timeout(2 * TEST_MS);
    const { editor, onGroup } = await benchWithGroup('drop', 'dropped.xosc');
    const document = editor.document;
    editor.revealRange(new vscode.Range(onGroup, onGroup), vscode.TextEditorRevealType.InCenter);
    await vscode.commands.executeCommand('modular2simple.library.focus');
    await waitFor('the Scenario Library listing', () => (api().library.tree.current?.modules.length ?? 0) > 0);
    await waitFor('the view drawing its modules', () => pageShows('library:lead-brake'));
    await waitFor('the editor drawing the group', () => pageShows('EgoBehaviour', '.monaco-editor .view-line'));
    // Dropped inside the group's Actors, where no group can go: nothing written, and the message says where it can.
    const before = document.getText();
    await dragOnto(
      { selector: '.monaco-list-row', text: 'library:lead-brake' },
      { selector: '.monaco-editor .view-line', text: '</Actors>' },
    );
    await waitFor('the refusal of the drop', () => pageShows('not on an Act or on a ManeuverGroup of an Act', '.notifications-toasts'));
    await screenshot('A library module dropped inside Actors is refused, saying where it can go');
    assert.equal(document.getText(), before, 'a refused drop changed the main');
    await vscode.commands.executeCommand('notifications.clearAll');
    // The mouse: from the module's row in the view onto the line of the ManeuverGroup in the editor.
    await dragOnto(
      { selector: '.monaco-list-row', text: 'library:lead-brake' },
      { selector: '.monaco-editor .view-line', text: 'EgoBehaviour' },
    );
    await waitFor(
      'the dropped module in the main',
      () => document.getText().includes('scenarioFileName="library:lead-brake"') || undefined,
    );
    const text = document.getText();
    const [ego, lead, trigger] = ['<ManeuverGroup name="EgoBehaviour"', '<ManeuverGroup name="LeadBrake"', '<StartTrigger>'].map((tag) =>
      text.indexOf(tag),
    );
    assert.ok(
      ego > 0 && lead > ego && trigger > lead && text.indexOf('<StartTrigger>', ego) > lead,
      `LeadBrake after EgoBehaviour, before the Act's StartTrigger (${ego}, ${lead}, ${trigger})`,
    );
    // The keys at their defaults and the roles played by the bench's entities of their names, as Insert into Main writes them.
    for (const key of ['SpeedActionDynamics.value', 'AbsoluteTargetSpeed.value', 'TimeHeadwayCondition.value'])
      assert.ok(text.includes(`key="${key}"`), `no ${key}`);
    assert.ok(text.includes('<ParameterReference key="TimeHeadwayCondition.entityRef" value="lead"/>'));
    assert.equal(text.split('scenarioFileName="library:lead-brake"').length, 2, 'one group dropped');
    assert.ok(await document.save(), 'the main was not saved');
    await assertClean(document);
    await screenshot('A library module dragged from the view onto a ManeuverGroup, clean');
  },
  libraryDropAsks: async function () {
    this.timeout(2 * TEST_MS);
    const { editor, onGroup } = await benchWithGroup('drop-asks', 'asks.xosc');
    const document = editor.document;
    // The lead car renamed: no entity of the main is named after lead-brake's role 'lead' (its 'ego' still is).
    const renamed = new vscode.WorkspaceEdit();
    renamed.replace(document.uri, new vscode.Range(0, 0, document.lineCount, 0), document.getText().replace(/"lead"/g, '"frontCar"'));
    assert.ok(await vscode.workspace.applyEdit(renamed), 'the rename of the lead car was refused');
    assert.ok(await document.save(), 'the main was not saved');
    assert.ok(!document.getText().includes('"lead"'));
    editor.revealRange(new vscode.Range(onGroup, onGroup), vscode.TextEditorRevealType.InCenter);
    await vscode.commands.executeCommand('modular2simple.library.focus');
    await waitFor('the Scenario Library listing', () => (api().library.tree.current?.modules.length ?? 0) > 0);
    await waitFor('the view drawing its modules', () => pageShows('library:lead-brake'));
    await waitFor('the editor drawing the group', () => pageShows('EgoBehaviour', '.monaco-editor .view-line'));
    const drop = async () => {
      await dragOnto(
        { selector: '.monaco-list-row', text: 'library:lead-brake' },
        { selector: '.monaco-editor .view-line', text: 'EgoBehaviour' },
      );
      await waitFor('the quick pick asking who plays the lead', async () => {
        const shown = await quickInput();
        return (shown.visible && shown.title.startsWith('Drop library module:') && shown.value === '') || undefined;
      });
    };

    // Cancelled: the pick closes and the main is as it was, in the editor and on disk.
    const before = document.getText();
    await drop();
    await screenshot('A library module dropped on a main with no entity of its role asks who plays it');
    await pressKeys(['Escape']);
    await waitFor('the quick pick to close', async () => !(await quickInput()).visible || undefined);
    await new Promise((resolve) => setTimeout(resolve, 2_000));
    assert.equal(document.getText(), before, 'a cancelled drop changed the main');
    assert.ok(!document.isDirty, 'a cancelled drop left the main modified');
    assert.equal(fs.readFileSync(document.uri.fsPath, 'utf8'), before, 'a cancelled drop changed the file');

    // Answered: frontCar plays the lead; the ego is the main's entity of its name, not asked.
    await drop();
    await typeText('frontCar');
    await pressKeys(['Enter']);
    await waitFor(
      'the dropped module in the main',
      () => document.getText().includes('scenarioFileName="library:lead-brake"') || undefined,
    );
    assert.ok(!(await quickInput()).visible, 'a second question was asked (the ego has an entity of its name)');
    const text = document.getText();
    const group = /<ManeuverGroup name="LeadBrake"[\s\S]*?<\/ManeuverGroup>/.exec(text)?.[0];
    assert.ok(group, 'no group LeadBrake in the main');
    assert.match(group, /<Actors selectTriggeringEntities="false">\s*<EntityRef entityRef="frontCar"\/>\s*<\/Actors>/);
    assert.match(group, /<ParameterReference key="TimeHeadwayCondition.entityRef" value="frontCar"\/>/);
    assert.match(group, /<ParameterReference key="EntityRef.entityRef" value="ego"\/>/);
    assert.equal(text.split('scenarioFileName="library:lead-brake"').length, 2, 'one group dropped');
    assert.ok(await document.save(), 'the main was not saved');
    await assertClean(document);
    await screenshot('A library module dropped after choosing who plays its role, clean');
  },
};
