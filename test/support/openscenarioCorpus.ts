import * as fs from 'node:fs';
import * as path from 'node:path';
import { ProblemCode } from '../../server/src/core/problems';
import { sharedDir } from './paths';

/** The real OpenSCENARIO files (they run in esmini or CARLA), shared by the core and the server tests. */
export const openscenarioDir = path.join(sharedDir, 'corpus', 'openscenario');

/** The codes of the semantic checks (parameters, expressions, catalogs, names). */
export const SEMANTIC_CODES = new Set<ProblemCode>([
  'undeclared-parameter',
  'duplicate-parameter',
  'expression-syntax',
  'type-mismatch',
  'division-by-zero',
  'nonstandard-expression',
  'lenient-value',
  'simulator-value',
  'overflow',
  'catalog-directory',
  'unknown-catalog',
  'unknown-catalog-entry',
  'unknown-assigned-parameter',
  'unknown-storyboard-element',
  'undeclared-variable',
  'undeclared-entity',
  'undeclared-catalog-parameter',
  'duplicate-name',
  'duplicate-catalog-entry',
  'value-constraint',
  'unknown-traffic-signal',
  'unknown-traffic-signal-controller',
  'no-actor',
  'negative-transition-time',
  'non-positive-phase-duration',
  'out-of-range',
]);

/**
 * Files of the corpus that are genuinely wrong by the standard (each runs in esmini, which is
 * lenient), with the problems the checks rightly report. Nothing else may be reported.
 */
export const GENUINELY_WRONG: Record<string, { problems: string[]; reason: string }> = {
  'esmini/Catalogs/Controllers/ControllerCatalog.xosc': {
    problems: ['95:type-mismatch'],
    reason: 'FollowMode is declared parameterType="double" with value \'time\' (esmini reads it as text)',
  },
  'esmini/Catalogs/Vehicles/VehicleCatalog.xosc': {
    problems: ['66:duplicate-parameter'],
    reason: 'one Vehicle declares RefPointXOffset twice',
  },
  'esmini/follow_reference.xosc': {
    problems: ['9:duplicate-parameter'],
    reason: 'the root declares lane_change_duration twice',
  },
  'esmini/car_walk.xosc': {
    // Its catalog directory, missing, once at its line (the SCENARIO_PATH folder standing in for it holds no such catalog).
    problems: ['6:catalog-directory'],
    reason:
      "its catalog 'openx_assets_3d.catalog' in /tmp/openx-assets/catalogs is not shipped with esmini's samples (its road is an absolute Windows path too)",
  },
  'esmini/cut-in_environment.xosc': {
    problems: ['222:unknown-catalog'],
    reason: "EnvironmentCatalog.xosc names its Catalog 'VehicleCatalog' (esmini finds catalogs by file name)",
  },
  'esmini/light_state.xosc': {
    problems: ['25:unknown-catalog', '28:unknown-catalog'],
    reason: "MiscObjectCatalog.xosc names its Catalog 'MiscObject' (esmini finds catalogs by file name)",
  },
  'esmini/Catalogs/Environments/EnvironmentCatalog.xosc': {
    problems: ['41:out-of-range', '51:out-of-range'],
    reason: 'two Weathers give atmosphericPressure="10000" (Pa), outside the standard\'s range [80000..120000] (100000 was meant)',
  },
  'esmini/parking_demo.xosc': {
    problems: ['643:nonstandard-expression'],
    reason: '${pi} uses a constant only esmini defines',
  },
  'scenario_runner/VehicleLateralDistance.xosc': {
    problems: ['163:out-of-range'],
    reason:
      "LateralDistanceAction distance='-2.0': the distance is [0..inf[ (the ASAM model's documented range); a 1.0 file has no displacement to name the side. A warning: esmini keeps the sign (to the right of hero)",
  },
};

/**
 * Files of the corpus that use a form the standard does not allow but esmini reads with one clear
 * meaning: a warning with a fix to the standard form by SPEC 12, never an error.
 */
export const ESMINI_FORMS: Record<string, { problems: string[]; reason: string }> = {
  'esmini/cut-in.xosc': {
    problems: ['162:lenient-value'],
    reason:
      '${BrakeCondition_HWT + _ + $HeadwayTime_Brake} glues words as text (esmini gives BrakeCondition_HWT_0.7); the standard has no text in expressions',
  },
  'esmini/cut-in_environment.xosc': {
    problems: ['316:lenient-value'],
    reason: 'the same text-gluing expression as cut-in.xosc',
  },
  'esmini/traffic_lights.xosc': {
    problems: ['285:lenient-value'],
    reason: 'the string parameter RedLightDistance ("50") is used in arithmetic; esmini reads it as the number 50',
  },
};

