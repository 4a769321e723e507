import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot } from './paths';

/** The examples' lane_change.xosc imported by two groups of one main file, for two adversaries. */
export function writeTwoCutIns(folder: string): void {
  const examples = path.join(repoRoot, 'examples');
  fs.copyFileSync(path.join(examples, 'lane_change.xosc'), path.join(folder, 'lane_change.xosc'));
  const main = fs.readFileSync(path.join(examples, 'main.xosc'), 'utf8');
  const first = main.indexOf('        <ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">');
  const second = main.indexOf('        <ManeuverGroup maximumExecutionCount="1" name="LeadVehicle">');
  const startTrigger = main.indexOf('        <StartTrigger>', second);
  const cutInGroup = main.slice(first, second);
  const leadGroup = cutInGroup
    .replace('name="CutInVehicle"', 'name="CutInLead"')
    .replaceAll('"adversary"', '"lead"')
    .replace('key="RelativeDistanceCondition.value" value="12"', 'key="RelativeDistanceCondition.value" value="30"');
  fs.writeFileSync(path.join(folder, 'main.xosc'), main.slice(0, second) + leadGroup + main.slice(startTrigger));
}
