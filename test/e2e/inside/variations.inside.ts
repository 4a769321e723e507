import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { BIRDS_EYE_FILES } from '../birdsEyeSetup';
import { INSIDE_TESTS } from '../titles';
import { VARIATIONS_FILES } from '../variationsSetup';
import { api, TEST_MS, waitFor, workspaceRoot } from './helpers';
import { clickText, computedStyles, pageShows, screenshot } from './harnessClient';

/** The Variations view tests; run after the bird's-eye tests, in the same VS Code. */
export function defineVariationsTests(): void {
  describe('the Variations view in a real VS Code', function () {
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

    it(INSIDE_TESTS.variations, async function () {
      const csv = path.join(workspaceRoot(), VARIATIONS_FILES.results, 'results.csv');
      if (!fs.existsSync(csv)) {
        if (process.env.M2S_REQUIRE_ESMINI)
          throw new Error('M2S_REQUIRE_ESMINI is set, but there are no batch results (esmini or its roads are absent)');
        console.log('skipped: esmini is not built, so there is no batch to show');
        this.skip();
      }
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
      const view = api().variations;
      // As the explorer's context menu on results.csv does: the command with the file's URI.
      await vscode.commands.executeCommand('modular2simple.showVariations', vscode.Uri.file(csv));
      const first = await waitFor('the table and the scatter', () => (view.stats?.rows === 36 ? view.stats : undefined));
      assert.equal(first.shown, 36);
      assert.equal(first.points, 36, 'a point per run');
      assert.deepEqual([first.x, first.y], ['EgoSpeed', 'LeadSpeed']);
      assert.ok(await pageShows('36 runs:'), 'the summary is shown');
      const collisions = fs
        .readFileSync(csv, 'utf8')
        .split('\n')
        .filter((line) => line.split(',')[2] === 'true').length;
      assert.ok(collisions > 0 && collisions < 36, `${collisions} collisions: the fixture has some`);
      assert.ok(await pageShows(`collision (${collisions})`), 'the legend and the filter count the collisions');
      await screenshot('Variations view of 36 runs');

      // Sorted by a header, filtered by outcome: what the view draws follows.
      assert.ok(await clickText('min_distance_m'), 'no min_distance_m header');
      await waitFor('sorted by min_distance_m', () =>
        view.stats?.sort.column === 'min_distance_m' && view.stats.sort.direction === 'ascending' ? true : undefined,
      );
      assert.ok(await clickText(`ok (${36 - collisions})`), 'no ok filter');
      const filtered = await waitFor('only the collisions left', () => (view.stats?.shown === collisions ? view.stats : undefined));
      assert.equal(filtered.points, collisions);
      assert.deepEqual(filtered.outcomes.sort(), ['collision', 'discarded', 'error', 'limit', 'timeout']);
      await screenshot('Variations view: collisions only, by smallest distance');

      // A click on a row's index opens that run in the bird's-eye view.
      const firstCollision = fs
        .readFileSync(csv, 'utf8')
        .split('\n')
        .find((line) => line.split(',')[2] === 'true')!
        .split(',')[0];
      assert.ok(await clickText(`#${firstCollision}`), `no link to run ${firstCollision}`);
      const birdsEye = api().birdsEye;
      await waitFor("the run in the bird's-eye view", () =>
        view.openedRun === firstCollision && birdsEye.stats?.trajectories === 2 ? true : undefined,
      );
      await screenshot(`Variations view: run ${firstCollision} opened in the bird's-eye view`);

      // The row opened stands out from the others, though the pointer still rests on it (the click left it there).
      const [selectedBackground, otherBackground] = await computedStyles(
        ['tbody tr.selected', 'tbody tr:not(.selected)'],
        'background-color',
      );
      assert.ok(selectedBackground && otherBackground, 'the table is on the page');
      assert.notEqual(selectedBackground, otherBackground, `the selected row is drawn as the others (${selectedBackground})`);
      // The hover colour alone also differs from the others: the outline is what the selection adds in every theme.
      const [outline] = await computedStyles(['tbody tr.selected'], 'outline-style');
      assert.equal(outline, 'solid', 'the selected row is outlined');
      await vscode.commands.executeCommand('workbench.action.focusFirstEditorGroup');
      await screenshot(`Variations view: run ${firstCollision} selected`);

      // A run that was not kept: said in the view (no toast that stays after the next run), gone with new results.
      const other = fs
        .readFileSync(csv, 'utf8')
        .split('\n')
        .find((line) => line.split(',')[2] === 'true' && line.split(',')[0] !== firstCollision)
        ?.split(',')[0];
      if (other !== undefined) {
        const kept = path.join(path.dirname(csv), 'runs', other);
        fs.renameSync(kept, `${kept}.away`);
        try {
          assert.ok(await clickText(`#${other}`), `no link to run ${other}`);
          await waitFor('the view to say the run was not kept', () => view.lastNotice);
          await waitFor('the notice on the page', () => pageShows(`Run ${other} was not kept`, '#notice'));
          await screenshot(`Variations view: run ${other} not kept, said in the view`);
        } finally {
          fs.renameSync(`${kept}.away`, kept);
        }
        fs.appendFileSync(csv, '');
        await vscode.commands.executeCommand('modular2simple.showVariations', vscode.Uri.file(csv));
        await waitFor('the notice gone with the results shown again', () => (view.lastNotice === undefined ? true : undefined));
        // The view state clears before the webview repaints: wait for the page, not the state.
        await waitFor('the notice to leave the page', async () => !(await pageShows(`Run ${other} was not kept`, '#notice')));
      }
      await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    });
  });
}
