import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import {
  CodeAction,
  CompletionItem,
  Diagnostic,
  DiagnosticSeverity,
  DiagnosticTag,
  Hover,
  InlayHint,
  Location,
  MarkupContent,
  SemanticTokens,
  TextEdit,
  WorkspaceEdit,
} from 'vscode-languageserver/node';
import { SEMANTIC_TOKENS_LEGEND } from '../../server/src/features/semanticTokens';
import { BARE, CARS, FAULTY, PARAMETERS } from './fixtures/parameters';
import { fileUri, TestClient } from './harness';
import { applyEdits, inside, Position, textAt } from '../support/textEdits';
import { problemCodeOf } from '../support/diagnostics';
import { repoRoot } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

type Range = { start: Position; end: Position };

function lineOf(text: string, needle: string, nth = 0): number {
  return inside(text, needle, 0, nth).line;
}

function hoverText(hover: Hover | null): string {
  assert.ok(hover, 'a hover');
  return (hover.contents as MarkupContent).value;
}

/** Decodes LSP semantic tokens into `line:text:type[+modifiers]`. */
function decodeTokens(text: string, tokens: SemanticTokens): string[] {
  const lines = text.split('\n');
  const result: string[] = [];
  let line = 0;
  let character = 0;
  for (let i = 0; i < tokens.data.length; i += 5) {
    const [deltaLine, deltaStart, length, type, modifiers] = tokens.data.slice(i, i + 5);
    line += deltaLine;
    character = deltaLine === 0 ? character + deltaStart : deltaStart;
    const names = SEMANTIC_TOKENS_LEGEND.tokenModifiers.filter((_, bit) => modifiers & (1 << bit));
    result.push(
      `${line}:${lines[line].slice(character, character + length)}:${SEMANTIC_TOKENS_LEGEND.tokenTypes[type]}${names.map((name) => `+${name}`).join('')}`,
    );
  }
  return result;
}

