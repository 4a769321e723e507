import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { BIRDS_EYE_FILES, HIGHWAY_MERGE_FILES } from '../birdsEyeSetup';
import type { BirdsEyeView } from '../../../client/src/birdsEye/panel';
import { INSIDE_TESTS } from '../titles';
import { api, open, packageUri, positionOf, replaceText, revertAndClose, TEST_MS, waitFor, waitForPage, workspaceRoot } from './helpers';
import { clickText, pageShows, runFromPalette, screenshot } from './harnessClient';

function skipUnless(context: Mocha.Context, condition: boolean, why: string): void {
  if (condition) return;
  if (process.env.M2S_REQUIRE_ESMINI) throw new Error(`M2S_REQUIRE_ESMINI is set, but ${why}`);
  console.log(`skipped: ${why}`);
  context.skip();
}

/**
 * Plays the run from the view's Play button until the page shows `seconds` played: the time the page reports, not a
 * fixed sleep, which a loaded machine's page may not have played through.
 */
async function playPast(view: BirdsEyeView, seconds: number): Promise<void> {
  let shown = 0;
  const listening = view.onDidChangeTime((time) => (shown = time));
  try {
    assert.ok(await clickText('Play run'), 'no Play button');
    await waitFor(`the run played past ${seconds} s`, () => shown > seconds || undefined);
  } finally {
    listening.dispose();
  }
}

/** Pauses the playback; a run that played to its end meanwhile (a slow click) has stopped by itself. */
async function pause(): Promise<void> {
  if (await clickText('Pause run')) return;
  assert.ok(await pageShows('Play run'), 'neither a Pause button nor a run played to its end');
}

