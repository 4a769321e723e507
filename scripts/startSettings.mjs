// The user settings `npm start` writes for code-server, kept apart from start.mjs so that a test can check them.
import * as fs from 'node:fs';
import * as path from 'node:path';

/**
 * What npm start sets unless the user has set it in that profile. `files.autoSave` is off because VS Code
 * in the browser saves after every pause by default, which would write each half-typed edit into the
 * repository's examples/: the bundled examples change only when the user saves.
 */
export const START_DEFAULTS = {
  'workbench.startupEditor': 'none',
  'telemetry.telemetryLevel': 'off',
  'git.openRepositoryInParentFolders': 'never',
  'files.autoSave': 'off',
};

/** Writes the profile's settings.json: the defaults, then what the user set there, then the esmini paths found now. */
export function writeStartSettings(settingsFile, esminiSettings) {
  let current = {};
  try {
    current = JSON.parse(fs.readFileSync(settingsFile, 'utf8'));
  } catch {
    // none yet, or not plain JSON: written anew
  }
  const settings = { ...START_DEFAULTS, ...current, ...esminiSettings };
  fs.mkdirSync(path.dirname(settingsFile), { recursive: true });
  fs.writeFileSync(settingsFile, JSON.stringify(settings, null, 2));
  return settings;
}
