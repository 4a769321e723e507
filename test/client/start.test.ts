import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { writeStartSettings } from '../../scripts/startSettings.mjs';
import { repoRoot } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

describe('npm start: the settings of the VS Code it opens', () => {
  it('turns auto-save off, so that the bundled examples change only when the user saves', () => {
    const settingsFile = path.join(temporaryWorkspace(), 'user-data', 'User', 'settings.json');
    writeStartSettings(settingsFile, { 'modular2simple.esmini.path': '/esmini/bin/esmini' });
    const written = JSON.parse(fs.readFileSync(settingsFile, 'utf8')) as Record<string, unknown>;
    assert.equal(written['files.autoSave'], 'off');
    assert.equal(written['modular2simple.esmini.path'], '/esmini/bin/esmini');
    assert.equal(written['workbench.startupEditor'], 'none');
  });

  it('turns it off in a profile written before, and keeps what the user set there since', () => {
    const settingsFile = path.join(temporaryWorkspace(), 'settings.json');
    fs.writeFileSync(settingsFile, JSON.stringify({ 'editor.fontSize': 15, 'telemetry.telemetryLevel': 'off' }));
    assert.equal(writeStartSettings(settingsFile, {})['files.autoSave'], 'off');
    fs.writeFileSync(settingsFile, JSON.stringify({ 'files.autoSave': 'onFocusChange' }));
    assert.equal(writeStartSettings(settingsFile, {})['files.autoSave'], 'onFocusChange');
    const written = JSON.parse(fs.readFileSync(settingsFile, 'utf8')) as Record<string, unknown>;
    assert.equal(written['files.autoSave'], 'onFocusChange');
  });

  it('is what start.mjs writes', () => {
    const script = fs.readFileSync(path.join(repoRoot, 'scripts', 'start.mjs'), 'utf8');
    assert.match(script, /import \{ writeStartSettings \} from '\.\/startSettings\.mjs'/);
    assert.match(script, /writeStartSettings\(path\.join\(userData, 'User', 'settings\.json'\), esminiSettings\)/);
    assert.doesNotMatch(script, /autoSave/);
  });
});
