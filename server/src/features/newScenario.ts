import * as path from 'node:path';
import { NewScenarioParams, NewScenarioResult } from '../../../common/src/protocol';
import { egoPlacement, newMainScenario } from '../core/newScenario';
import { parseOpenDrive } from '../core/opendrive/road';
import { nodeFileSystem } from '../core/sources';
import { decodeUtf8 } from '../core/text';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { invalidParams } from './commands';

/** Road networks larger than this are refused rather than read (as the bird's-eye view does). */
const MAX_ROAD_FILE_BYTES = 64 * 1024 * 1024;

function diskPath(value: unknown, what: string): string {
  if (typeof value !== 'string' || value.trim() === '') throw invalidParams(`${what}: a file: URI or a path is required`);
  const resolved = filePathOf(value) ?? (value.includes('://') ? undefined : value);
  if (!resolved || !path.isAbsolute(resolved)) throw invalidParams(`${what}: ${value} is no absolute file path or file: URI`);
  return resolved;
}

/** The new main's text: the road network read with the project's OpenDRIVE reader, the ego on its first driving lane, the road named relative to the new file. */
export async function newScenario(workspace: Workspace, params: NewScenarioParams): Promise<NewScenarioResult> {
  const scenario = diskPath(params?.scenario, 'scenario');
  if (!scenario.toLowerCase().endsWith('.xosc')) throw invalidParams(`scenario: ${scenario} does not end in .xosc`);
  const road = diskPath(params.roadNetwork, 'roadNetwork');
  // Bounded, and refused when not a regular file (a FIFO, a device), as every read is.
  const bytes = await nodeFileSystem.readFile(road, MAX_ROAD_FILE_BYTES).catch((error: Error) => {
    throw invalidParams(`the road network could not be read: ${error.message}`);
  });
  if (!bytes) throw invalidParams(`the road network ${road} does not exist`);
  const network = parseOpenDrive(decodeUtf8(bytes));
  const ego = egoPlacement(network);
  if (!ego) {
    const why = network.problems.length > 0 ? network.problems[0].message : `none of its ${network.roads.length} roads has a driving lane`;
    throw invalidParams(`no place for the ego in ${road}: ${why}`);
  }
  const roadFile = path.relative(path.dirname(scenario), road).split(path.sep).join('/');
  const setting = workspace.settings.schemaVersion;
  const text = newMainScenario({ version: setting === 'auto' || setting === 'off' ? '1.3' : setting, roadFile, ego });
  return { text, roadFile, ego };
}
