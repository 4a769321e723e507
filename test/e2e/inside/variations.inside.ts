import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { BIRDS_EYE_FILES } from '../birdsEyeSetup';
import { INSIDE_TESTS } from '../titles';
import { VARIATIONS_FILES } from '../variationsSetup';
import { esminiOrSkip } from './esmini.inside';
import { api, open, TEST_MS, waitFor, waitForPage, workspaceRoot } from './helpers';
import { clickElement, clickText, computedStyles, pageBoxes, pageShows, runFromPalette, screenshot } from './harnessClient';

/** What the toasts show now, read at once. */
async function toastsText(): Promise<string> {
  return (await pageBoxes('.notifications-toasts')).map((box) => box.text).join('\n');
}

/** The Variations view's table as the page shows it: a record of cells by column name for each row. */
async function shownRows(): Promise<Record<string, string>[]> {
  const columns = (await pageBoxes('table.results thead th')).map((box) => box.text.replace(/ [▲▼]$/, '').trim());
  const rows = await pageBoxes('table.results tbody tr');
  return rows.map((row) => Object.fromEntries(row.text.split('\t').map((cell, i) => [columns[i], cell.trim()])));
}

/**
 * follow.xosc in esmini's samples' layout (xosc/ beside xodr/), with its road a parameter, and a distribution of it
 * beside it: the road e6mini or a file that is not there, times a StopTrigger at 2 s or at 40 s (past the 30 s that
 * Run Variations cut every run at before).
 */
