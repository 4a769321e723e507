/** The simulators whose known gaps can be checked; `asam` is the standard alone (no extra checks). */
export const SIMULATORS = ['asam', 'carla', 'esmini'] as const;

export type Simulator = (typeof SIMULATORS)[number];

export function isSimulator(value: unknown): value is Simulator {
  return typeof value === 'string' && (SIMULATORS as readonly string[]).includes(value);
}

/** The ScenarioRunner releases whose facts differ (core/profiles/carla.ts); a fact names the releases it holds for. */
export const CARLA_RELEASES = ['0.9.15', '0.9.16'] as const;

export type CarlaRelease = (typeof CARLA_RELEASES)[number];

/** The release checked when none is chosen: the latest. */
export const DEFAULT_CARLA_RELEASE: CarlaRelease = '0.9.16';

export function isCarlaRelease(value: unknown): value is CarlaRelease {
  return typeof value === 'string' && (CARLA_RELEASES as readonly string[]).includes(value);
}
