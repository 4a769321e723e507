import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';
import { CodeAction, CompletionItem, Diagnostic, Hover, Location, MarkupContent } from 'vscode-languageserver/node';
import { main } from '../../server/src/cli';
import { MAIN, mainWithKeys, PACKAGE_MAIN, SIMPLE } from './fixtures/scenarios';
import { fileUri, TestClient, useServer } from './harness';
import { withoutSchema } from '../support/fixtures';
import { markers, positionAfter, positionAt } from '../support/cursor';
import { temporaryWorkspace } from '../support/workspace';

/** The fixtures' simple scenario with a speed default that is full of Markdown characters (its parameters declared). */
const SIMPLE_EXPRESSION = markers(SIMPLE)
  .text.replace('parameterAttributes="value" value="5"', 'parameterAttributes="value" value="${2*$a*$b}"')
  .replace(
    '<OpenSCENARIO>\n',
    '<OpenSCENARIO>\n  <ParameterDeclarations>\n    <ParameterDeclaration name="a" parameterType="double" value="1"/>\n    <ParameterDeclaration name="b" parameterType="double" value="2"/>\n  </ParameterDeclarations>\n',
  )
  .replace('<Event name="SlowDown"', '<Event name="Slow*Down*"');

/** Overrides of group Brake: a bare `value` (both value attributes) and a more specific key for one of them. */
const MAIN_OVERRIDES = mainWithKeys(['<ParameterReference key="value" value="8"/>', '<ParameterReference key="SimulationTimeCondition.value" value="9"/>']);

function lineOf(text: string, needle: string): number {
  return text.slice(0, text.indexOf(needle)).split('\n').length - 1;
}

