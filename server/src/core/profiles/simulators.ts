import type { CarlaRelease } from './scenarioRunner';

/** The simulators whose known gaps can be checked; `asam` is the standard alone (no extra checks). */
export const SIMULATORS = ['asam', 'carla', 'esmini'] as const;

export type Simulator = (typeof SIMULATORS)[number];

export function isSimulator(value: unknown): value is Simulator {
  return typeof value === 'string' && (SIMULATORS as readonly string[]).includes(value);
}

export { CARLA_RELEASES, isCarlaRelease } from './scenarioRunner';
export type { CarlaRelease } from './scenarioRunner';

/** The ScenarioRunner release checked when none is chosen: the latest. */
export const DEFAULT_CARLA_RELEASE = '0.9.16' satisfies CarlaRelease;
