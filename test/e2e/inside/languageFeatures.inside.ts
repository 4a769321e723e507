import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import * as vscode from 'vscode';
import {
  api,
  type InsideTests,
  open,
  positionOf,
  replaceText,
  requireServerFeature,
  revertAndClose,
  waitFor,
  WAIT_MS,
  workspaceRoot,
} from './helpers';
import { catalogFile, vehicleObject } from '../../support/fixtures';
import { pageShows, post, pressKeys, screenshot } from './harnessClient';

/** A one-road OpenDRIVE file: what the road-file check looks for is that it is there. */
const OUTSIDE_ROAD = `<?xml version="1.0" encoding="UTF-8"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="4" name="outside" version="1"/>
  <road name="r" length="100" id="0" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
    <lanes><laneSection s="0"><center><lane id="0" type="driving" level="false"/></center>
      <right><lane id="-1" type="driving" level="false"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>
</OpenDRIVE>
`;

/** A vehicle catalog holding `car_outside`: the fixtures' car, out of its ScenarioObject. */
const OUTSIDE_CATALOG = catalogFile(
  'VehicleCatalog',
  vehicleObject('unused')
    .replace(/ *<\/?ScenarioObject[^>]*>\n/g, '')
    .replace('name="car"', 'name="car_outside"'),
);

/**
 * Writes `file` outside the workspace until `seen` holds: a new watcher starts in its own time, so a creation made
 * before it started goes unseen, and the file is removed and written again, waiting longer each time.
 */
async function writeUntilSeen(what: string, file: string, content: string, seen: () => boolean): Promise<void> {
  let patience = 3_000;
  await waitFor(
    what,
    async () => {
      fs.rmSync(file, { force: true });
      await new Promise((resolve) => setTimeout(resolve, 500));
      fs.writeFileSync(file, content);
      const found = await waitFor(`${path.basename(file)} to be seen`, () => seen() || undefined, patience).catch(() => undefined);
      patience = Math.min(2 * patience, WAIT_MS / 2);
      return found;
    },
    2 * WAIT_MS,
  );
}

