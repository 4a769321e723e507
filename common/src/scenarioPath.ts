import * as path from 'node:path';
import { pathsFor } from './paths';

/** Splits SCENARIO_PATH on `;` and on the platform's delimiter (the original split on `;` only). */
export function splitScenarioPath(value: string | undefined): string[] {
  if (!value) return [];
  return value
    .split(new RegExp(`[;${path.delimiter === ';' ? '' : path.delimiter}]`))
    .map((entry) => entry.trim())
    .filter((entry) => entry.length > 0)
    .map((entry) => pathsFor(entry).resolve(entry));
}
