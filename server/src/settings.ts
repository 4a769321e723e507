import { isSchemaVersion } from './core/schema/model';
import { SchemaVersionSetting } from './core/schema/version';
import { splitScenarioPath } from './core/sources';
import { DEFAULT_FORMAT_OPTIONS } from './core/format';
import { CarlaRelease, DEFAULT_CARLA_RELEASE, isCarlaRelease, isSimulator, Simulator } from './core/profiles/simulators';

export interface ServerSettings {
  /** Directories searched after SCENARIO_PATH. */
  scenarioPath: string[];
  /** The user's scenario libraries (`modular2simple.library.folders`), searched for `library:NAME` before the built-in one. */
  libraryFolders: string[];
  /** Delay between the last edit and new diagnostics, in milliseconds. */
  diagnosticsDelay: number;
  /** Files larger than this are indexed by name only, never parsed for workspace symbols. */
  maxIndexedFileBytes: number;
  /** The simulator whose known gaps are reported as warnings (`asam`: none). */
  simulator: Simulator;
  /** With `simulator` = `carla`: the ScenarioRunner release whose facts apply (`modular2simple.carla.release`). */
  carlaRelease: CarlaRelease;
  /** Past this width a formatted start tag puts each attribute on its own line. */
  formatMaxLineWidth: number;
  /** The OpenSCENARIO schema files are checked against (`modular2simple.schema.version`). */
  schemaVersion: SchemaVersionSetting | 'off';
  /** Folders where a scenario's road file is looked for (`modular2simple.esmini.roadPath`, relative to the first workspace folder): Run in esmini's, and the export's. */
  roadPath: string[];
}

export const DEFAULT_SETTINGS: ServerSettings = {
  scenarioPath: [],
  libraryFolders: [],
  diagnosticsDelay: 5,
  maxIndexedFileBytes: 8 * 1024 * 1024,
  simulator: 'asam',
  carlaRelease: DEFAULT_CARLA_RELEASE,
  formatMaxLineWidth: DEFAULT_FORMAT_OPTIONS.maxLineWidth,
  schemaVersion: 'auto',
  roadPath: [],
};

/** Reads settings sent by a client, keeping defaults for anything missing or of the wrong type. */
export function readSettings(value: unknown): ServerSettings {
  const record = (value && typeof value === 'object' ? value : {}) as Record<string, unknown>;
  const scenarioPath = Array.isArray(record.scenarioPath)
    ? record.scenarioPath.filter((entry): entry is string => typeof entry === 'string' && entry.trim().length > 0)
    : typeof record.scenarioPath === 'string'
      ? splitScenarioPath(record.scenarioPath)
      : [];
  const diagnostics = (record.diagnostics && typeof record.diagnostics === 'object' ? record.diagnostics : {}) as Record<string, unknown>;
  const delay = typeof diagnostics.delay === 'number' && diagnostics.delay >= 0 ? diagnostics.delay : DEFAULT_SETTINGS.diagnosticsDelay;
  const format = (record.format && typeof record.format === 'object' ? record.format : {}) as Record<string, unknown>;
  const width =
    typeof format.maxLineWidth === 'number' && format.maxLineWidth >= 1
      ? Math.floor(format.maxLineWidth)
      : DEFAULT_SETTINGS.formatMaxLineWidth;
  const simulator = isSimulator(record.simulator) ? record.simulator : DEFAULT_SETTINGS.simulator;
  const carla = (record.carla && typeof record.carla === 'object' ? record.carla : {}) as Record<string, unknown>;
  const carlaRelease = typeof carla.release === 'string' && isCarlaRelease(carla.release) ? carla.release : DEFAULT_SETTINGS.carlaRelease;
  const schema = (record.schema && typeof record.schema === 'object' ? record.schema : {}) as Record<string, unknown>;
  const schemaVersion =
    schema.version === 'off' || schema.version === 'auto' || isSchemaVersion(schema.version)
      ? schema.version
      : DEFAULT_SETTINGS.schemaVersion;
  const library = (record.library && typeof record.library === 'object' ? record.library : {}) as Record<string, unknown>;
  const libraryFolders = Array.isArray(library.folders)
    ? library.folders.filter((entry): entry is string => typeof entry === 'string' && entry.trim().length > 0)
    : [];
  const esmini = (record.esmini && typeof record.esmini === 'object' ? record.esmini : {}) as Record<string, unknown>;
  const roadPath = Array.isArray(esmini.roadPath)
    ? esmini.roadPath.filter((entry): entry is string => typeof entry === 'string' && entry.trim().length > 0)
    : [];
  return {
    scenarioPath,
    libraryFolders,
    diagnosticsDelay: delay,
    maxIndexedFileBytes: DEFAULT_SETTINGS.maxIndexedFileBytes,
    simulator,
    carlaRelease,
    formatMaxLineWidth: width,
    schemaVersion,
    roadPath,
  };
}