/** The language server's features as the editor shows them: diagnostics, completion, definition, the scenario path, expressions, the schema. */
export const languageFeatureTests: InsideTests = {
  diagnostic: async function () {
    requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
    const editor = await open('main.xosc');
    const uri = editor.document.uri;
    await waitFor(
      'the example to check clean',
      () => vscode.languages.getDiagnostics(uri).every((d) => d.severity !== vscode.DiagnosticSeverity.Error) || undefined,
    );
    await replaceText(editor.document, 'key="AbsoluteTargetSpeed.value"', 'key="AbsoluteTargetSped.value"');
    const keyLine = positionOf(editor.document, 'AbsoluteTargetSped.value').line;
    const diagnostic = await waitFor('a diagnostic on the bad key', () =>
      vscode.languages.getDiagnostics(uri).find((d) => d.range.start.line === keyLine),
    );
    assert.match(diagnostic.message, /AbsoluteTargetSped\.value|AbsoluteTargetSpeed/);
    editor.revealRange(diagnostic.range, vscode.TextEditorRevealType.InCenter);
    editor.selection = new vscode.Selection(diagnostic.range.start, diagnostic.range.start);
    await vscode.commands.executeCommand('editor.action.marker.next');
    await screenshot('diagnostic on a bad key (marker)');
    await revertAndClose();
  },

  completion: async function () {
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
      const result = await vscode.commands.executeCommand<vscode.CompletionList>(
        'vscode.executeCompletionItemProvider',
        editor.document.uri,
        cursor,
      );
      return result.items.length > 0 ? result : undefined;
    });
    const labels = list.items.map((item) => (typeof item.label === 'string' ? item.label : item.label.label));
    for (const expected of ['dynamicsShape', 'delay', 'SimulationTimeCondition.value']) {
      assert.ok(
        labels.some((label) => label === expected || label.endsWith(`.${expected}`)),
        `completion lacks ${expected}: ${labels.join(', ')}`,
      );
    }
    assert.ok(!labels.includes('AbsoluteTargetSpeed.value'), `a key already given is offered again: ${labels.join(', ')}`);
    await vscode.commands.executeCommand('editor.action.triggerSuggest');
    await waitFor(
      'the suggest widget',
      async () => (await post<{ found: boolean }>('/findText', { text: 'dynamicsShape' })).found || undefined,
    );
    await screenshot('completion offers the overridable keys (widget)');
    await revertAndClose();
  },

  definition: async function () {
    requireServerFeature(this, 'go to definition', !!api().serverCapabilities()?.definitionProvider);
    const editor = await open('main.xosc');
    const cursor = positionOf(editor.document, 'scenarioFileName="lane_change.xosc"', 'scenarioFileName="lane'.length);
    editor.selection = new vscode.Selection(cursor, cursor);
    const locations = await vscode.commands.executeCommand<(vscode.Location | vscode.LocationLink)[]>(
      'vscode.executeDefinitionProvider',
      editor.document.uri,
      cursor,
    );
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
  },

  scenarioPath: async function () {
    requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
    // A library folder outside the workspace, found only through the setting.
    const library = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-library-'));
    fs.copyFileSync(path.join(workspaceRoot(), 'lane_change.xosc'), path.join(library, 'shared_lane_change.xosc'));
    const editor = await open('main.xosc');
    const uri = editor.document.uri;
    await replaceText(editor.document, 'scenarioFileName="lane_change.xosc"', 'scenarioFileName="shared_lane_change.xosc"');
    const line = positionOf(editor.document, 'shared_lane_change.xosc').line;
    const onReference = (): vscode.Diagnostic | undefined =>
      vscode.languages.getDiagnostics(uri).find((d) => d.range.start.line === line && d.severity === vscode.DiagnosticSeverity.Error);
    await waitFor('the missing file to be reported', onReference);
    const settings = vscode.workspace.getConfiguration('modular2simple');
    await settings.update('scenarioPath', [library], vscode.ConfigurationTarget.Workspace);
    try {
      await waitFor('the reference to resolve through the setting', () => !onReference() || undefined);
      // The library lies outside the workspace, and still its files are watched: a file removed there is reported.
      // A new watcher starts in its own time: the file goes away and comes back until the removal is seen.
      const [present, away] = [path.join(library, 'shared_lane_change.xosc'), path.join(library, 'moved_away.xosc')];
      // Each try waits twice as long as the last: on a loaded machine the watcher's event and the new diagnostics take their time.
      let patience = 3_000;
      await waitFor(
        'the removed library file to be reported',
        async () => {
          if (fs.existsSync(away)) fs.renameSync(away, present);
          await new Promise((resolve) => setTimeout(resolve, 500));
          fs.renameSync(present, away);
          const reported = await waitFor('the removal to be reported', onReference, patience).catch(() => undefined);
          patience = Math.min(2 * patience, WAIT_MS / 2);
          return reported;
        },
        2 * WAIT_MS,
      );
      fs.renameSync(path.join(library, 'moved_away.xosc'), path.join(library, 'shared_lane_change.xosc'));
      await waitFor('the restored library file to resolve', () => !onReference() || undefined);
    } finally {
      await settings.update('scenarioPath', undefined, vscode.ConfigurationTarget.Workspace);
      await revertAndClose();
      fs.rmSync(library, { recursive: true, force: true });
    }
  },

  roadPath: async function () {
    requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
    // A road folder outside the workspace, named only by the setting: the editor does not watch it by itself.
    const roads = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-roads-'));
    const road = path.join(roads, 'outside_road.xodr');
    const editor = await open('main.xosc');
    const uri = editor.document.uri;
    await replaceText(editor.document, 'filepath="Town05"', 'filepath="outside_road.xodr"');
    const roadFile = (): vscode.Diagnostic | undefined =>
      vscode.languages
        .getDiagnostics(uri)
        .find((d) => (typeof d.code === 'object' ? String(d.code.value) : String(d.code)) === 'road-file');
    const settings = vscode.workspace.getConfiguration('modular2simple.esmini');
    await settings.update('roadPath', [roads], vscode.ConfigurationTarget.Workspace);
    try {
      // The server has looked in the folder and found nothing there: what it read of it stays until it hears otherwise.
      await waitFor('the road-file warning naming the road folder', () => (roadFile()?.message.includes(roads) ? true : undefined));
      await writeUntilSeen('the road-file warning to go once the road appears in the road folder', road, OUTSIDE_ROAD, () => !roadFile());
    } finally {
      await settings.update('roadPath', undefined, vscode.ConfigurationTarget.Workspace);
      await revertAndClose();
      fs.rmSync(roads, { recursive: true, force: true });
    }
  },

  catalogDirectory: async function () {
    requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
    // A catalog folder outside the workspace, named only by the scenario's Directory: neither the editor nor a setting watches it.
    const catalogs = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-catalogs-'));
    const catalog = path.join(catalogs, 'VehicleCatalog.xosc');
    const editor = await open('main.xosc');
    const uri = editor.document.uri;
    await replaceText(
      editor.document,
      '<CatalogLocations/>',
      `<CatalogLocations><VehicleCatalog><Directory path="${catalogs}"/></VehicleCatalog></CatalogLocations>`,
    );
    await replaceText(
      editor.document,
      '<ScenarioObject name="adversary">',
      '<ScenarioObject name="shared"><CatalogReference catalogName="VehicleCatalog" entryName="car_outside"/></ScenarioObject><ScenarioObject name="adversary">',
    );
    const unknownCatalog = (): vscode.Diagnostic | undefined =>
      vscode.languages
        .getDiagnostics(uri)
        .find((d) => /^unknown-catalog/.test(typeof d.code === 'object' ? String(d.code.value) : String(d.code)));
    try {
      await waitFor('the catalog error: the folder holds no VehicleCatalog yet', () => unknownCatalog() ?? undefined);
      // The server registers the folder's watcher once it has read there.
      await writeUntilSeen(
        'the catalog error to go once the catalog appears in the folder outside the workspace',
        catalog,
        OUTSIDE_CATALOG,
        () => !unknownCatalog(),
      );
    } finally {
      await revertAndClose();
      fs.rmSync(catalogs, { recursive: true, force: true });
    }
  },

  expression: async function () {
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
  },

  schemaCompletion: async function () {
    requireServerFeature(this, 'completion', !!api().serverCapabilities()?.completionProvider);
    const editor = await open('crossing.xosc');
    await replaceText(
      editor.document,
      '<Actions>\n        <Private entityRef="ego">',
      '<Actions>\n        <\n        <Private entityRef="ego">',
    );
    const line = positionOf(editor.document, '<Actions>').line + 1;
    editor.selection = new vscode.Selection(new vscode.Position(line, 9), new vscode.Position(line, 9));
    editor.revealRange(new vscode.Range(line, 0, line, 9), vscode.TextEditorRevealType.InCenter);
    const list = await waitFor('schema completion items', async () => {
      const result = await vscode.commands.executeCommand<vscode.CompletionList>(
        'vscode.executeCompletionItemProvider',
        editor.document.uri,
        new vscode.Position(line, 9),
      );
      return result.items.length > 0 ? result : undefined;
    });
    const labels = list.items.map((item) => (typeof item.label === 'string' ? item.label : item.label.label));
    assert.deepEqual(
      labels.filter((label) => ['GlobalAction', 'UserDefinedAction', 'Private'].includes(label)),
      ['GlobalAction', 'UserDefinedAction', 'Private'],
    );
    await vscode.commands.executeCommand('editor.action.triggerSuggest');
    await waitFor(
      'the suggest widget showing UserDefinedAction',
      async () =>
        (await post<{ found: boolean }>('/findText', { text: 'UserDefinedAction', selector: '.suggest-widget' })).found || undefined,
    );
    await screenshot('schema completion of a child element (widget)');
    await vscode.commands.executeCommand('hideSuggestWidget');
    await revertAndClose();
  },

  schemaDeprecated: async function () {
    requireServerFeature(this, 'diagnostics', !!api().serverCapabilities()?.textDocumentSync);
    const crossing = fs.readFileSync(path.join(workspaceRoot(), 'crossing.xosc'), 'utf8');
    // The example as an OpenSCENARIO 1.3 file whose Init activates a controller the way 1.0 did (deprecated since 1.1).
    const deprecated = crossing
      .replace('revMinor="0"', 'revMinor="3"')
      .replace(
        '<Actions>\n',
        '<Actions>\n        <Private entityRef="walker">\n          <PrivateAction>\n            <ActivateControllerAction longitudinal="true"/>\n          </PrivateAction>\n        </Private>\n',
      );
    const file = path.join(workspaceRoot(), 'deprecated_1_3.xosc');
    fs.writeFileSync(file, deprecated);
    const editor = await open('deprecated_1_3.xosc');
    const diagnostic = await waitFor('the deprecated diagnostic', () =>
      vscode.languages
        .getDiagnostics(editor.document.uri)
        .find(
          (candidate) => candidate.tags?.includes(vscode.DiagnosticTag.Deprecated) && /<ActivateControllerAction>/.test(candidate.message),
        ),
    );
    assert.match(diagnostic.message, /<ActivateControllerAction> is deprecated since OpenSCENARIO 1\.1/);
    editor.revealRange(diagnostic.range, vscode.TextEditorRevealType.InCenter);
    await waitFor(
      'the struck-through element name',
      async () =>
        (await post<{ found: boolean }>('/findText', { text: 'ActivateControllerAction', selector: '.squiggly-inline-deprecated' }))
          .found || undefined,
    );
    editor.selection = new vscode.Selection(diagnostic.range.start, diagnostic.range.start);
    await vscode.commands.executeCommand('editor.action.showHover');
    await screenshot('a deprecated element struck through (hover)');
    await vscode.commands.executeCommand('workbench.action.closeAllEditors');
    fs.rmSync(file, { force: true });
  },
};

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

