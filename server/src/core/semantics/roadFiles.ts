/**
 * Where a scenario's road file (`RoadNetwork/LogicFile`) is: one answer for every reader, so that
 * the bird's-eye view draws the file that Run in esmini loads.
 */
import * as path from 'node:path';
import { FileSystemHost, SourceRef } from '../sources';
import { XmlDocument, XmlElement } from '../xml';
// The model module, not the semantics index: the index runs the checks, whose road rules read road files through this one.
import { Evaluator, semanticModelOf } from './model';

export interface LogicFile {
  /** As the scenario says, `$parameters` and `${...}` evaluated. */
  filepath: string;
  element: XmlElement;
}

export interface RoadFileResolution {
  /** As the scenario says. */
  filepath: string;
  /** The first candidate that is a file, absolute; undefined when none is. */
  resolved?: string;
  /** Every path looked at, in order. */
  candidates: string[];
}

/** The document's `RoadNetwork/LogicFile` and its filepath as evaluated; undefined when it names none. */
export function logicFileOf(document: XmlDocument, evaluator?: Evaluator): LogicFile | undefined {
  const network = document.root?.children.find((child) => child.name === 'RoadNetwork');
  const element = network?.children.find((child) => child.name === 'LogicFile');
  const written = element?.attributes.find((attribute) => attribute.name === 'filepath');
  if (!element || !written) return undefined;
  const filepath = (evaluator ?? new Evaluator(semanticModelOf(document))).textOf(element, written) ?? written.value;
  return filepath.trim() ? { filepath, element } : undefined;
}

/** The folder a scenario's relative file names start from: the file's folder, or for a file inside a package the package's. */
export function scenarioFolderOf(ref: SourceRef): string {
  return path.dirname(ref.disk);
}

/** Road folders (a setting, a request's field) as absolute paths: a relative one starts at `base` (the workspace folder, or the working directory). */
export function roadFolders(roadPath: readonly unknown[] | undefined, base: string): string[] {
  return (roadPath ?? [])
    .filter((folder): folder is string => typeof folder === 'string' && folder.trim() !== '')
    .map((folder) => path.resolve(base, folder));
}

/**
 * The paths a LogicFile's filepath is looked for at, in order: beside the scenario (the path as
 * written, relative to the scenario's folder, then its file name there), then the same in each road
 * folder. The order per folder is esmini's (its `LocateFile`: the path, then the file name).
 */
export function roadFileCandidates(filepath: string, scenarioFolder: string, roadFolderList: readonly string[]): string[] {
  const name = path.basename(filepath.replace(/\\/g, '/'));
  const candidates: string[] = [];
  for (const folder of [scenarioFolder, ...roadFolderList.map((entry) => path.resolve(scenarioFolder, entry))]) {
    candidates.push(path.resolve(folder, filepath), path.resolve(folder, name));
  }
  return [...new Set(candidates)];
}

/** The road file a scenario in `scenarioFolder` uses: the first candidate that is a regular file. */
export async function resolveRoadFile(
  host: FileSystemHost,
  filepath: string,
  scenarioFolder: string,
  roadFolderList: readonly string[],
): Promise<RoadFileResolution> {
  const candidates = roadFileCandidates(filepath, scenarioFolder, roadFolderList);
  for (const candidate of candidates) if ((await host.kind(candidate)) === 'file') return { filepath, resolved: candidate, candidates };
  return { filepath, candidates };
}