describe('language server: issue 7 server items (JSON-RPC)', function () {
  const server = useServer({ 'simple.xosc': SIMPLE_EXPRESSION, 'main.xosc': MAIN_OVERRIDES }, 'main.xosc');

  describe('item 4: a key stands for exactly the attributes it sets', function () {
    it('goes from a bare key only to the attribute no more specific key takes', async function () {
      const locations = await server.client.request<Location[]>('textDocument/definition', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')));
      assert.deepEqual(
        locations.map((location) => `${path.basename(location.uri)}:${location.range.start.line}`),
        [`simple.xosc:${lineOf(SIMPLE_EXPRESSION, '<AbsoluteTargetSpeed')}`],
      );
    });

    it('counts in the hover only the attributes the key sets, naming the one a more specific key takes', async function () {
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /^key `value` sets 1 attribute:\n/);
      assert.match(value, /AbsoluteTargetSpeed\.value`: default `\$\{2\*\$a\*\$b\}` declared at `simple\.xosc:\d+`; takes effect: `8` \(this key\)/);
      assert.match(value, /Matched, but set by a more specific key:\n\n- `[^`]*SimulationTimeCondition\.value`: `9` from `SimulationTimeCondition\.value` on line \d+/);
    });

    it('still goes from the specific key to its attribute', async function () {
      const locations = await server.client.request<Location[]>('textDocument/definition', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="SimulationTime')));
      assert.deepEqual(locations.map((location) => location.range.start.line), [lineOf(SIMPLE_EXPRESSION, '<SimulationTimeCondition')]);
    });
  });

  describe('item 5: hovers show values literally', function () {
    it('shows a default of ${2*$a*$b} as code, not as emphasis', async function () {
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'key="val')));
      const value = (hover.contents as MarkupContent).value;
      assert.ok(value.includes('default `${2*$a*$b}`'), value);
      // Outside code spans no Markdown character of a value is left to be read as emphasis.
      const outsideCode = value.replace(/`[^`]*`/g, '');
      assert.ok(!/[*_]/.test(outsideCode), outsideCode);
    });

    it('escapes names in the group hover', async function () {
      const hover = await server.client.request<Hover>('textDocument/hover', server.client.at(server.openUri, positionAfter(MAIN_OVERRIDES, 'maneuverGroupName="Br')));
      const value = (hover.contents as MarkupContent).value;
      assert.match(value, /^ManeuverGroup \*\*Brake\*\* of `simple\.xosc`/);
      assert.ok(value.includes('- Event **Slow\\*Down\\***: SetSpeed (SpeedAction)'), value);
    });
  });

  describe('item 6: completion offers what fits, once', function () {
    const labelsAt = async (marked: string) => {
      const typed = markers(marked);
      const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
      const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, positionAt(typed.text, typed.offsets[0])));
      await server.client.close(uri);
      return [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? '')).map((item) => item.label);
    };
    const inGroup = (content: string) => `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  ${content}`;

    it('offers each overridable attribute once, in its shortest unambiguous key', async function () {
      const labels = await labelsAt(inGroup(`<ScenarioReference scenarioFileName="simple.xosc">
    <ManeuverGroupReference maneuverGroupName="Brake">
      <ParameterReference key="|"`));
      assert.deepEqual(labels, ['AbsoluteTargetSpeed.value', 'delay', 'missing', 'SimulationTimeCondition.value']);
    });

    it('offers ScenarioReference snippets inside a ManeuverGroup, simple scenarios first', async function () {
      const labels = await labelsAt(inGroup('<|'));
      assert.deepEqual(labels, ['ScenarioReference simple.xosc Brake', 'ScenarioReference simple.xosc Wait', 'ScenarioReference main.xosc Outer.Brake']);
    });

    it('offers no ScenarioReference snippet outside a ManeuverGroup', async function () {
      assert.deepEqual(await labelsAt('<OpenSCENARIO><Storyboard><Init><Actions>\n  <|'), []);
      assert.deepEqual(await labelsAt(inGroup('<Maneuver name="M">\n  <|')), []);
      assert.deepEqual(await labelsAt(inGroup('<Maneuver name="M"></Maneuver>\n  <|')).then((labels) => labels.length), 3);
    });
  });
});

describe('language server: completion right after opening, through an unpacked package (JSON-RPC)', function () {
  // The package's groups come from its flattened model, which only exists once rendered.
  const server = useServer({ 'inner/main.xosc': PACKAGE_MAIN, 'inner/simple.xosc': markers(SIMPLE).text, 'other.xosc': markers(SIMPLE).text }, 'other.xosc');

  it('offers the keys of a group of the package at the first request', async function () {
    const typed = markers(`<OpenSCENARIO><Storyboard><Story name="S"><Act name="A"><ManeuverGroup name="G"><Actors><EntityRef entityRef="e"/></Actors>
  <ScenarioReference scenarioFileName="inner.mosc">
    <ManeuverGroupReference maneuverGroupName="Inner.Brake">
      <ParameterReference key="|"`);
    const uri = await server.client.open(fileUri(path.join(server.root, 'typing.xosc')), typed.text);
    const items = await server.client.request<CompletionItem[]>('textDocument/completion', server.client.at(uri, positionAt(typed.text, typed.offsets[0])));
    assert.ok(items.some((item) => item.label === 'AbsoluteTargetSpeed.value'), items.map((item) => item.label).join(', '));
  });
});

/** The fixtures' simple scenario with Wait twice (nothing refers to it) and Brake twice (the main files refer to it). */
function withDuplicateGroups(): string {
  const simpleText = markers(SIMPLE).text;
  const waitStart = simpleText.indexOf('        <ManeuverGroup name="Wait"');
  const waitEnd = simpleText.indexOf('</ManeuverGroup>', waitStart) + '</ManeuverGroup>\n'.length;
  const wait = simpleText.slice(waitStart, waitEnd);
  return simpleText.slice(0, waitEnd) + wait + wait.replace('name="Wait"', 'name="Brake"') + simpleText.slice(waitEnd);
}

describe('language server: duplicate group names (issue 7, item 8; JSON-RPC)', function () {
  const duplicated = withDuplicateGroups();
  const server = useServer({ 'simple.xosc': duplicated, 'main.xosc': mainWithKeys([]) }, 'main.xosc');

  it('warns on the reference that is ambiguous', async function () {
    const diagnostics = await server.client.diagnosticsOf(server.openUri);
    assert.deepEqual(diagnostics.map((diagnostic) => diagnostic.code), ['ambiguous-group']);
  });

  it('does not warn on duplicate names in a file of its own', async function () {
    const uri = await server.client.openFile(path.join(server.root, 'simple.xosc'));
    const diagnostics = await server.client.diagnosticsOf(uri);
    assert.deepEqual(diagnostics.filter((diagnostic) => diagnostic.code === 'duplicate-group'), []);
    await server.client.close(uri);
  });
});

interface WorkspaceReport {
  items: { uri: string; kind: string; resultId?: string; items?: Diagnostic[] }[];
}

/** `file:line:code:severity` of every problem, from `check --format json` or from workspace/diagnostic. */
async function checkLines(root: string): Promise<string[]> {
  const printed: string[] = [];
  // The harness turns the server's schema check off (minimal fixtures), so check runs the same way.
  await main(withoutSchema(['check', root, '--format', 'json', '--root', root]), { out: (text) => printed.push(text), err: () => undefined });
  const report = JSON.parse(printed.join('')) as { problems: { file: string; line: number; code: string; severity: string }[] };
  return report.problems.map((problem) => `${path.resolve(problem.file)}:${problem.line}:${problem.code}:${problem.severity}`).sort();
}

function reportLines(report: WorkspaceReport): string[] {
  const severityName = ['', 'error', 'warning', 'information'];
  return report.items
    .flatMap((file) => (file.items ?? []).map((diagnostic) => `${fileURLToPath(file.uri)}:${diagnostic.range.start.line + 1}:${diagnostic.code}:${severityName[diagnostic.severity ?? 0]}`))
    .sort();
}

describe('language server: workspace-wide pull diagnostics (issue 7, item 7; JSON-RPC)', function () {
  const server = useServer(
    {
      'simple.xosc': withDuplicateGroups(),
      'main.xosc': markers(MAIN).text,
      'clean.xosc': mainWithKeys(['<ParameterReference key="AbsoluteTargetSpeed.value" value="9"/>']),
      'unopened/broken.xosc': mainWithKeys(['<ParameterReference key="nosuchkey" value="1"/>']).replace('scenarioFileName="simple.xosc"', 'scenarioFileName="../simple.xosc"'),
    },
    'clean.xosc',
    { pullDiagnostics: true },
  );

  it('reports every scenario file of the workspace as check does, open or not', async function () {
    const report = await server.client.request<WorkspaceReport>('workspace/diagnostic', { previousResultIds: [] });
    const lines = reportLines(report);
    assert.ok(lines.some((line) => line.includes(`${path.sep}unopened${path.sep}broken.xosc:`) && line.includes(':unknown-key:error')), lines.join('\n'));
    assert.deepEqual(lines, await checkLines(server.root));
  });

  it('answers unchanged for what did not change, and pushes nothing', async function () {
    const first = await server.client.request<WorkspaceReport>('workspace/diagnostic', { previousResultIds: [] });
    const again = await server.client.request<WorkspaceReport>('workspace/diagnostic', {
      previousResultIds: first.items.map((item) => ({ uri: item.uri, value: item.resultId })),
    });
    assert.ok(again.items.every((item) => item.kind === 'unchanged'));
    assert.equal(server.client.diagnostics.size, 0, 'a pulling client gets no diagnostics pushed');
  });

  it('pulls an open document\'s diagnostics, with those other files place in it, and asks for a new pull after an edit', async function () {
    const uri = await server.client.openFile(path.join(server.root, 'simple.xosc'));
    const report = await server.client.request<{ kind: string; items: Diagnostic[] }>('textDocument/diagnostic', { textDocument: { uri } });
    // The duplicate Brake is reported because main.xosc and clean.xosc refer to that name.
    assert.deepEqual(report.items.map((diagnostic) => diagnostic.code).sort(), ['duplicate-group', 'unknown-parameter-attribute']);
    const before = server.client.refreshes;
    await server.client.change(uri, [{ range: { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } }, text: ' ' }]);
    await server.client.until(() => server.client.refreshes > before || undefined, 'a workspace/diagnostic/refresh');
    await server.client.close(uri);
  });
});

describe('language server: workspaces as users have them (issue 7, item 13; JSON-RPC)', function () {
  const simpleText = markers(SIMPLE).text;
  /** A main file in a sub-folder whose simple scenario lies elsewhere: found only through a search root or a scenario path. */
  const mainIn = (fileName: string) => mainWithKeys([]).replace('scenarioFileName="simple.xosc"', `scenarioFileName="${fileName}"`);
  let parent: string;
  let client: TestClient | undefined;

  before(function () {
    parent = temporaryWorkspace({
      'first/placeholder.xosc': simpleText,
      'second/lib.xosc': simpleText,
      'second/sub/main.xosc': mainIn('lib.xosc'),
      'second/libraries/own.xosc': simpleText,
      'second/other/uses-own.xosc': mainIn('own.xosc'),
    });
  });

  afterEach(async function () {
    await client?.stop();
    client = undefined;
  });

  after(function () {
    if (parent) fs.rmSync(parent, { recursive: true, force: true });
  });

  const codesOf = async (filePath: string, predicate?: (diagnostics: Diagnostic[]) => boolean) =>
    (await (client as TestClient).diagnosticsOf(await (client as TestClient).openFile(filePath), predicate)).map((diagnostic) => diagnostic.code);

  it('searches upward to the folder a file is in, not only to the first folder', async function () {
    client = await TestClient.start({ root: path.join(parent, 'first'), folders: [path.join(parent, 'second')] });
    await client.indexed();
    assert.deepEqual(await codesOf(path.join(parent, 'second', 'sub', 'main.xosc')), []);
  });

  it('reads the scenario path setting of each folder', async function () {
    client = await TestClient.start({
      root: path.join(parent, 'first'),
      folders: [path.join(parent, 'second')],
      settings: { scenarioPath: ['nowhere'] },
      folderSettings: { [path.join(parent, 'second')]: { scenarioPath: ['libraries'] } },
    });
    await client.indexed();
    assert.deepEqual(await codesOf(path.join(parent, 'second', 'other', 'uses-own.xosc')), []);
  });

  it('follows workspace folders being added', async function () {
    client = await TestClient.start({ root: path.join(parent, 'first') });
    await client.indexed();
    const uri = fileUri(path.join(parent, 'second', 'sub', 'main.xosc'));
    assert.deepEqual(await codesOf(path.join(parent, 'second', 'sub', 'main.xosc')), ['missing-file']);
    await client.connection.sendNotification('workspace/didChangeWorkspaceFolders', { event: { added: [{ uri: fileUri(path.join(parent, 'second')), name: 'second' }], removed: [] } });
    await client.until(() => (client as TestClient).diagnostics.get(uri)?.diagnostics.length === 0 || undefined, 'the file to resolve in its new folder');
  });

  it('checks an untitled document', async function () {
    client = await TestClient.start({ root: path.join(parent, 'second') });
    await client.indexed();
    const uri = await client.open('untitled:Untitled-1', mainIn('lib.xosc').replace('maneuverGroupName="Brake">', 'maneuverGroupName="Brake">\n<ParameterReference key="nosuchkey" value="1"/>'));
    const diagnostics = await client.diagnosticsOf(uri);
    assert.deepEqual(diagnostics.map((diagnostic) => diagnostic.code), ['unknown-key']);
  });
});

describe('language server: quick fixes (issue 7, item 11; JSON-RPC)', function () {
  const simpleText = markers(SIMPLE).text;
  const server = useServer(
    {
      'simple.xosc': simpleText,
      'dotted.xosc': simpleText.replace('parameterAttributes="value" value="5"', 'parameterAttributes="AbsoluteTargetSpeed.value" value="5"'),
      'keys.xosc': mainWithKeys(['<ParameterReference key="SimulationTimeCondition.valeu" value="1"/>', '<ParameterReference key="TimeHeadwayCondition.value" value="1"/>']),
      'usesite.xosc': mainWithKeys(['<ParameterReference key="AbsoluteTargetSpeed.value" value="7"/>']).replace('scenarioFileName="simple.xosc"', 'scenarioFileName="dotted.xosc"'),
      'group.xosc': mainWithKeys([]).replace('maneuverGroupName="Brake"', 'maneuverGroupName="Nothing"'),
    },
    'keys.xosc',
  );

  async function fixes(name: string, code: string): Promise<{ diagnostic: Diagnostic; actions: CodeAction[] }[]> {
    const uri = await server.client.openFile(path.join(server.root, name));
    const diagnostics = (await server.client.diagnosticsOf(uri)).filter((diagnostic) => diagnostic.code === code);
    const result = [];
    for (const diagnostic of diagnostics) {
      const actions = await server.client.request<CodeAction[]>('textDocument/codeAction', { textDocument: { uri }, range: diagnostic.range, context: { diagnostics: [diagnostic] } });
      result.push({ diagnostic, actions: actions.filter((action) => action.diagnostics) });
    }
    return result;
  }

  it('replaces a mistyped key by the key of the same element and attribute, and offers nothing for a key of another element', async function () {
    const [typo, other] = await fixes('keys.xosc', 'unknown-key');
    assert.deepEqual(typo.actions.map((action) => action.title), ["Change key to 'SimulationTimeCondition.value'"]);
    assert.deepEqual(other.actions.map((action) => action.title), [], 'TimeHeadwayCondition.value means something else');
  });

  it('fixes at the use site a mistake that lives in the simple scenario', async function () {
    const [{ actions }] = await fixes('usesite.xosc', 'unknown-key');
    assert.deepEqual(actions.map((action) => action.title), ["List 'value' in dotted.xosc instead"]);
    const [edit] = actions[0].edit?.changes?.[fileUri(path.join(server.root, 'dotted.xosc'))] ?? [];
    assert.equal(edit?.newText, 'value');
    const dotted = fs.readFileSync(path.join(server.root, 'dotted.xosc'), 'utf8');
    assert.equal(dotted.split('\n')[edit.range.start.line].slice(edit.range.start.character, edit.range.end.character), 'AbsoluteTargetSpeed.value');
  });

  it('offers the groups that exist for an unknown group', async function () {
    const [{ actions }] = await fixes('group.xosc', 'unknown-group');
    assert.deepEqual(actions.map((action) => action.title), ["Change to 'Brake'", "Change to 'Wait'"]);
  });
});