async function showExpression(): Promise<void> {
  const editor = await open('expressions.xosc');
  const hints = await waitFor('the inlay hints', async () => {
    const found = await vscode.commands.executeCommand<vscode.InlayHint[]>(
      'vscode.executeInlayHintProvider',
      editor.document.uri,
      new vscode.Range(0, 0, editor.document.lineCount, 0),
    );
    return found.length > 0 ? found : undefined;
  });
  assert.deepEqual(
    hints.map((hint) => hint.label),
    ['= 3'],
  );
  // What a person sees: the value drawn after the attribute, then the hover over the expression.
  // The editor draws spaces as no-break spaces.
  await waitFor(
    'the hint drawn in the editor',
    async () => (await pageShows('= 3', '.monaco-editor .view-lines')) || (await pageShows('=\u00a03', '.monaco-editor .view-lines')),
  );
  const cursor = positionOf(editor.document, '${2*$a/$b}', 3);
  editor.selection = new vscode.Selection(cursor, cursor);
  await vscode.commands.executeCommand('workbench.action.focusActiveEditorGroup');
  await vscode.commands.executeCommand('editor.action.showHover');
  await waitFor(
    'the hover with the value and the declarations',
    async () =>
      (await pageShows('= 3 (double)', '.monaco-hover')) && (await pageShows('declared in <OpenSCENARIO> on line 6', '.monaco-hover')),
  );
  await screenshot('expression value as inlay hint and hover');
}