function reasonsFolder(repository: string, roads: string, distributions: string[]): string {
  const folder = path.join(workspaceRoot(), 'variationsReasons');
  fs.mkdirSync(path.join(folder, 'xosc'), { recursive: true });
  fs.mkdirSync(path.join(folder, 'xodr'), { recursive: true });
  fs.copyFileSync(path.join(roads, 'e6mini.xodr'), path.join(folder, 'xodr', 'e6mini.xodr'));
  const follow = fs.readFileSync(path.join(repository, 'test', 'fixtures', 'variations', 'follow.xosc'), 'utf8');
  const scenario = follow
    .replace('<LogicFile filepath="e6mini.xodr"/>', '<LogicFile filepath="$Road"/>')
    .replace(
      '<ParameterDeclarations>',
      '<ParameterDeclarations>\n    <ParameterDeclaration name="Road" parameterType="string" value="../xodr/e6mini.xodr"/>',
    )
    // Ego as fast as the lead: no collision, so that each row's colour is its status.
    .replace('name="EgoSpeed" parameterType="double" value="20"', 'name="EgoSpeed" parameterType="double" value="10"');
  assert.equal((scenario.match(/\$Road|name="Road"|name="EgoSpeed" parameterType="double" value="10"/g) ?? []).length, 3);
  fs.writeFileSync(path.join(folder, 'xosc', 'follow.xosc'), scenario);
  for (const name of distributions)
    fs.writeFileSync(
      path.join(folder, 'xosc', name),
      `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-28T00:00:00" description="a road that is there or not, an end at 2 s or 40 s" author="modular2simple tests"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath="follow.xosc"/>
    <Deterministic>
      <DeterministicSingleParameterDistribution parameterName="Road">
        <DistributionSet><Element value="../xodr/e6mini.xodr"/><Element value="../xodr/e6mini_gone.xodr"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="StopTime">
        <DistributionSet><Element value="2"/><Element value="40"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
    </Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
`,
    );
  return folder;
}

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
      // Named as the table lists it, not by its file (every kept run is a trajectories.csv beside a scenario.xosc).
      await waitFor('the run named by its index', () => pageShows(`run: #${firstCollision} of `));
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

    it(INSIDE_TESTS.variationsReasons, async function () {
      this.timeout(2 * TEST_MS);
      const { repository, esmini, roads } = esminiOrSkip(this);
      const folder = reasonsFolder(repository, roads, ['follow_to_end.xosc', 'follow_limit.xosc']);
      const esminiSettings = vscode.workspace.getConfiguration('modular2simple.esmini');
      await esminiSettings.update('path', esmini, vscode.ConfigurationTarget.Workspace);
      const view = api().variations;
      /** Opens the distribution, runs Run Variations from the palette as a person does, and waits for its 4 rows in the view. */
      const runVariations = async (name: string): Promise<Record<string, string>[]> => {
        await vscode.commands.executeCommand('workbench.action.closeAllEditors');
        await vscode.commands.executeCommand('notifications.clearAll');
        const distribution = await open(`variationsReasons/xosc/${name}`);
        await waitFor('the Run Variations lens', async () => {
          const lenses = await vscode.commands.executeCommand<vscode.CodeLens[]>(
            'vscode.executeCodeLensProvider',
            distribution.document.uri,
            100,
          );
          return lenses.some((lens) => lens.command?.command === 'modular2simple.runVariations');
        });
        await runFromPalette('Modular2Simple: Run Variations');
        // Two runs name a road that is not there: the batch ends with an error notification saying why.
        const toasts = await waitFor(`the notification that Run Variations of ${name} ended`, async () => {
          const shown = await toastsText();
          return shown.includes(`Run Variations of ${name}`) ? shown : undefined;
        });
        const results = path.join(folder, 'xosc', name.replace(/\.xosc$/, '.results'));
        await waitFor('the results in the Variations view', () => (view.folder === results && view.stats?.rows === 4 ? true : undefined));
        assert.ok(!toasts.includes('Running the variations of'), `the batch's progress is still shown beside its result:\n${toasts}`);
        assert.match(toasts, /2 of 4 runs failed in esmini/);
        assert.ok(
          !toasts.includes(path.join(results, 'results.csv')) && toasts.includes(`${path.basename(results)}/results.csv`),
          `the notification names results.csv by its path in the workspace, not the whole path:\n${toasts}`,
        );
        assert.match(toasts, /Failed to locate OpenDRIVE file \.\.\/xodr\/e6mini_gone\.xodr/);
        await waitForPage('4 runs:');
        // Each run's reason (the last column) is read in the view as it opens, without scrolling sideways.
        const [area] = await pageBoxes('#tableArea');
        const reasons = await pageBoxes('table.results tbody td:last-child');
        assert.ok(area && reasons.length === 4, 'the table is on the page');
        for (const reason of reasons)
          assert.ok(
            reason.left >= area.left && reason.right <= area.right,
            `the reason "${reason.text}" is drawn at ${reason.left}-${reason.right}, beyond the view's ${area.left}-${area.right}`,
          );
        return shownRows();
      };
      const refusal = /^esmini did not run the scenario \(exit code \d+\): Failed to locate OpenDRIVE file \.\.\/xodr\/e6mini_gone\.xodr$/;
      const REFUSED = "esmini's refusal, in its words";
      /** Status, end time and reason of the runs of e6mini ending at 2 s and at 40 s, then of the road not there. */
      const outcomes = (rows: Record<string, string>[]): string[][] =>
        ['e6mini.xodr', 'e6mini_gone.xodr'].flatMap((road) =>
          ['2', '40'].map((stopTime) => {
            const found = rows.find((each) => each.Road === `../xodr/${road}` && each.StopTime === stopTime);
            assert.ok(found, `no row of ${road} and StopTime ${stopTime} in ${JSON.stringify(rows)}`);
            return [found.status, found.end_time_s, refusal.test(found.reason) ? REFUSED : found.reason];
          }),
        );
      try {
        // No duration set: each run goes to its StopTrigger, 40 s included; the runs esmini refused are errors, each with esmini's reason.
        const toEnd = await runVariations('follow_to_end.xosc');
        assert.deepEqual(
          outcomes(toEnd),
          [
            ['ok', '2.050', ''],
            ['ok', '40.050', ''],
            ['error', '', REFUSED],
            ['error', '', REFUSED],
          ],
          'each run esmini ran ended by its StopTrigger, the one at 40 s too',
        );
        assert.ok(await pageShows('4 runs: 2 ok, 0 limit, 0 collision, 0 timeout, 2 error, 0 discarded'), 'the summary');
        await screenshot('Run Variations: runs to their StopTrigger, esmini refusals with their reason');

        // The duration setting at 10 s: the run whose StopTrigger comes later stops there, as limit, and says so.
        await esminiSettings.update('duration', 10, vscode.ConfigurationTarget.Workspace);
        const limited = await runVariations('follow_limit.xosc');
        assert.deepEqual(outcomes(limited), [
          ['ok', '2.050', ''],
          [
            'limit',
            '10.000',
            'stopped at the 10 s limit set by the modular2simple.esmini.duration setting, before the scenario ended by itself',
          ],
          ['error', '', REFUSED],
          ['error', '', REFUSED],
        ]);
        assert.ok(await pageShows('4 runs: 1 ok, 1 limit, 0 collision, 0 timeout, 2 error, 0 discarded'), 'the summary');
        // The rows name the setting that set the limit (the editor tells the CLI it), and so does a notification.
        await waitFor('a notification naming the duration setting', async () =>
          (await toastsText()).includes(
            'Run Variations of follow_limit.xosc: 1 run stopped at the 10 s limit of the modular2simple.esmini.duration setting',
          )
            ? true
            : undefined,
        );
        await screenshot('Run Variations with a 10 s duration: ok, limit and error, each with its reason');

        // The duration at 5 s and Run Variations again: the folder holds the 10 s batch's results, which the CLI never
        // mixes with another's; the editor asks before it replaces them, and shows the new batch, not the old one.
        await esminiSettings.update('duration', 5, vscode.ConfigurationTarget.Workspace);
        await vscode.commands.executeCommand('notifications.clearAll');
        // Back in the distribution's editor: the palette offers Run Variations there, not over the view.
        await open('variationsReasons/xosc/follow_limit.xosc');
        await runFromPalette('Modular2Simple: Run Variations');
        await waitForPage(
          'Run Variations of follow_limit.xosc: follow_limit.results holds the results of an earlier batch, and it differs in the duration limit',
        );
        await screenshot('Run Variations asks before replacing the results of another batch');
        assert.ok(await clickElement('.notifications-toasts .monaco-button', 'Replace'), 'no Replace button in the question');
        const replaced = await waitFor('the new batch in the view', async () => {
          const shown = outcomes(await shownRows());
          return shown[1][1] === '5.000' ? shown : undefined;
        });
        assert.deepEqual(replaced, [
          ['ok', '2.050', ''],
          [
            'limit',
            '5.000',
            'stopped at the 5 s limit set by the modular2simple.esmini.duration setting, before the scenario ended by itself',
          ],
          ['error', '', REFUSED],
          ['error', '', REFUSED],
        ]);
        await screenshot('Run Variations replaced the results of the 10 s batch by those of the 5 s batch');
      } finally {
        for (const key of ['path', 'duration']) await esminiSettings.update(key, undefined, vscode.ConfigurationTarget.Workspace);
        await vscode.commands.executeCommand('workbench.action.closeAllEditors');
        fs.rmSync(folder, { recursive: true, force: true });
      }
    });
  });
}
