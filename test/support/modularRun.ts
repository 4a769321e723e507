import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiXodrDir } from './esminiBinaries';
import { repoRoot } from './paths';

/**
 * A modular scenario on esmini's e6mini road laid out as users lay them out: `xosc/main.xosc` imports
 * its cut-in from `xosc/cut_in_group.xosc`, and both name the road `../xodr/e6mini.xodr` and a scene
 * graph `../models/e6mini.osgb` that a headless run does not need. e6mini names rail-poles, which
 * esmini remarks on. The run is clean: 0 errors, 0 warnings.
 */
export const MODULAR_RUN = {
  main: 'xosc/main.xosc',
  simple: 'xosc/cut_in_group.xosc',
  road: 'xodr/e6mini.xodr',
} as const;

/** Copies the modular-run fixture and esmini's e6mini road into `root` (made when missing); returns `root`. */
export function modularRunWorkspace(root: string): string {
  fs.mkdirSync(path.join(root, 'xosc'), { recursive: true });
  fs.mkdirSync(path.join(root, 'xodr'), { recursive: true });
  for (const file of [MODULAR_RUN.main, MODULAR_RUN.simple])
    fs.copyFileSync(path.join(repoRoot, 'test', 'fixtures', 'modularRun', file), path.join(root, file));
  fs.copyFileSync(path.join(esminiXodrDir, 'e6mini.xodr'), path.join(root, MODULAR_RUN.road));
  return root;
}

/** A different road under e6mini's name in `folder` (esmini's straight 500 m road: no road 0, so e6mini's positions fail on it). */
export function decoyRoad(folder: string): string {
  fs.mkdirSync(folder, { recursive: true });
  const decoy = path.join(folder, 'e6mini.xodr');
  fs.copyFileSync(path.join(esminiXodrDir, 'straight_500m.xodr'), decoy);
  return decoy;
}