describe('editor features on the semantic model: $name, ${...} and catalogs (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;
  let uri: string;
  const text = PARAMETERS;

  before(async function () {
    const zip = new JSZip();
    zip.file('main.xosc', PARAMETERS);
    zip.file('catalogs/Cars.xosc', CARS);
    root = temporaryWorkspace({
      'parameters.xosc': PARAMETERS,
      'catalogs/Cars.xosc': CARS,
      'faulty.xosc': FAULTY,
      'bare.xosc': BARE,
      'bundle.mosc': await zip.generateAsync({ type: 'uint8array' }),
    });
    client = await TestClient.start({ root });
    await client.indexed();
    uri = await client.openFile(path.join(root, 'parameters.xosc'));
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('reports no diagnostic on the well-formed file (the entity check reads $owner as Ego)', async function () {
    const diagnostics = await client.diagnosticsOf(uri);
    assert.deepEqual(
      diagnostics.map((diagnostic) => `${diagnostic.range.start.line + 1}:${problemCodeOf(diagnostic)}: ${diagnostic.message}`),
      [],
    );
  });

  it('goes from $speed to the declaration of its own scope (Maneuver, Story, root)', async function () {
    const inManeuver = await client.request<Location[]>('textDocument/definition', client.at(uri, inside(text, 'value="$speed"', 9, 0)));
    assert.equal(inManeuver.length, 1);
    assert.equal(inManeuver[0].uri, uri);
    assert.equal(inManeuver[0].range.start.line, lineOf(text, 'name="speed" parameterType="double" value="30"'));
    const inOuterGroup = await client.request<Location[]>('textDocument/definition', client.at(uri, inside(text, 'value="$speed"', 9, 1)));
    assert.equal(inOuterGroup[0].range.start.line, lineOf(text, 'name="speed" parameterType="double" value="20"'));
    const inDeclaration = await client.request<Location[]>('textDocument/definition', client.at(uri, inside(text, '$speed * 3', 2)));
    assert.equal(inDeclaration[0].range.start.line, lineOf(text, 'name="speed" parameterType="double" value="10"'));
    assert.equal(textAt(text, inDeclaration[0].range), 'speed');
  });

  it('finds the references of one declaration only', async function () {
    const locations = await client.request<Location[]>('textDocument/references', {
      ...client.at(uri, inside(text, 'name="speed" parameterType="double" value="20"', 7)),
      context: { includeDeclaration: true },
    });
    assert.deepEqual(
      locations.map((location) => `${location.range.start.line}:${textAt(text, location.range)}`),
      [
        `${lineOf(text, 'name="speed" parameterType="double" value="20"')}:speed`,
        `${lineOf(text, 'value="$speed"', 1)}:$speed`,
        `${lineOf(text, '${$speed + 0.5}')}:$speed`,
      ],
    );
  });

  it('renames a parameter scope-aware, never touching a same-named parameter of another scope', async function () {
    const at = client.at(uri, inside(text, 'value="$speed"', 10, 0));
    const prepared = await client.request<{ range: Range; placeholder: string }>('textDocument/prepareRename', at);
    assert.equal(prepared.placeholder, 'speed');
    assert.equal(textAt(text, prepared.range), 'speed');
    const edit = await client.request<WorkspaceEdit>('textDocument/rename', { ...at, newName: 'maneuverSpeed' });
    const renamed = applyEdits(text, edit.changes?.[uri] ?? []);
    assert.equal(edit.changes?.[uri]?.length, 2, 'the Maneuver declaration and its one use');
    assert.match(renamed, /name="maneuverSpeed" parameterType="double" value="30"/);
    assert.match(renamed, /<AbsoluteTargetSpeed value="\$maneuverSpeed"\/>/);
    // The root's and the Story's speed, and every use of them, stay.
    assert.match(renamed, /name="speed" parameterType="double" value="10"/);
    assert.match(renamed, /name="speed" parameterType="double" value="20"/);
    assert.equal(renamed.match(/<AbsoluteTargetSpeed value="\$speed"\/>/g)?.length, 1);
    assert.match(renamed, /\$\{\$speed \* 3\}/);
    assert.match(renamed, /\$\{\$speed \+ 0\.5\}/);
    await assert.rejects(client.request('textDocument/rename', { ...at, newName: '1bad' }), /not a parameter name/);
  });

  it("renames every $name, also the one inside an expression with errors (esmini's text gluing in its cut-in.xosc)", async function () {
    const glued = BARE.replace(
      '<RoadNetwork/>',
      '<ParameterDeclarations>\n    <ParameterDeclaration name="HeadwayTime_Brake" parameterType="double" value="0.7"/>\n  </ParameterDeclarations>\n  <RoadNetwork/>',
    )
      .replace('<Condition name="End"', '<Condition name="${BrakeCondition_HWT + _ + $HeadwayTime_Brake}"')
      .replace('value="$stopTime"', 'value="$HeadwayTime_Brake"');
    const scratch = fileUri(path.join(root, 'glued.xosc'));
    await client.open(scratch, glued);
    for (const at of [inside(glued, 'value="$HeadwayTime_Brake"', 9), inside(glued, '+ $HeadwayTime_Brake}', 4)]) {
      const prepared = await client.request<{ range: Range; placeholder: string }>('textDocument/prepareRename', client.at(scratch, at));
      assert.equal(prepared.placeholder, 'HeadwayTime_Brake');
      const edit = await client.request<WorkspaceEdit>('textDocument/rename', { ...client.at(scratch, at), newName: 'BrakeHeadway' });
      const renamed = applyEdits(glued, edit.changes?.[scratch] ?? []);
      assert.equal(edit.changes?.[scratch]?.length, 3, 'the declaration and both uses');
      assert.match(renamed, /name="BrakeHeadway" parameterType="double"/);
      assert.match(renamed, /name="\$\{BrakeCondition_HWT \+ _ \+ \$BrakeHeadway\}"/);
      assert.match(renamed, /value="\$BrakeHeadway"/);
      assert.doesNotMatch(renamed, /HeadwayTime_Brake/);
    }
    const references = await client.request<Location[]>('textDocument/references', {
      ...client.at(scratch, inside(glued, 'value="$HeadwayTime_Brake"', 9)),
      context: { includeDeclaration: false },
    });
    assert.equal(references.length, 2);
    await client.close(scratch);
  });

  it('completes $ inside a Maneuver with the parameters in scope, the inner declarations first, with value and type', async function () {
    const edited = text.replace('<AbsoluteTargetSpeed value="$speed"/>', '<AbsoluteTargetSpeed value="$"/>');
    const scratch = fileUri(path.join(root, 'scratch.xosc'));
    await client.open(scratch, edited);
    const items = await client.request<CompletionItem[]>('textDocument/completion', client.at(scratch, inside(edited, 'value="$"', 8)));
    const ordered = [...items].sort((a, b) => (a.sortText ?? '').localeCompare(b.sortText ?? ''));
    assert.deepEqual(
      ordered.map((item) => `${item.label} ${item.detail}`),
      ['$speed double = 30', '$gap double = 2', '$a double = 6', '$b double = 4', '$owner string = Ego', '$carSpeed double = 30'],
    );
    assert.equal(textAt(edited, (ordered[0].textEdit as TextEdit).range), '$');
    await client.close(scratch);
  });

  it('hovers ${2*$a/$b} with its value and the declarations of a and b', async function () {
    const hover = await client.request<Hover>('textDocument/hover', client.at(uri, inside(text, '${2*$a/$b}', 5)));
    const shown = hoverText(hover);
    assert.match(shown, /`\$\{2\*\$a\/\$b\}` = \*\*3\*\* \(double\)/);
    assert.match(shown, new RegExp(`\`\\$a\` = 6 \\(double\\), declared in \`<OpenSCENARIO>\` on line ${lineOf(text, 'name="a"') + 1}`));
    assert.match(shown, new RegExp(`\`\\$b\` = 4 \\(double\\), declared in \`<OpenSCENARIO>\` on line ${lineOf(text, 'name="b"') + 1}`));
  });

  it('hovers $name with its type, value and declaration, and a catalog entry parameter with its assignment', async function () {
    const shown = hoverText(await client.request<Hover>('textDocument/hover', client.at(uri, inside(text, 'value="$speed"', 9, 1))));
    assert.match(shown, /\*\*\$speed\*\* = 20 \(double\)/);
    assert.match(shown, /declared in `<Story S>` on line/);
    const owner = hoverText(await client.request<Hover>('textDocument/hover', client.at(uri, inside(text, 'entityRef="$owner"', 13))));
    assert.match(owner, /\*\*\$owner\*\* = Ego \(string\)/);
    const assignment = hoverText(
      await client.request<Hover>('textDocument/hover', client.at(uri, inside(text, 'parameterRef="MaxSpeed"', 16))),
    );
    assert.match(assignment, /parameter \*\*MaxSpeed\*\* of Vehicle \*\*Sedan\*\* \(catalog Cars\): double, default `50`/);
    assert.match(assignment, /this reference sets it to \*\*30\*\*; declared in `catalogs\/Cars\.xosc` on line 7/);
  });

  it('shows the value of every ${...} as an inlay hint after the attribute', async function () {
    const lines = text.split('\n').length;
    const hints = await client.request<InlayHint[]>('textDocument/inlayHint', {
      textDocument: { uri },
      range: { start: { line: 0, character: 0 }, end: { line: lines, character: 0 } },
    });
    assert.deepEqual(
      hints.map((hint) => `${hint.position.line}:${hint.label}`),
      [`${lineOf(text, '${$speed * 3}')}:= 30`, `${lineOf(text, '${2*$a/$b}')}:= 3`, `${lineOf(text, '${$speed + 0.5}')}:= 20.5`],
    );
    const first = hints[0];
    assert.equal(
      text.split('\n')[first.position.line].slice(first.position.character - 2, first.position.character),
      '}"',
      'placed right after the closing quote',
    );
    const part = await client.request<InlayHint[]>('textDocument/inlayHint', {
      textDocument: { uri },
      range: { start: { line: lineOf(text, '${2*$a/$b}'), character: 0 }, end: { line: lineOf(text, '${2*$a/$b}') + 1, character: 0 } },
    });
    assert.deepEqual(
      part.map((hint) => hint.label),
      ['= 3'],
    );
  });

  it('goes from entryName to the catalog entry, from catalogName to the catalog, from parameterRef to the entry parameter', async function () {
    const cars = fileUri(path.join(root, 'catalogs', 'Cars.xosc'));
    const entry = await client.request<Location[]>('textDocument/definition', client.at(uri, inside(text, 'entryName="Sedan"', 12)));
    assert.deepEqual(
      entry.map((location) => `${location.uri}:${textAt(CARS, location.range)}`),
      [`${cars}:Sedan`],
    );
    const catalog = await client.request<Location[]>('textDocument/definition', client.at(uri, inside(text, 'catalogName="Cars"', 14)));
    assert.deepEqual(
      catalog.map((location) => `${location.uri}:${location.range.start.line}`),
      [`${cars}:${lineOf(CARS, '<Catalog name="Cars">')}`],
    );
    const parameter = await client.request<Location[]>(
      'textDocument/definition',
      client.at(uri, inside(text, 'parameterRef="MaxSpeed"', 15)),
    );
    assert.deepEqual(
      parameter.map((location) => `${location.uri}:${textAt(CARS, location.range)}`),
      [`${cars}:MaxSpeed`],
    );
  });

  it('completes catalog names and the entries of the named catalog', async function () {
    const names = await client.request<CompletionItem[]>('textDocument/completion', client.at(uri, inside(text, 'catalogName="Cars"', 13)));
    assert.deepEqual(
      names.map((item) => item.label),
      ['Cars'],
    );
    const entries = await client.request<CompletionItem[]>(
      'textDocument/completion',
      client.at(uri, inside(text, 'entryName="Sedan"', 11)),
    );
    assert.deepEqual(entries.map((item) => item.label).sort(), ['Sedan', 'Truck']);
    assert.match(entries.find((item) => item.label === 'Sedan')?.detail ?? '', /Vehicle of Cars/);
  });

  it('reports unknown catalogs, entries and assigned parameters at their names', async function () {
    const wrong = text.replace('entryName="Sedan"', 'entryName="Sedna"').replace('parameterRef="MaxSpeed"', 'parameterRef="TopSpeed"');
    const scratch = fileUri(path.join(root, 'wrong-catalog.xosc'));
    await client.open(scratch, wrong);
    const diagnostics = await client.diagnosticsOf(scratch, (list) => list.length > 0);
    assert.deepEqual(
      diagnostics.map((diagnostic) => `${String(problemCodeOf(diagnostic))}:${textAt(wrong, diagnostic.range)}`),
      ['unknown-catalog-entry:Sedna'],
    );
    await client.change(scratch, [{ text: wrong.replace('entryName="Sedna"', 'entryName="Sedan"') }]);
    const assigned = await client.diagnosticsOf(scratch, (list) =>
      list.some((diagnostic) => problemCodeOf(diagnostic) === 'unknown-assigned-parameter'),
    );
    assert.deepEqual(
      assigned.map((diagnostic) => `${String(problemCodeOf(diagnostic))}:${textAt(wrong, diagnostic.range)}`),
      ['unknown-assigned-parameter:TopSpeed'],
    );
    await client.change(scratch, [
      { text: wrong.replace('catalogName="Cars"', 'catalogName="Bikes"').replace('entryName="Sedna"', 'entryName="Sedan"') },
    ]);
    const catalog = await client.diagnosticsOf(scratch, (list) =>
      list.some((diagnostic) => problemCodeOf(diagnostic) === 'unknown-catalog'),
    );
    assert.ok(
      catalog.some((diagnostic) => problemCodeOf(diagnostic) === 'unknown-catalog' && diagnostic.severity === DiagnosticSeverity.Error),
    );
    await client.close(scratch);
  });

  it('highlights $name and ${...} (operators, numbers, parameters) apart from literals', async function () {
    const tokens = decodeTokens(text, await client.request<SemanticTokens>('textDocument/semanticTokens/full', { textDocument: { uri } }));
    const line = lineOf(text, '${2*$a/$b}');
    assert.deepEqual(
      tokens.filter((token) => token.startsWith(`${line}:`)),
      [
        `${line}:\${:operator`,
        `${line}:2:number`,
        `${line}:*:operator`,
        `${line}:$a:parameter`,
        `${line}:/:operator`,
        `${line}:$b:parameter`,
        `${line}:}:operator`,
      ],
    );
    assert.ok(tokens.includes(`${lineOf(text, 'name="speed" parameterType="double" value="30"')}:speed:parameter+declaration`));
    assert.ok(tokens.includes(`${lineOf(text, 'entityRef="$owner"')}:$owner:parameter`));
    // Literals are not tokens.
    assert.ok(!tokens.some((token) => token.includes(':Ego:') || token.includes(':greaterThan:')), tokens.join('\n'));
    const ranged = decodeTokens(
      text,
      await client.request<SemanticTokens>('textDocument/semanticTokens/range', {
        textDocument: { uri },
        range: { start: { line, character: 0 }, end: { line: line + 1, character: 0 } },
      }),
    );
    assert.deepEqual(
      ranged,
      tokens.filter((token) => token.startsWith(`${line}:`)),
    );
  });

  describe('diagnostics and the quick fix', function () {
    it('reports undeclared, unused (faded hint), declared twice and an expression error at their text', async function () {
      const faulty = await client.openFile(path.join(root, 'faulty.xosc'));
      const diagnostics = await client.diagnosticsOf(faulty);
      const shown = diagnostics
        .map((diagnostic) => `${String(problemCodeOf(diagnostic))}:${textAt(FAULTY, diagnostic.range)}:${diagnostic.severity}`)
        .sort();
      assert.deepEqual(shown, [
        `division-by-zero:0:${DiagnosticSeverity.Error}`,
        `duplicate-parameter:used:${DiagnosticSeverity.Warning}`,
        `undeclared-parameter:$stopTime:${DiagnosticSeverity.Error}`,
        `unused-parameter:idle:${DiagnosticSeverity.Hint}`,
      ]);
      const unused = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'unused-parameter') as Diagnostic;
      assert.deepEqual(unused.tags, [DiagnosticTag.Unnecessary]);
    });

    it('offers to declare an undeclared parameter in the nearest ParameterDeclarations', async function () {
      const faulty = fileUri(path.join(root, 'faulty.xosc'));
      const diagnostic = (await client.diagnosticsOf(faulty)).find(
        (candidate) => problemCodeOf(candidate) === 'undeclared-parameter',
      ) as Diagnostic;
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri: faulty },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
      const declare = actions.find((action) => action.title.startsWith("Declare parameter 'stopTime'"));
      assert.ok(declare, actions.map((action) => action.title).join(', '));
      const fixed = applyEdits(FAULTY, declare.edit?.changes?.[faulty] ?? []);
      assert.match(
        fixed,
        /<ParameterDeclaration name="idle" parameterType="double" value="3"\/>\n {4}<ParameterDeclaration name="stopTime" parameterType="string" value=""\/>\n {2}<\/ParameterDeclarations>/,
      );
    });

    it('creates the root ParameterDeclarations after the FileHeader when there is none', async function () {
      const bare = await client.openFile(path.join(root, 'bare.xosc'));
      const diagnostic = (await client.diagnosticsOf(bare)).find(
        (candidate) => problemCodeOf(candidate) === 'undeclared-parameter',
      ) as Diagnostic;
      const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri: bare },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
      const fixed = applyEdits(BARE, actions[0].edit?.changes?.[bare] ?? []);
      assert.match(
        fixed,
        /author="tests"\/>\n {2}<ParameterDeclarations>\n {4}<ParameterDeclaration name="stopTime" parameterType="string" value=""\/>\n {2}<\/ParameterDeclarations>\n {2}<RoadNetwork\/>/,
      );
      await client.change(bare, [{ text: fixed }]);
      const after = await client.diagnosticsOf(
        bare,
        (list) => !list.some((candidate) => problemCodeOf(candidate) === 'undeclared-parameter'),
      );
      assert.ok(after.every((candidate) => problemCodeOf(candidate) !== 'undeclared-parameter'));
    });
  });

  it('works inside a .mosc package (mosc: URIs) and refuses to rename there when packages are read-only', async function () {
    const packageUri = `mosc:${path.join(root, 'bundle.mosc')}/main.xosc`;
    const contents = await client.request<string>('modular2simple/readPackageEntry', { uri: packageUri }).catch(() => undefined);
    if (contents !== undefined) assert.equal(contents, PARAMETERS);
    await client.open(packageUri, PARAMETERS);
    const definition = await client.request<Location[]>(
      'textDocument/definition',
      client.at(packageUri, inside(text, 'value="$speed"', 9, 0)),
    );
    assert.equal(definition[0].uri, packageUri);
    assert.equal(definition[0].range.start.line, lineOf(text, 'name="speed" parameterType="double" value="30"'));
    const entry = await client.request<Location[]>('textDocument/definition', client.at(packageUri, inside(text, 'entryName="Sedan"', 12)));
    assert.match(entry[0].uri, /^mosc:.*bundle\.mosc\/catalogs\/Cars\.xosc$/);
    const hover = hoverText(await client.request<Hover>('textDocument/hover', client.at(packageUri, inside(text, '${2*$a/$b}', 5))));
    assert.match(hover, /= \*\*3\*\*/);
    await assert.rejects(
      client.request('textDocument/rename', { ...client.at(packageUri, inside(text, 'value="$speed"', 9, 0)), newName: 'x' }),
      /cannot write into packages/,
    );
    await client.close(packageUri);
  });
});

