import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { DiagnosticSeverity } from 'vscode-languageserver/node';
import { fileUri, TestClient } from './harness';
import { problemCodeOf } from '../support/diagnostics';
import { temporaryWorkspace } from '../support/workspace';

const SCENARIO = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-01-01T00:00:00" description="simulator" author="test"/>
  <Entities/>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="s"><Act name="a"><ManeuverGroup name="g" maximumExecutionCount="1">
      <Actors selectTriggeringEntities="false"/>
      <Maneuver name="m"><Event name="e" priority="overwrite"><Action name="x">
        <PrivateAction><VisibilityAction graphics="false" traffic="true" sensors="true"/></PrivateAction>
      </Action></Event></Maneuver>
    </ManeuverGroup></Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;

describe('simulator profile in the language server', function () {
  let client: TestClient;
  let uri: string;

  before(async () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO });
    client = await TestClient.start({ root, settings: { simulator: 'carla' } });
    uri = await client.open(fileUri(path.join(root, 'scenario.xosc')), SCENARIO);
  });

  after(async () => {
    await client.stop();
  });

  it('publishes what CARLA refuses as errors and what it runs otherwise as warnings, at their source positions', async () => {
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.some((diagnostic) => problemCodeOf(diagnostic) === 'simulator'));
    const simulator = diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'simulator');
    const version = simulator.find((diagnostic) =>
      /accepts only OpenSCENARIO 1\.0; this file states 1\.1/.test(String(diagnostic.message)),
    );
    assert.ok(version);
    assert.equal(version.severity, DiagnosticSeverity.Error);
    const road = simulator.find((diagnostic) => /names no LogicFile/.test(String(diagnostic.message)));
    assert.equal(road?.severity, DiagnosticSeverity.Error);
    assert.equal(version.range.start.line, 2);
    assert.equal(SCENARIO.split('\n')[2].slice(version.range.start.character, version.range.end.character), '1');
    const action = simulator.find((diagnostic) => /does not support VisibilityAction/.test(String(diagnostic.message)));
    assert.equal(action?.range.start.line, 9);
    assert.equal(action?.severity, DiagnosticSeverity.Error);
  });

  it('drops them when the setting goes back to asam', async () => {
    await client.settingsChanged({ simulator: 'asam' });
    const diagnostics = await client.diagnosticsOf(uri, (list) => !list.some((diagnostic) => problemCodeOf(diagnostic) === 'simulator'));
    assert.deepEqual(
      diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'simulator'),
      [],
    );
  });
});