/**
 * Files of the corpus that break a rule of the standard (an error in its reading, as ASAM's Quality
 * Checker reports it) where esmini runs them with one meaning: a warning with simulator esmini (SPEC 12).
 * A value out of its range that esmini reads with one clear meaning is a warning in every reading.
 */
export const ESMINI_ACCEPTS: Record<string, { problems: string[]; reason: string }> = {
  'esmini/Catalogs/Maneuvers/HWManeuvers.xosc': {
    problems: ['84:undeclared-catalog-parameter'],
    reason:
      'a maneuver uses $AccRate without declaring it (ASAM QC parameters.valid_parameter_declaration_in_catalogs); esmini takes it from the referencing scenario',
  },
  'esmini/acc-test.xosc': {
    problems: ['262:duplicate-name', '168:out-of-range', '214:out-of-range'],
    reason:
      "one Maneuver holds two Events named EgoSpeedEvent (ASAM QC reference_control.unique_element_names_on_same_level); esmini runs both. And a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/alks-test.xosc': {
    problems: ['167:out-of-range', '213:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in.xosc': {
    problems: ['152:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_environment.xosc': {
    problems: ['306:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_external.xosc': {
    problems: ['154:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_interactive.xosc': {
    problems: ['168:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_simple.xosc': {
    problems: ['127:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_sloppy.xosc': {
    problems: ['171:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_visibility.xosc': {
    problems: ['155:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/pedestrian.xosc': {
    problems: ['206:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/routing-test.xosc': {
    problems: ['108:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/slow-lead-vehicle.xosc': {
    problems: ['87:out-of-range'],
    reason:
      "a SpeedActionDynamics rate below zero, outside TransitionDynamics value [0..inf[ (the ASAM model's documented range); esmini takes its magnitude",
  },
  'esmini/cut-in_sumo.xosc': {
    problems: ['28:out-of-range', '29:out-of-range'],
    reason: "maxSteering='30' (degrees, it seems), outside Axle maxSteering [0..PI] rad; esmini reads it and uses it nowhere",
  },
  'esmini/straight_500m.xosc': {
    problems: ['29:out-of-range', '34:out-of-range'],
    reason: "maxSteering='30' (degrees, it seems), outside Axle maxSteering [0..PI] rad; esmini reads it and uses it nowhere",
  },
  'esmini/straight_500m_pedestrian.xosc': {
    problems: ['29:out-of-range', '34:out-of-range', '58:out-of-range', '63:out-of-range'],
    reason: "maxSteering='30' (degrees, it seems), outside Axle maxSteering [0..PI] rad; esmini reads it and uses it nowhere",
  },
  'esmini/trajectory-test.xosc': {
    problems: ['30:out-of-range', '31:out-of-range', '48:out-of-range', '49:out-of-range'],
    reason: "maxSteering='30' (degrees, it seems), outside Axle maxSteering [0..PI] rad; esmini reads it and uses it nowhere",
  },
  'esmini/parking_demo.xosc': {
    problems: ['393:out-of-range', '813:out-of-range'],
    reason:
      "Clothoid curvatureDot below zero, outside [0..inf[ (the ASAM model's documented range); esmini reads it as curvaturePrime, which has no bound",
  },
};

/** What the semantic checks report on the corpus: the genuinely wrong files' problems, what esmini accepts, and the esmini forms' warnings, by file. */
export function expectedCorpusFindings(): Record<string, string[]> {
  const expected: Record<string, string[]> = {};
  for (const list of [GENUINELY_WRONG, ESMINI_ACCEPTS, ESMINI_FORMS])
    for (const [file, entry] of Object.entries(list)) (expected[file] ??= []).push(...entry.problems);
  return expected;
}

/** Every `.xosc` of the corpus, sorted. */
export function corpusFiles(): string[] {
  const found: string[] = [];
  const walk = (directory: string) => {
    for (const entry of fs.readdirSync(directory, { withFileTypes: true })) {
      const full = path.join(directory, entry.name);
      if (entry.isDirectory()) walk(full);
      else if (entry.name.endsWith('.xosc')) found.push(full);
    }
  };
  walk(openscenarioDir);
  return found.sort();
}