describe('editor features across a composition: provenance and the source value of a declaration', function () {
  const fixtures = path.join(repoRoot, 'test', 'fixtures', 'semantics');
  let client: TestClient;

  before(async function () {
    client = await TestClient.start({ root: fixtures });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
  });

  it('hovers an imported group attribute with the value the main file gives it (override, carried)', async function () {
    const mainUri = await client.openFile(path.join(fixtures, 'main.xosc'));
    await client.diagnosticsOf(mainUri);
    const sourcePath = path.join(fixtures, 'speed_up.xosc');
    const sourceText = fs.readFileSync(sourcePath, 'utf8');
    const sourceUri = await client.openFile(sourcePath);
    const carried = hoverText(
      await client.request<Hover>(
        'textDocument/hover',
        client.at(sourceUri, inside(sourceText, 'parameterRef="Speed" value="$TargetSpeed"', 30)),
      ),
    );
    assert.match(carried, /\*\*\$TargetSpeed\*\* = 20 \(double\)/);
    assert.match(carried, /in `main\.xosc` \(group Accelerate\): \*\*20\*\*, carried from `speed_up\.xosc`/);
    const overridden = hoverText(
      await client.request<Hover>('textDocument/hover', client.at(sourceUri, inside(sourceText, 'value="$BrakeTime"', 8))),
    );
    assert.match(overridden, /in `main\.xosc` \(group Accelerate\): \*\*6\*\*, overridden by key `SimulationTimeCondition\.value`/);
    await client.close(sourceUri);
  });

  it('declares a parameter with the value of the source scenario that declares it', async function () {
    const mainPath = path.join(fixtures, 'main.xosc');
    const original = fs.readFileSync(mainPath, 'utf8');
    const edited = original.replace(
      '<SimulationTimeCondition value="12" rule="greaterThan"/>',
      '<SimulationTimeCondition value="$TargetSpeed" rule="greaterThan"/>',
    );
    assert.notEqual(edited, original);
    const mainUri = fileUri(mainPath);
    await client.change(mainUri, [{ text: edited }]);
    const diagnostic = await client.until(
      () =>
        client.diagnostics
          .get(mainUri)
          ?.diagnostics.find(
            (candidate) => problemCodeOf(candidate) === 'undeclared-parameter' && textAt(edited, candidate.range) === '$TargetSpeed',
          ),
      'the undeclared $TargetSpeed',
    );
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri: mainUri },
      range: diagnostic.range,
      context: { diagnostics: [diagnostic] },
    });
    const declare = actions.find((action) => action.title.startsWith("Declare parameter 'TargetSpeed'"));
    assert.ok(declare, actions.map((action) => action.title).join(', '));
    assert.match(declare.title, /value 20 from speed_up\.xosc/);
    const fixed = applyEdits(edited, declare.edit?.changes?.[mainUri] ?? []);
    assert.match(
      fixed,
      /<ParameterDeclaration name="owner" parameterType="string" value="Ego"\/>\n {4}<ParameterDeclaration name="TargetSpeed" parameterType="double" value="20"\/>\n {2}<\/ParameterDeclarations>/,
    );
  });

  it('warns at a ParameterReference key that sets attributes with different defaults, listing them', async function () {
    const root = temporaryWorkspace({});
    fs.cpSync(fixtures, root, { recursive: true });
    const sourcePath = path.join(root, 'speed_up.xosc');
    fs.writeFileSync(
      sourcePath,
      fs
        .readFileSync(sourcePath, 'utf8')
        .replace(
          '<SpeedActionDynamics dynamicsShape="linear" value="2"',
          '<SpeedActionDynamics parameterAttributes="value" dynamicsShape="linear" value="2"',
        ),
    );
    const mainPath = path.join(root, 'main.xosc');
    const mainText = fs
      .readFileSync(mainPath, 'utf8')
      .replace(
        '<ParameterReference key="SimulationTimeCondition.value" value="6"/>',
        '<ParameterReference key="SimulationTimeCondition.value" value="6"/>\n              <ParameterReference key="value" value="3"/>',
      );
    fs.writeFileSync(mainPath, mainText);
    const other = await TestClient.start({ root });
    try {
      await other.indexed();
      const mainUri = await other.openFile(mainPath);
      const diagnostics = await other.diagnosticsOf(mainUri, (list) =>
        list.some((diagnostic) => problemCodeOf(diagnostic) === 'key-mixed-defaults'),
      );
      const mixed = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'key-mixed-defaults') as Diagnostic;
      assert.equal(mixed.severity, DiagnosticSeverity.Warning);
      assert.equal(textAt(mainText, mixed.range), 'value');
      assert.match(String(mixed.message), /sets 2 attributes whose defaults differ: '2' \(1×\), '\$BrakeTime' \(1×\)/);
      assert.deepEqual(
        mixed.relatedInformation?.map((related) => related.location.uri),
        [fileUri(sourcePath), fileUri(sourcePath)],
      );
      // The literal the key reaches shows the value the main file gives it.
      const sourceText = fs.readFileSync(sourcePath, 'utf8');
      const sourceUri = await other.openFile(sourcePath);
      const hover = hoverText(
        await other.request<Hover>('textDocument/hover', other.at(sourceUri, inside(sourceText, 'dynamicsShape="linear" value="2"', 30))),
      );
      assert.match(hover, /in `main\.xosc` \(group Accelerate\): \*\*3\*\*, overridden by key `value`/);
    } finally {
      await other.stop();
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});
