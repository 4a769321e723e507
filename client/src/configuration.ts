import * as path from 'node:path';

/**
 * The settings the client hands to the server for one workspace folder: relative `scenarioPath`
 * entries resolved against that folder (the setting is resource-scoped, so a second folder's
 * relative entries name folders of its own, not of the first folder).
 */
export function resolveScenarioPaths(settings: unknown, folder: string | undefined): unknown {
  if (!folder || typeof settings !== 'object' || settings === null || Array.isArray(settings)) return settings;
  const scenarioPath = (settings as { scenarioPath?: unknown }).scenarioPath;
  if (!Array.isArray(scenarioPath)) return settings;
  const resolved = scenarioPath.map((entry: unknown) =>
    typeof entry === 'string' && entry.trim() ? path.resolve(folder, entry.trim()) : entry,
  );
  return { ...(settings as Record<string, unknown>), scenarioPath: resolved };
}