/** The bird's-eye view tests; run after the main suite, in the same VS Code. */
export function defineBirdsEyeTests(): void {
  describe("the bird's-eye view in a real VS Code", function () {
    this.timeout(TEST_MS);
    const settings = () => vscode.workspace.getConfiguration('modular2simple');

    before(async function () {
      await waitFor('the extension to activate', () => vscode.extensions.getExtension('modular2simple.modular2simple')?.isActive);
      await settings().update('esmini.roadPath', [BIRDS_EYE_FILES.roadFolder], vscode.ConfigurationTarget.Workspace);
    });

    after(async () => {
      await settings().update('esmini.roadPath', undefined, vscode.ConfigurationTarget.Workspace);
    });

    afterEach(async function () {
      await screenshot(`${this.currentTest?.state === 'failed' ? 'FAILED ' : ''}${this.currentTest?.title ?? 'unnamed'}`).catch(
        () => undefined,
      );
    });

    it(INSIDE_TESTS.birdsEye, async function () {
      skipUnless(
        this,
        fs.existsSync(path.join(workspaceRoot(), BIRDS_EYE_FILES.roadFolder, 'e6mini.xodr')),
        "esmini's road files (../shared/esmini/xodr) are absent",
      );
      const editor = await open(BIRDS_EYE_FILES.scenario);
      // As a person does: the command palette, with the scenario's editor active.
      const started = Date.now();
      await runFromPalette("Modular2Simple: Show Bird's-Eye View");
      const view = api().birdsEye;
      const stats = await waitFor('the view to draw the road and the entities', () =>
        view.stats && view.stats.lanes > 0 && view.stats.entities === 2 ? view.stats : undefined,
      );
      // A figure, not a bound: the drawing's speed is bench/birdsEye.ts's to measure (a bound here failed under load).
      console.log(`command to picture: ${Date.now() - started} ms (roads drawn in ${stats.staticDrawMs.toFixed(1)} ms)`);
      assert.deepEqual(view.scene?.problems, []);
      assert.equal(view.scene?.roadFile?.resolved, path.join(workspaceRoot(), BIRDS_EYE_FILES.roadFolder, 'e6mini.xodr'));
      const [ego, adversary] = view.scene?.entities ?? [];
      assert.deepEqual([ego?.name, adversary?.name], ['Ego', 'Adversary']);
      // esmini puts them there (its first CSV row): within 1 cm.
      assert.ok(Math.abs((ego?.x ?? NaN) - 8.173369) < 0.01 && Math.abs((ego?.y ?? NaN) - 49.970175) < 0.01, `Ego at ${ego?.x}, ${ego?.y}`);
      await waitForPage('CutInEvent');
      // The planned start of CutInEvent.
      await waitForPage('planned 2 s');
      await screenshot("bird's-eye view before a run");

      // Clicking an entity opens its TeleportAction.
      const expected = positionOf(editor.document, '<Position><LanePosition roadId="0" laneId="-3"').line;
      await vscode.commands.executeCommand('workbench.action.focusFirstEditorGroup');
      assert.ok(await clickText('■ Ego'), 'no Ego button in the view');
      await waitFor('the Ego placement to open', () => {
        const active = vscode.window.activeTextEditor;
        return active?.document.uri.path.endsWith(BIRDS_EYE_FILES.scenario) && active.selection.active.line === expected ? true : undefined;
      });

      // An unsaved edit moves Ego: the view follows.
      const before = view.scene;
      await replaceText(editor.document, 'name="EgoS" parameterType="double" value="50"', 'name="EgoS" parameterType="double" value="150"');
      await waitFor('the view to follow the edit', () =>
        view.scene !== before && (view.scene?.entities[0]?.y ?? 0) > 140 ? true : undefined,
      );
      await revertAndClose();
    });

    it(INSIDE_TESTS.birdsEyeRun, async function () {
      const csv = path.join(workspaceRoot(), BIRDS_EYE_FILES.csv);
      skipUnless(this, fs.existsSync(csv), 'esmini is not built (.cache/esmini/bin/esmini), so there is no run to show');
      await open(BIRDS_EYE_FILES.scenario);
      const view = api().birdsEye;
      // What the esmini run command does when a run ends.
      const started = Date.now();
      await vscode.commands.executeCommand('modular2simple.birdsEye.showRun', csv, {
        logPath: path.join(workspaceRoot(), BIRDS_EYE_FILES.log),
        scenario: vscode.Uri.file(path.join(workspaceRoot(), BIRDS_EYE_FILES.scenario)).toString(),
      });
      await waitFor('the trajectories', () => (view.stats?.trajectories === 2 && view.stats.lanes > 0 ? true : undefined));
      console.log(`run handed over to trajectories drawn: ${Date.now() - started} ms`);
      // When CutInEvent and BrakeEvent started.
      await waitForPage('started 2.05 s');
      await waitForPage('started 6.05 s');
      // Clicking an event opens it in the source.
      const eventLine = positionOf((await open(BIRDS_EYE_FILES.scenario)).document, '<Event name="BrakeEvent"').line;
      assert.ok(await clickText('BrakeEvent'), 'no BrakeEvent button in the view');
      await waitFor('BrakeEvent to open', () => (vscode.window.activeTextEditor?.selection.active.line === eventLine ? true : undefined));
      await playPast(view, 1.5);
      await screenshot("bird's-eye view playing a run");
      await pause();
      const played = await waitFor('the playback figures', () =>
        view.stats && !view.stats.playing && view.stats.frames > 0 ? view.stats : undefined,
      );
      assert.ok(played.time > 1, `playback reached ${played.time} s`);
      console.log(
        `playback: ${played.frames} frames, ${played.frameMeanMs.toFixed(2)} ms mean, ${played.frameWorstMs.toFixed(2)} ms worst to draw a frame`,
      );
      // The picture saved as PNG and as SVG, as the view's buttons do (here to given files).
      const png = path.join(workspaceRoot(), 'birdsEye', 'picture.png');
      const svg = path.join(workspaceRoot(), 'birdsEye', 'picture.svg');
      await vscode.commands.executeCommand('modular2simple.birdsEye.save', 'png', png);
      await vscode.commands.executeCommand('modular2simple.birdsEye.save', 'svg', svg);
      assert.deepEqual([...fs.readFileSync(png).subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
      assert.ok(fs.statSync(png).size > 5000, `the PNG is only ${fs.statSync(png).size} bytes`);
      const drawing = fs.readFileSync(svg, 'utf8');
      assert.match(drawing, /^<\?xml[^]*<svg /);
      assert.ok((drawing.match(/<polygon /g) ?? []).length > 10, 'the SVG holds the lanes');
      assert.match(drawing, />Adversary<\/text>/);
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    });

    it(INSIDE_TESTS.birdsEyeAnalysis, async function () {
      const csv = path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.csv);
      skipUnless(
        this,
        fs.existsSync(csv),
        'esmini is not built, or its highway_merge.xosc or soderleden.xodr is absent, so there is no run of it to analyse',
      );
      const scenario = vscode.Uri.file(path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.scenario));
      await vscode.window.showTextDocument(scenario, { preview: false });
      const view = api().birdsEye;
      await vscode.commands.executeCommand('modular2simple.birdsEye.showRun', csv, {
        logPath: path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.log),
        scenario: scenario.toString(),
      });
      const first = await waitFor('the six trajectories', () =>
        view.stats?.trajectories === 6 && view.stats.lanes > 0 && view.stats.time === 0 ? view.stats : undefined,
      );
      assert.equal(view.scene?.roadFile?.resolved, path.join(workspaceRoot(), 'birdsEye', 'xodr', 'soderleden.xodr'));
      // *Entities* frames the cars where they are now (some 170 m across at the start), not their trajectories (over 500 m).
      assert.ok(first.spanMetres < 300, `the view spans ${first.spanMetres} m`);
      // Every car labelled, no two labels overlapping (the placement leaves out a label rather than overlap it).
      assert.deepEqual([...first.labels].sort(), ['A1', 'A2', 'A3', 'A4', 'A5', 'Ego']);
      await screenshot("bird's-eye view of highway_merge after a run, the cars framed");

      // Following Ego: the plots of its speed, gap and time to collision appear under the map.
      view.choose('Ego');
      await waitFor('Ego chosen', () => (view.stats?.chosen === 'Ego' ? true : undefined));
      await playPast(view, 1.5);
      await pause();
      const played = await waitFor('the playback figures', () =>
        view.stats && !view.stats.playing && view.stats.frames > 0 ? view.stats : undefined,
      );
      assert.ok(played.time > 1, `playback reached ${played.time} s`);
      assert.ok(played.spanMetres < 300, 'following keeps the scale');
      console.log(
        `following Ego: ${played.frames} frames, ${played.frameMeanMs.toFixed(2)} ms mean, ${played.frameWorstMs.toFixed(2)} ms worst to draw a frame`,
      );
      await screenshot("bird's-eye view following Ego on highway_merge, with its speed, gap and TTC plots");

      // A second concrete scenario (A1 faster, a shorter gap): overlaid, then side by side.
      await vscode.commands.executeCommand('modular2simple.birdsEye.showRun', path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.variantCsv), {
        logPath: path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.variantLog),
        compare: true,
      });
      const overlaid = await waitFor('the compared run overlaid', () =>
        view.stats?.compared === 6 && !view.stats.sideBySide ? view.stats : undefined,
      );
      assert.equal(overlaid.trajectories, 6, 'the first run stays');
      // The title names the compared run.
      await waitForPage('compared with: highway_merge_fast.csv');
      await screenshot("bird's-eye view comparing two runs of highway_merge, the second dashed");
      await vscode.commands.executeCommand('modular2simple.birdsEye.showRun', path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.variantCsv), {
        logPath: path.join(workspaceRoot(), HIGHWAY_MERGE_FILES.variantLog),
        compare: 'side',
      });
      await waitFor('the runs side by side', () => (view.stats?.compared === 6 && view.stats.sideBySide ? true : undefined));
      await screenshot("bird's-eye view comparing two runs of highway_merge side by side");

      // Exported at a chosen resolution, with the time, a legend, a scale bar, the plots and the events.
      const png = path.join(workspaceRoot(), 'birdsEye', 'highway_merge.png');
      const svg = path.join(workspaceRoot(), 'birdsEye', 'highway_merge.svg');
      await vscode.commands.executeCommand('modular2simple.birdsEye.save', 'png', png, { width: 1600, height: 900 });
      await vscode.commands.executeCommand('modular2simple.birdsEye.save', 'svg', svg, { width: 1600, height: 900 });
      const header = fs.readFileSync(png);
      assert.deepEqual([header.readUInt32BE(16), header.readUInt32BE(20)], [1600, 900], 'the PNG is 1600 x 900');
      const drawing = fs.readFileSync(svg, 'utf8');
      assert.match(drawing, /<svg [^>]*width="1600" height="900"/);
      assert.match(drawing, />t = \d+\.\d\d s of 14\.\d\d s · highway_merge\.csv vs highway_merge_fast\.csv</);
      assert.match(drawing, />\d+ (k?m)<\/text>/, 'a scale bar');
      for (const name of ['Ego', 'A1', 'A5']) assert.match(drawing, new RegExp(`>${name}</text>`));
      // The followed car's plots and the event list, as the panel shows them.
      assert.match(drawing, />speed of Ego \(m\/s\)</, "Ego's plots");
      assert.match(drawing, />time to collision with Ego \(s\)</);
      assert.match(drawing, />EgoLaneChangeEvent · Ego · [^<]* · started \d+\.\d\d s/, 'the event list with its start time');
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    });

    it(INSIDE_TESTS.birdsEyePackage, async function () {
      // The example package names a road (Town05) that is not in the workspace: the view says so and still shows the scenario.
      const inside = packageUri('braking.mosc', 'main.xosc');
      await vscode.window.showTextDocument(inside, { preview: false });
      await vscode.commands.executeCommand('modular2simple.showBirdsEye', inside);
      const view = api().birdsEye;
      const scene = await waitFor('the scene of the package', () => (view.scene?.uri === inside.toString() ? view.scene : undefined));
      assert.equal(scene.title, 'main.xosc');
      assert.match(scene.problems.join('\n'), /road file "Town05" not found/);
      assert.ok(scene.events.length > 0, 'the events of the package are listed');
      assert.equal(vscode.Uri.parse(scene.events[0].source?.uri ?? '').scheme, 'mosc');
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    });
  });
}
