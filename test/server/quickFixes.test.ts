import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CodeAction, Diagnostic } from 'vscode-languageserver/node';
import { mainWithKeys, SIMPLE } from './fixtures/scenarios';
import { fileUri, useServer } from './harness';
import { problemCodeOf } from '../support/diagnostics';

describe('language server: quick fixes (JSON-RPC)', function () {
  const simpleText = SIMPLE;
  const server = useServer(
    {
      'simple.xosc': simpleText,
      'dotted.xosc': simpleText.replace(
        'parameterAttributes="value" value="5"',
        'parameterAttributes="AbsoluteTargetSpeed.value" value="5"',
      ),
      'keys.xosc': mainWithKeys([
        '<ParameterReference key="SimulationTimeCondition.valeu" value="1"/>',
        '<ParameterReference key="TimeHeadwayCondition.value" value="1"/>',
      ]),
      'usesite.xosc': mainWithKeys(['<ParameterReference key="AbsoluteTargetSpeed.value" value="7"/>']).replace(
        'scenarioFileName="simple.xosc"',
        'scenarioFileName="dotted.xosc"',
      ),
      'group.xosc': mainWithKeys([]).replace('maneuverGroupName="Brake"', 'maneuverGroupName="Nothing"'),
      'typo.xosc': mainWithKeys([]).replace('scenarioFileName="simple.xosc"', 'scenarioFileName="simpel.xosc"'),
    },
    'keys.xosc',
  );

  async function fixes(name: string, code: string): Promise<{ diagnostic: Diagnostic; actions: CodeAction[] }[]> {
    const uri = await server.client.openFile(path.join(server.root, name));
    const diagnostics = (await server.client.diagnosticsOf(uri)).filter((diagnostic) => problemCodeOf(diagnostic) === code);
    const result = [];
    for (const diagnostic of diagnostics) {
      const actions = await server.client.request<CodeAction[]>('textDocument/codeAction', {
        textDocument: { uri },
        range: diagnostic.range,
        context: { diagnostics: [diagnostic] },
      });
      result.push({ diagnostic, actions: actions.filter((action) => action.diagnostics) });
    }
    return result;
  }

  it('replaces a mistyped key by the key of the same element and attribute, and offers nothing for a key of another element', async function () {
    const [typo, other] = await fixes('keys.xosc', 'unknown-key');
    assert.deepEqual(
      typo.actions.map((action) => action.title),
      ["Change key to 'SimulationTimeCondition.value'"],
    );
    assert.deepEqual(
      other.actions.map((action) => action.title),
      [],
      'TimeHeadwayCondition.value means something else',
    );
  });

  it('fixes at the use site a mistake that lives in the simple scenario', async function () {
    const [{ actions }] = await fixes('usesite.xosc', 'unknown-key');
    assert.deepEqual(
      actions.map((action) => action.title),
      ["List 'value' in dotted.xosc instead"],
    );
    const [edit] = actions[0].edit?.changes?.[fileUri(path.join(server.root, 'dotted.xosc'))] ?? [];
    assert.equal(edit?.newText, 'value');
    const dotted = fs.readFileSync(path.join(server.root, 'dotted.xosc'), 'utf8');
    assert.equal(
      dotted.split('\n')[edit.range.start.line].slice(edit.range.start.character, edit.range.end.character),
      'AbsoluteTargetSpeed.value',
    );
  });

  it('names the absolute folders a misspelt scenarioFileName was looked up in, and the closest file there, with a quick fix', async function () {
    const [{ diagnostic, actions }] = await fixes('typo.xosc', 'missing-file');
    const message = typeof diagnostic.message === 'string' ? diagnostic.message : diagnostic.message.value;
    assert.ok(message.includes(`searched ${server.root}`), message);
    assert.doesNotMatch(message, /searched \.(,|$)/m);
    assert.match(message, /did you mean 'simple\.xosc'\?/);
    assert.deepEqual(
      actions.map((action) => action.title),
      ["Change to 'simple.xosc'"],
    );
    assert.equal(actions[0].isPreferred, true);
    const [edit] = actions[0].edit?.changes?.[fileUri(path.join(server.root, 'typo.xosc'))] ?? [];
    assert.equal(edit?.newText, 'simple.xosc');
  });

  it('offers the groups that exist for an unknown group', async function () {
    const [{ actions }] = await fixes('group.xosc', 'unknown-group');
    assert.deepEqual(
      actions.map((action) => action.title),
      ["Change to 'Brake'", "Change to 'Wait'"],
    );
  });
});
